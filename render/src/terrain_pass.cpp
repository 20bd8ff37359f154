#include "terrain_pass.hpp"

#include <epoxy/gl.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "kiri/geometry/terrain/ground.hpp"
#include "terrain_levels.hpp"
#include "render_targets.hpp"
#include "shadow_map_pass.hpp"
#include "sun_volume.hpp"
#include "kiri/geometry/terrain/terrain.hpp"

namespace kiri::render::detail {
namespace {

struct TerrainPassVertex {
    float position[3];
    float normal[3];
};

// Offsets of the surround's rings from the grid's edge: the first a third of a cell out, each
// spacing 15 % longer than the last (the mesh follows the surround's smoothstep within a per cent
// of its drop), the last at the ease distance, where the surround is flat. Close rings by the
// edge: a fog reaching the DEM's edge shades the surround beyond it out to where the sun's path
// clears the fog's wall, and the fog's shade is interpolated between the rings (a cell out first,
// the jacksboro_wind view's ground beyond the DEM's western edge a line of pixels 15 to 30 % too
// dark: combined 1.95 / 14.2 % off the reference, now 1.73 / 9.3 %).
std::vector<double> ring_offsets(double cell, double ease)
{
    std::vector<double> out;
    double spacing = cell / 3.0, offset = 0.0;
    while (offset + spacing < ease) {
        offset += spacing;
        out.push_back(offset);
        spacing *= 1.15;
    }
    out.push_back(ease);
    return out;
}

// The tensor grid's coordinates along one axis: the rings before the grid, its samples, the
// rings after.
std::vector<double> axis(double first, double step, int samples, const std::vector<double>& rings)
{
    std::vector<double> out;
    for (auto r = rings.rbegin(); r != rings.rend(); ++r)
        out.push_back(first - *r);
    for (int i = 0; i < samples; ++i)
        out.push_back(first + i * step);
    const double last = first + (samples - 1) * step;
    for (double r : rings)
        out.push_back(last + r);
    return out;
}

// The fog's fine shade map (GroundShade::bind_fine), clear of the shadow map's (shadow_map_pass.hpp).
constexpr int fine_shade_unit = 12;
static_assert(fine_shade_unit != shadow_map_unit);

}  // namespace

TerrainPass::TerrainPass() { program(false, Shade::none); }

// Whether terrain.frag can read which samples passed the depth test (GL_ARB_post_depth_coverage,
// llvmpipe's and NVIDIA's); without it, those its triangle covers. Its #extension line goes before
// every stage of the program (the preamble's way), so `enable`: a stage it means nothing to warns.
static bool post_depth_coverage()
{
    static const bool has = epoxy_has_gl_extension("GL_ARB_post_depth_coverage");
    return has;
}

const ShaderProgram& TerrainPass::program(bool shadow, Shade shade) const
{
    std::unique_ptr<ShaderProgram>& p = programs_[shadow][int(shade)];
    if (!p) {
        std::vector<std::string_view> files{"terrain.vert", shadow ? "terrain_shadow.glsl" : "froxel_none.glsl",
                                            "ground.glsl"};
        files.push_back(shade == Shade::fine ? "ground_shade.glsl" : "ground_shade_none.glsl");
        files.push_back("terrain.frag");
        std::string preamble =
            post_depth_coverage() ? "#extension GL_ARB_post_depth_coverage : enable\n#define SEEN_SAMPLES 1\n" : "";
        if (shade != Shade::none)
            preamble += "#define FOG_SHADE_SAMPLES 1\n";
        p = std::make_unique<ShaderProgram>(files, preamble);
    }
    return *p;
}

bool TerrainPass::set_terrain(const geometry::Terrain& terrain, double exaggeration, bool surround)
{
    const geometry::Heightfield& hf = terrain.heightfield();
    if (uploaded_heights_ == hf.z.data() && uploaded_size_ == hf.z.size() && uploaded_exaggeration_ == exaggeration &&
        uploaded_surround_ == surround)
        return false;
    if (hf.nx < 2 || hf.ny < 2) {
        for (Level& l : levels_)
            l = {};
        return false;
    }
    const geometry::Ground ground(hf, surround);
    const std::vector<double> rings =
        surround ? ring_offsets(std::min(hf.dx, hf.dy), ground.ease()) : std::vector<double>{};
    const int k = int(rings.size());
    const std::vector<double> xs = axis(hf.x0, hf.dx, hf.nx, rings), ys = axis(hf.y0, hf.dy, hf.ny, rings);
    const int nx = int(xs.size()), ny = int(ys.size());
    const auto in_grid = [&](int i, int j) { return i >= k && i < k + hf.nx && j >= k && j < k + hf.ny; };
    std::vector<TerrainPassVertex> vertices(std::size_t(nx) * ny);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            double z, gx, gy;  // height and slope, exaggeration applied
            if (in_grid(i, j)) {
                // The grid's samples with normals from central differences (one-sided at the border).
                const int gi = i - k, gj = j - k;
                const int im = std::max(gi - 1, 0), ip = std::min(gi + 1, hf.nx - 1);
                const int jm = std::max(gj - 1, 0), jp = std::min(gj + 1, hf.ny - 1);
                z = exaggeration * ground.sample(gi, gj);
                gx = ip > im ? exaggeration * (ground.sample(ip, gj) - ground.sample(im, gj)) / ((ip - im) * hf.dx)
                             : 0.0;
                gy = jp > jm ? exaggeration * (ground.sample(gi, jp) - ground.sample(gi, jm)) / ((jp - jm) * hf.dy)
                             : 0.0;
            } else {
                const glm::dvec3 n = ground.normal(xs[i], ys[j]);
                z = exaggeration * ground.height(xs[i], ys[j]);
                gx = -exaggeration * n.x / n.z;
                gy = -exaggeration * n.y / n.z;
            }
            const double inv = 1.0 / std::sqrt(gx * gx + gy * gy + 1.0);
            vertices[std::size_t(j) * nx + i] = {{float(xs[i]), float(ys[j]), float(z)},
                                                 {float(-gx * inv), float(-gy * inv), float(inv)}};
        }
    // Per level (every sample, every 2nd, 4th and 8th) the level's grid and its surround, on the
    // same vertices, counter-clockwise seen from above; the first level's grid is every cell split
    // along (i, j)-(i+1, j+1), as geometry::Terrain does (terrain_levels.hpp).
    std::vector<std::uint32_t> indices;
    const GridLayout layout{hf.nx, hf.ny, nx, k};
    for (int level = 0; level < int(std::size(levels_)); ++level) {
        Level& l = levels_[level];
        const std::vector<std::uint32_t> grid = grid_level_indices(layout, 1 << level);
        l.grid = {GLsizei(indices.size()), GLsizei(grid.size())};
        indices.insert(indices.end(), grid.begin(), grid.end());
        const std::vector<std::uint32_t> outer = surround_level_indices(layout, 1 << level);
        l.surround = {GLsizei(indices.size()), GLsizei(outer.size())};
        indices.insert(indices.end(), outer.begin(), outer.end());
    }
    vao_ = make_vertex_array();
    shaded_ = false;
    shade_grid_ = {hf.nx, hf.ny, nx, k, glm::vec2(float(hf.x0), float(hf.y0)), glm::vec2(float(hf.dx), float(hf.dy))};
    vertex_count_ = GLsizei(vertices.size());
    ++uploads_;
    vertices_ = make_buffer();
    indices_ = make_buffer();
    glNamedBufferStorage(vertices_.get(), GLsizeiptr(vertices.size() * sizeof(TerrainPassVertex)), vertices.data(), 0);
    glNamedBufferStorage(indices_.get(), GLsizeiptr(indices.size() * sizeof(std::uint32_t)), indices.data(), 0);
    glVertexArrayVertexBuffer(vao_.get(), 0, vertices_.get(), 0, sizeof(TerrainPassVertex));
    glVertexArrayElementBuffer(vao_.get(), indices_.get());
    for (GLuint attribute : {0u, 1u}) {
        glEnableVertexArrayAttrib(vao_.get(), attribute);
        glVertexArrayAttribFormat(vao_.get(), attribute, 3, GL_FLOAT, GL_FALSE, attribute * 3 * sizeof(float));
        glVertexArrayAttribBinding(vao_.get(), attribute, 0);
    }
    const auto [lo, hi] = std::minmax_element(hf.z.begin(), hf.z.end());
    min_ = {hf.x0, hf.y0, exaggeration * *lo};
    max_ = {hf.x_max(), hf.y_max(), exaggeration * *hi};
    if (exaggeration < 0.0)
        std::swap(min_.z, max_.z);
    colour_z_min_ = float(exaggeration * ground.z_min());
    colour_z_max_ = float(exaggeration * ground.z_max());
    if (exaggeration < 0.0)
        std::swap(colour_z_min_, colour_z_max_);
    water_ = ground.sea_level().has_value();
    sea_level_ = float(exaggeration * ground.sea_level().value_or(0.0));
    water_tolerance_ = float(std::abs(exaggeration) * ground.water_tolerance());
    base_z_ = float(exaggeration * ground.base());
    uploaded_heights_ = hf.z.data();
    uploaded_size_ = hf.z.size();
    uploaded_exaggeration_ = exaggeration;
    uploaded_surround_ = surround;
    return true;
}

