#include "kiri/geometry/layers/layer_export.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>
#include <stb_image_write.h>

#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/medium/medium.hpp"

namespace kiri::geometry {
namespace {

using json = nlohmann::json;

constexpr int gl_float = 5126, gl_unsigned_int = 5125, gl_unsigned_short = 5123;
constexpr int array_buffer = 34962, element_array_buffer = 34963;

// The binary chunk and the JSON that describes it, grown view by view.
struct GlbBuilder {
    std::vector<std::uint8_t> bin;
    json views = json::array(), accessors = json::array();

    int view(const void* data, std::size_t bytes, int target)
    {
        while (bin.size() % 4)
            bin.push_back(0);
        json v = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes}};
        if (target)
            v["target"] = target;
        const auto* p = static_cast<const std::uint8_t*>(data);
        bin.insert(bin.end(), p, p + bytes);
        views.push_back(v);
        return int(views.size()) - 1;
    }
    int accessor(const std::vector<float>& data, int components, const char* type, bool bounds)
    {
        json a = {{"bufferView", view(data.data(), data.size() * sizeof(float), array_buffer)},
                  {"componentType", gl_float},
                  {"count", data.size() / std::size_t(components)},
                  {"type", type}};
        if (bounds) {
            std::vector<float> lo(std::size_t(components), INFINITY), hi(std::size_t(components), -INFINITY);
            for (std::size_t i = 0; i < data.size(); ++i) {
                lo[i % components] = std::min(lo[i % components], data[i]);
                hi[i % components] = std::max(hi[i % components], data[i]);
            }
            a["min"] = lo;
            a["max"] = hi;
        }
        accessors.push_back(a);
        return int(accessors.size()) - 1;
    }
    //! Unsigned 16-bit values read as [0, 1] (normalized), e.g. a colour.
    int normalized(const std::vector<std::uint16_t>& data, int components, const char* type)
    {
        accessors.push_back({{"bufferView", view(data.data(), data.size() * 2, array_buffer)},
                             {"componentType", gl_unsigned_short},
                             {"normalized", true},
                             {"count", data.size() / std::size_t(components)},
                             {"type", type}});
        return int(accessors.size()) - 1;
    }
    int indices(const std::vector<std::uint32_t>& data)
    {
        accessors.push_back({{"bufferView", view(data.data(), data.size() * 4, element_array_buffer)},
                             {"componentType", gl_unsigned_int},
                             {"count", data.size()},
                             {"type", "SCALAR"}});
        return int(accessors.size()) - 1;
    }
};

std::vector<std::uint8_t> png_bytes(const LayerTexture& t)
{
    std::vector<std::uint8_t> out;
    // glTF's texture origin is the top-left: the atlas rows (v = 0 first) are flipped.
    stbi_flip_vertically_on_write(1);
    const int ok = stbi_write_png_to_func(
        [](void* context, void* data, int size) {
            auto* v = static_cast<std::vector<std::uint8_t>*>(context);
            v->insert(v->end(), static_cast<std::uint8_t*>(data), static_cast<std::uint8_t*>(data) + size);
        },
        &out, t.width, t.height, 4, t.rgba.data(), t.width * 4);
    stbi_flip_vertically_on_write(0);
    if (!ok)
        throw IoError({}, "texture", "PNG encoding failed");
    return out;
}

std::ofstream open_out(const std::filesystem::path& path)
{
    std::ofstream out(path, std::ios::binary);
    if (!out)
        throw IoError(path.string(), "", "cannot open for writing");
    return out;
}

void close_out(std::ofstream& out, const std::filesystem::path& path)
{
    out.close();
    if (!out)
        throw IoError(path.string(), "", "write failed (disk full?)");
}

}  // namespace

double exported_alpha(const LayerVertex& v, const LayerOptions& options)
{
    if (options.shading == LayerShading::medium) {  // the slab seen from above: sigma_t density r share
        const double r = options.count > 0 ? v.exponent * options.thickness / options.count : options.thickness;
        return 1.0 - std::exp(-options.optics.extinction * v.alpha * r * v.slab);
    }
    return 1.0 - std::pow(std::max(1.0 - v.alpha * options.opacity, 0.0), v.exponent);
}

