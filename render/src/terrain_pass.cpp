#include "terrain_pass.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "shadow_map_pass.hpp"
#include "kiri/geometry/terrain/terrain.hpp"

namespace kiri::render::detail {
namespace {

struct Vertex {
    float position[3];
    float normal[3];
};

// Grid vertices with normals from central differences (one-sided at the border), in double.
std::vector<Vertex> grid_vertices(const geometry::Heightfield& hf, double exaggeration)
{
    std::vector<Vertex> out(std::size_t(hf.nx) * hf.ny);
    for (int j = 0; j < hf.ny; ++j) {
        const int jm = std::max(j - 1, 0), jp = std::min(j + 1, hf.ny - 1);
        for (int i = 0; i < hf.nx; ++i) {
            const int im = std::max(i - 1, 0), ip = std::min(i + 1, hf.nx - 1);
            const double gx = ip > im ? exaggeration * (hf.at(ip, j) - hf.at(im, j)) / ((ip - im) * hf.dx) : 0.0;
            const double gy = jp > jm ? exaggeration * (hf.at(i, jp) - hf.at(i, jm)) / ((jp - jm) * hf.dy) : 0.0;
            const double inv = 1.0 / std::sqrt(gx * gx + gy * gy + 1.0);
            Vertex& v = out[std::size_t(j) * hf.nx + i];
            v.position[0] = float(hf.x_of(i));
            v.position[1] = float(hf.y_of(j));
            v.position[2] = float(exaggeration * hf.at(i, j));
            v.normal[0] = float(-gx * inv);
            v.normal[1] = float(-gy * inv);
            v.normal[2] = float(inv);
        }
    }
    return out;
}

// Two triangles per cell split along (i, j)-(i+1, j+1), as geometry::Terrain does, counter-
// clockwise seen from above.
std::vector<std::uint32_t> grid_indices(int nx, int ny)
{
    std::vector<std::uint32_t> out;
    out.reserve(std::size_t(nx - 1) * (ny - 1) * 6);
    for (int j = 0; j + 1 < ny; ++j)
        for (int i = 0; i + 1 < nx; ++i) {
            const std::uint32_t a = std::uint32_t(j * nx + i), b = a + 1, c = a + 1 + std::uint32_t(nx),
                                d = a + std::uint32_t(nx);
            out.insert(out.end(), {a, b, c, a, c, d});
        }
    return out;
}

}  // namespace

TerrainPass::TerrainPass() : program_({"terrain.vert", "froxel_none.glsl", "terrain.frag"}) {}

bool TerrainPass::set_terrain(const geometry::Terrain& terrain, double exaggeration)
{
    const geometry::Heightfield& hf = terrain.heightfield();
    if (uploaded_heights_ == hf.z.data() && uploaded_size_ == hf.z.size() && uploaded_exaggeration_ == exaggeration)
        return false;
    if (hf.nx < 2 || hf.ny < 2) {
        index_count_ = 0;
        return false;
    }
    const std::vector<Vertex> vertices = grid_vertices(hf, exaggeration);
    const std::vector<std::uint32_t> indices = grid_indices(hf.nx, hf.ny);
    vao_ = make_vertex_array();
    vertices_ = make_buffer();
    indices_ = make_buffer();
    glNamedBufferStorage(vertices_.get(), GLsizeiptr(vertices.size() * sizeof(Vertex)), vertices.data(), 0);
    glNamedBufferStorage(indices_.get(), GLsizeiptr(indices.size() * sizeof(std::uint32_t)), indices.data(), 0);
    glVertexArrayVertexBuffer(vao_.get(), 0, vertices_.get(), 0, sizeof(Vertex));
    glVertexArrayElementBuffer(vao_.get(), indices_.get());
    for (GLuint attribute : {0u, 1u}) {
        glEnableVertexArrayAttrib(vao_.get(), attribute);
        glVertexArrayAttribFormat(vao_.get(), attribute, 3, GL_FLOAT, GL_FALSE, attribute * 3 * sizeof(float));
        glVertexArrayAttribBinding(vao_.get(), attribute, 0);
    }
    index_count_ = GLsizei(indices.size());
    const auto [lo, hi] = std::minmax_element(hf.z.begin(), hf.z.end());
    min_ = {hf.x0, hf.y0, exaggeration * *lo};
    max_ = {hf.x_max(), hf.y_max(), exaggeration * *hi};
    if (exaggeration < 0.0)
        std::swap(min_.z, max_.z);
    uploaded_heights_ = hf.z.data();
    uploaded_size_ = hf.z.size();
    uploaded_exaggeration_ = exaggeration;
    return true;
}

void TerrainPass::draw_mesh() const
{
    if (!has_terrain())
        return;
    glBindVertexArray(vao_.get());
    glDrawElements(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr);
}

void TerrainPass::draw(const FrameContext& frame, const ShadowMapPass* shadow) const
{
    if (!has_terrain())
        return;
    if (shadow && !shadow_program_)
        shadow_program_ = std::make_unique<ShaderProgram>(
            std::initializer_list<std::string_view>{"terrain.vert", "terrain_shadow.glsl", "terrain.frag"});
    const ShaderProgram& p = shadow ? *shadow_program_ : program_;
    if (shadow)
        shadow->bind(p, true);
    p.set("u_view_projection", frame.view_projection);
    p.set("u_eye", frame.eye);
    p.set("u_sun_direction", frame.sun_direction);
    p.set("u_sun_radiance", frame.sun_radiance);
    p.set("u_ambient", frame.ambient);
    p.set("u_sky_horizon", frame.sky_horizon);
    p.set("u_z_min", float(min_.z));
    p.set("u_z_max", float(max_.z));
    p.set("u_haze_density", frame.haze_density);
    p.use();
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glBindVertexArray(vao_.get());
    glDrawElements(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr);
}

}  // namespace kiri::render::detail