void TerrainPass::set_ground_uniforms(const ShaderProgram& p, const FrameContext& frame) const
{
    p.set("u_ground_albedo", frame.ground_albedo);
    p.set("u_z_min", colour_z_min_);
    p.set("u_z_max", colour_z_max_);
    p.set("u_water", int(water_));
    p.set("u_sea_level", sea_level_);
    p.set("u_water_tolerance", water_tolerance_);
    p.set("u_ground", int(has_terrain() && levels_[0].surround.count > 0));
    p.set("u_ground_z", base_z_);
}

void TerrainPass::set_resolution(double scale)
{
    level_ = 0;
    while (level_ + 1 < int(std::size(levels_)) && std::isfinite(scale) && scale * (1 << (level_ + 1)) <= 1.0 + 1e-9)
        ++level_;
}

GLsizei TerrainPass::drawn_triangles() const { return has_terrain() ? levels_[level_].grid.count / 3 : 0; }

void TerrainPass::draw_mesh() const
{
    if (!has_terrain())
        return;
    glBindVertexArray(vao_.get());
    glDrawElements(GL_TRIANGLES, levels_[0].grid.count, GL_UNSIGNED_INT, nullptr);  // at offset 0
}

bool TerrainPass::set_fog_shade(const SunVolume* sun, const glm::vec3& sun_direction)
{
    if (!has_terrain())
        return false;
    const int before = shade_.updates();
    const bool shaded = shade_.update(sun, sun_direction, vertices_.get(), int(vertex_count_),
                                      int(sizeof(TerrainPassVertex) / sizeof(float)), shade_grid_, uploads_);
    if (shaded) {
        glVertexArrayVertexBuffer(vao_.get(), 1, shade_.buffer(), 0, 4 * sizeof(float));
        glVertexArrayAttribFormat(vao_.get(), 2, 4, GL_FLOAT, GL_FALSE, 0);
        glVertexArrayAttribBinding(vao_.get(), 2, 1);
        glEnableVertexArrayAttrib(vao_.get(), 2);
    } else if (shaded_) {
        glDisableVertexArrayAttrib(vao_.get(), 2);
    }
    shaded_ = shaded;
    return shade_.updates() != before;
}

