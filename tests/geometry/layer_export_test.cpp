// The compact glTF of the layer stack (layer_export.hpp), read back: every layer is the base
// plus the morph target at its weight, with its own alpha, equal to the stack kiri builds.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "geometry/fog_test_terrains.hpp"
#include "kiri/geometry/layers/layer_export.hpp"
#include "kiri/geometry/scene/fog_spec.hpp"
#include "temp_path.hpp"

using namespace kiri::geometry;
using json = nlohmann::json;

namespace {

struct Glb {
    json gltf;
    std::string bin;

    explicit Glb(const std::filesystem::path& path)
    {
        std::ifstream in(path, std::ios::binary);
        std::stringstream s;
        s << in.rdbuf();
        const std::string bytes = s.str();
        std::uint32_t json_bytes = 0, bin_bytes = 0;
        std::memcpy(&json_bytes, bytes.data() + 12, 4);
        gltf = json::parse(bytes.substr(20, json_bytes));
        std::memcpy(&bin_bytes, bytes.data() + 20 + json_bytes, 4);
        bin = bytes.substr(20 + json_bytes + 8, bin_bytes);
    }
    // Element k of accessor a as `components` values of T.
    template <class T>
    std::vector<double> element(int a, std::size_t k, int components) const
    {
        const json& acc = gltf["accessors"][a];
        const json& view = gltf["bufferViews"][acc["bufferView"].get<int>()];
        const std::size_t offset = view["byteOffset"].get<std::size_t>() + k * components * sizeof(T);
        std::vector<double> out(static_cast<std::size_t>(components), 0.0);
        for (int c = 0; c < components; ++c) {
            T v;
            std::memcpy(&v, bin.data() + offset + c * sizeof(T), sizeof(T));
            out[std::size_t(c)] = double(v);
        }
        return out;
    }
};

}  // namespace

TEST(LayerExport, TheCompactGlbHoldsEveryLayerOfTheStack)
{
    const Terrain terrain(kiri::test::make_heightfield(81, 81, 25.0, -1000.0, -1000.0, kiri::test::hills));
    FogSpec spec;
    spec.patch_size = 500.0;
    spec.margin = 100.0;
    spec.tessellation.level = 4;
    BaseSurface surface = fog_control_surface(terrain, spec);
    fit_fog_surface(surface, terrain, spec);
    const Tessellation tessellation = tessellate(surface, spec.tessellation);
    LayerOptions options;
    options.count = 6;
    options.thickness = 200.0;
    options.max_count = 40;
    options.enlargement_rate = 0.02;         // (2.10) visibly on: a shear from the centre
    options.shading = LayerShading::source;  // the shading the enlargement is drawn in
    const LayerBase base = make_layer_base(surface, tessellation, options);
    const glm::dvec3 eye(-1500.0, -1800.0, 1500.0);  // near: narrowing (2.8) and added layers (2.9)
    const std::vector<LayerMesh> layers = build_layers(base, options, eye);
    ASSERT_GT(layers.size(), 7u);

    const std::filesystem::path path = kiri::test::temp_path("layers.glb");
    write_layers_glb(path, base, layers, options);
    const Glb glb(path);
    std::filesystem::remove(path);
    const json& meshes = glb.gltf["meshes"];
    ASSERT_EQ(meshes.size(), layers.size());
    const std::size_t nv = base.position.size();
    double worst_position = 0.0, worst_alpha = 0.0;
    for (std::size_t l = 0; l < layers.size(); ++l) {
        const json& primitive = meshes[l]["primitives"][0];
        const double weight = meshes[l]["weights"][0].get<double>();
        EXPECT_GE(weight, 0.0);
        EXPECT_LE(weight, 1.0);
        const int position = primitive["attributes"]["POSITION"].get<int>();
        const int target = primitive["targets"][0]["POSITION"].get<int>();
        const int color = primitive["attributes"]["COLOR_0"].get<int>();
        EXPECT_EQ(position, meshes[0]["primitives"][0]["attributes"]["POSITION"].get<int>());  // shared
        for (std::size_t i = 0; i < nv; i += 7) {
            const auto p = glb.element<float>(position, i, 3), d = glb.element<float>(target, i, 3);
            const glm::dvec3 want = layers[l].vertices[i].position;
            for (int k = 0; k < 3; ++k)
                worst_position =
                    std::max(worst_position, std::abs(p[std::size_t(k)] + weight * d[std::size_t(k)] - want[k]));
            const double alpha = glb.element<std::uint16_t>(color, i, 4)[3] / 65535.0;
            worst_alpha = std::max(worst_alpha, std::abs(alpha - exported_alpha(layers[l].vertices[i], options)));
        }
    }
    EXPECT_LT(worst_position, 2e-3);  // float precision of 1 km coordinates
    EXPECT_LE(worst_alpha, 0.5 / 65535.0 + 1e-12);
}