void write_layers_glb(const std::filesystem::path& path, const LayerBase& base, const std::vector<LayerMesh>& layers,
                      const LayerOptions& options, const TriMesh* terrain)
{
    GlbBuilder b;
    json meshes = json::array(), nodes = json::array(), children = json::array();
    const std::size_t nv = base.position.size();
    // Layer i's vertex is p + i d(p) ([Thesis] (2.6)-(2.10) per vertex: the spacing lifts it,
    // the enlargement (2.10) pushes it from the centre, both linear in i), so every layer is the
    // base mesh with one morph target, d scaled by the top layer's index, at weight i / top
    // (the mesh's weight, in [0, 1] as DCC tools' shape keys expect). Only the alpha differs
    // per layer: a COLOR_0 of its own, the rest is shared.
    const int top = layers.empty() ? 0 : layers.back().index;
    std::vector<float> positions(nv * 3), displacement(nv * 3, 0.0f), normals(nv * 3), uvs(nv * 2);
    for (std::size_t i = 0; i < nv; ++i) {
        const glm::dvec3 n = glm::length(base.normal[i]) > 0.0 ? glm::normalize(base.normal[i]) : glm::dvec3(0, 0, 1);
        const glm::dvec3 p = layers.empty() ? base.position[i] : layers.front().vertices[i].position;
        const glm::dvec3 d = top > 0 ? layers.back().vertices[i].position - p : glm::dvec3(0.0);
        for (int k = 0; k < 3; ++k) {
            normals[i * 3 + k] = float(n[k]);
            positions[i * 3 + k] = float(p[k]);
            displacement[i * 3 + k] = float(d[k]);
        }
        // glTF's v runs downwards from the image's top row.
        uvs[i * 2] = float(base.atlas_uv[i].x);
        uvs[i * 2 + 1] = float(1.0 - base.atlas_uv[i].y);
    }
    const int position_accessor = b.accessor(positions, 3, "VEC3", true);
    const int displacement_accessor = b.accessor(displacement, 3, "VEC3", true);
    const int normal_accessor = b.accessor(normals, 3, "VEC3", false);
    const int uv_accessor = b.accessor(uvs, 2, "VEC2", false);
    const int index_accessor = b.indices(base.triangles);
    const std::vector<std::uint8_t> png = png_bytes(base.texture);
    const int image_view = b.view(png.data(), png.size(), 0);

    for (const LayerMesh& layer : layers) {
        std::vector<std::uint16_t> colors(nv * 4, 65535);
        for (std::size_t i = 0; i < nv; ++i)
            colors[i * 4 + 3] =
                std::uint16_t(std::lround(65535.0 * std::clamp(exported_alpha(layer.vertices[i], options), 0.0, 1.0)));
        const double weight = top > 0 ? double(layer.index) / top : 0.0;
        json primitive = {{"attributes",
                           {{"POSITION", position_accessor},
                            {"NORMAL", normal_accessor},
                            {"TEXCOORD_0", uv_accessor},
                            {"COLOR_0", b.normalized(colors, 4, "VEC4")}}},
                          {"targets", json::array({{{"POSITION", displacement_accessor}}})},
                          {"indices", index_accessor},
                          {"material", 0}};
        const std::string name = "layer " + std::to_string(layer.index);
        meshes.push_back({{"name", name}, {"primitives", json::array({primitive})}, {"weights", {weight}}});
        nodes.push_back({{"name", name}, {"mesh", int(meshes.size()) - 1}});
        children.push_back(int(nodes.size()) - 1);
    }
    json materials =
        json::array({{{"name", "fog layer"},
                      {"pbrMetallicRoughness",
                       {{"baseColorTexture", {{"index", 0}}}, {"metallicFactor", 0.0}, {"roughnessFactor", 1.0}}},
                      {"alphaMode", "BLEND"},
                      {"doubleSided", true}}});
    if (terrain && terrain->n_vertices() > 0) {
        std::vector<float> positions, tnormals;
        positions.reserve(terrain->n_vertices() * 3);
        for (auto v : terrain->vertices()) {
            const auto& p = terrain->point(v);
            positions.insert(positions.end(), {float(p[0]), float(p[1]), float(p[2])});
        }
        std::vector<std::uint32_t> tris;
        tris.reserve(terrain->n_faces() * 3);
        for (auto f : terrain->faces())
            for (auto v : terrain->fv_range(f))
                tris.push_back(std::uint32_t(v.idx()));
        materials.push_back(
            {{"name", "terrain"},
             {"pbrMetallicRoughness",
              {{"baseColorFactor", {0.32, 0.36, 0.22, 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", 1.0}}}});
        json primitive = {{"attributes", {{"POSITION", b.accessor(positions, 3, "VEC3", true)}}},
                          {"indices", b.indices(tris)},
                          {"material", 1}};
        meshes.push_back({{"name", "terrain"}, {"primitives", json::array({primitive})}});
        nodes.push_back({{"name", "terrain"}, {"mesh", int(meshes.size()) - 1}});
        children.push_back(int(nodes.size()) - 1);
    }
    // z-up metres -> glTF y-up: -90 degrees about x.
    const double h = std::sqrt(0.5);
    nodes.push_back({{"name", "kiri (z-up metres)"}, {"rotation", {-h, 0.0, 0.0, h}}, {"children", children}});
    while (b.bin.size() % 4)
        b.bin.push_back(0);

    // The fog's optics and their equivalents in the engines the file is taken to (medium.hpp).
    const double sigma = options.optics.extinction;
    const EngineFog engines = engine_fog(sigma);
    json fog_optics = {{"extinction_per_m", sigma},
                       {"albedo", options.optics.albedo},
                       {"anisotropy_g", options.optics.anisotropy},
                       {"hdrp_fog_attenuation_distance_m", engines.hdrp_attenuation_distance_m},
                       {"unreal_exponential_height_fog_density", engines.unreal_fog_density},
                       {"godot_fog_density", engines.godot_density}};
    if (sigma > 0.0 && std::isfinite(sigma))
        fog_optics["visibility_m"] = visibility_from_extinction(sigma);
    json gltf = {
        {"asset", {{"version", "2.0"}, {"generator", "kiri"}, {"extras", {{"kiri_fog_optics", fog_optics}}}}},
        {"scene", 0},
        {"scenes", json::array({{{"nodes", json::array({int(nodes.size()) - 1})}}})},
        {"nodes", nodes},
        {"meshes", meshes},
        {"materials", materials},
        {"textures", json::array({{{"sampler", 0}, {"source", 0}}})},
        {"images", json::array({{{"bufferView", image_view}, {"mimeType", "image/png"}}})},
        {"samplers", json::array({{{"magFilter", 9729}, {"minFilter", 9729}, {"wrapS", 33071}, {"wrapT", 33071}}})},
        {"accessors", b.accessors},
        {"bufferViews", b.views},
        {"buffers", json::array({{{"byteLength", b.bin.size()}}})}};
    std::string text = gltf.dump();
    while (text.size() % 4)
        text.push_back(' ');
    const auto u32 = [](std::ofstream& out, std::uint32_t v) { out.write(reinterpret_cast<const char*>(&v), 4); };
    std::ofstream out = open_out(path);
    u32(out, 0x46546C67);  // "glTF"
    u32(out, 2);
    u32(out, std::uint32_t(12 + 8 + text.size() + 8 + b.bin.size()));
    u32(out, std::uint32_t(text.size()));
    u32(out, 0x4E4F534A);  // "JSON"
    out.write(text.data(), std::streamsize(text.size()));
    u32(out, std::uint32_t(b.bin.size()));
    u32(out, 0x004E4942);  // "BIN"
    out.write(reinterpret_cast<const char*>(b.bin.data()), std::streamsize(b.bin.size()));
    close_out(out, path);
}

void write_layers_obj(const std::filesystem::path& path, const LayerBase& base, const std::vector<LayerMesh>& layers)
{
    std::ofstream out = open_out(path);
    out << "# kiri fog layers: " << layers.size() << " layers, " << base.position.size() << " vertices each\n";
    out.precision(10);
    const std::size_t nv = base.position.size();
    for (std::size_t i = 0; i < nv; ++i)
        out << "vt " << base.atlas_uv[i].x << ' ' << base.atlas_uv[i].y << '\n';
    for (std::size_t i = 0; i < nv; ++i)
        out << "vn " << base.normal[i].x << ' ' << base.normal[i].y << ' ' << base.normal[i].z << '\n';
    for (std::size_t l = 0; l < layers.size(); ++l) {
        out << "g layer_" << layers[l].index << "\n";
        for (const LayerVertex& v : layers[l].vertices)
            out << "v " << v.position.x << ' ' << v.position.y << ' ' << v.position.z << '\n';
        const std::size_t offset = l * nv + 1;
        for (std::size_t t = 0; t + 2 < base.triangles.size(); t += 3) {
            out << 'f';
            for (int k = 0; k < 3; ++k) {
                const std::size_t vi = base.triangles[t + k];
                out << ' ' << offset + vi << '/' << vi + 1 << '/' << vi + 1;
            }
            out << '\n';
        }
    }
    close_out(out, path);
}

void write_layers_ply(const std::filesystem::path& path, const LayerBase& base, const std::vector<LayerMesh>& layers,
                      const LayerOptions& options)
{
    const std::size_t nv = base.position.size(), nt = base.triangles.size() / 3;
    std::ofstream out = open_out(path);
    out << "ply\nformat binary_little_endian 1.0\ncomment kiri fog layers\n"
        << "element vertex " << nv * layers.size() << "\n"
        << "property float x\nproperty float y\nproperty float z\n"
        << "property float nx\nproperty float ny\nproperty float nz\n"
        << "property float u\nproperty float v\nproperty float alpha\nproperty int layer\n"
        << "element face " << nt * layers.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
    for (const LayerMesh& layer : layers)
        for (std::size_t i = 0; i < nv; ++i) {
            const LayerVertex& v = layer.vertices[i];
            const float f[9] = {
                float(v.position.x),       float(v.position.y),       float(v.position.z),
                float(base.normal[i].x),   float(base.normal[i].y),   float(base.normal[i].z),
                float(base.atlas_uv[i].x), float(base.atlas_uv[i].y), float(exported_alpha(v, options))};
            out.write(reinterpret_cast<const char*>(f), sizeof f);
            const std::int32_t index = layer.index;
            out.write(reinterpret_cast<const char*>(&index), 4);
        }
    for (std::size_t l = 0; l < layers.size(); ++l)
        for (std::size_t t = 0; t < nt; ++t) {
            const std::uint8_t three = 3;
            out.write(reinterpret_cast<const char*>(&three), 1);
            for (int k = 0; k < 3; ++k) {
                const auto idx = std::int32_t(l * nv + base.triangles[t * 3 + k]);
                out.write(reinterpret_cast<const char*>(&idx), 4);
            }
        }
    close_out(out, path);
}

}  // namespace kiri::geometry