// terrain.frag's u_shown_offsets (the mean offset of each set of a pixel's 4 samples; zero for
// another count: the centre) and u_rays (the ray through a window point, linear in it).
static void set_shown_samples(const ShaderProgram& p, const FrameContext& frame, const FrameSamples* samples)
{
    std::array<glm::vec2, 16> shown{};
    if (samples && samples->offsets && samples->count == 4)
        for (int mask = 1; mask < 16; ++mask) {
            glm::vec2 sum(0.0f);
            int n = 0;
            for (int s = 0; s < 4; ++s)
                if (mask & (1 << s)) {
                    sum += glm::vec2(samples->offsets[2 * s], samples->offsets[2 * s + 1]);
                    ++n;
                }
            shown[std::size_t(mask)] = sum / float(n);
        }
    glProgramUniform2fv(p.id(), p.location("u_shown_offsets"), 16, &shown[0].x);
    // The frame's NDC rays in window points (independent of its near and far planes, which move
    // with the scene's bounds: two frames of one view shade the ground alike).
    const glm::vec3 rays[3] = {glm::vec3(frame.ray_forward - frame.ray_right - frame.ray_up),
                               glm::vec3(frame.ray_right * (2.0 / double(frame.width))),
                               glm::vec3(frame.ray_up * (2.0 / double(frame.height)))};
    glProgramUniform3fv(p.id(), p.location("u_rays"), 3, &rays[0].x);
}

void TerrainPass::draw(const FrameContext& frame, const ShadowMapPass* shadow, const FrameSamples* samples) const
{
    if (!has_terrain())
        return;
    const Shade shade = !shaded_ ? Shade::none : shade_.refined_vertices() > 0 ? Shade::fine : Shade::vertices;
    const ShaderProgram& p = program(shadow != nullptr, shade);
    if (shadow)
        shadow->bind(p, true);
    if (shade == Shade::fine)
        shade_.bind_fine(p, fine_shade_unit);
    p.set("u_view_projection", frame.view_projection);
    set_light_uniforms(p, frame);
    set_shown_samples(p, frame, samples);
    set_ground_uniforms(p, frame);
    p.use();
    if (!shaded_)
        glVertexAttrib4f(2, 0.0f, 0.0f, 0.0f, 0.0f);  // no fog's shade: tau_sun 0, nothing to refine
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glBindVertexArray(vao_.get());
    const Level& level = levels_[level_];
    const auto draw_range = [](Range r) {
        glDrawElements(GL_TRIANGLES, r.count, GL_UNSIGNED_INT,
                       reinterpret_cast<const void*>(std::size_t(r.offset) * sizeof(std::uint32_t)));
    };
    draw_range(level.grid);
    if (level.surround.count > 0) {
        // The frame's far plane is fitted to the grid: the surround beyond it is kept at the far
        // depth (the sky pass's flat ground is what lies further still).
        glEnable(GL_DEPTH_CLAMP);
        glDepthFunc(GL_LEQUAL);
        draw_range(level.surround);
        glDisable(GL_DEPTH_CLAMP);
        glDepthFunc(GL_LESS);
    }
}

}  // namespace kiri::render::detail
