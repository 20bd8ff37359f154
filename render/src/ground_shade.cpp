#include "ground_shade.hpp"

#include <algorithm>

#include "staged_read.hpp"
#include "sun_volume.hpp"

namespace kiri::render::detail {
namespace {

// Each vertex marches its tau_sun through the Medium, once per sun and fog. The sun volume's
// columns (100 m and more) cannot follow the ground's ridges and valleys under the fog: read at
// the ground there, the sun's transmittance was 0.066 off the reference's (mean |dT| where the
// fog shades, the default scene), marched in 64 steps 0.014, in 128 0.006. Between the
// vertices (Jacksboro's 75 m grid) it is interpolated: 0.010 on the default scene, but a fog's
// shore or wall crossing a cell within metres (the wind scene's fill) spilled its shade over
// the sunlit ground beside it (0.048): there the fine map below.
constexpr int most_march_steps = 128;
// A budget of samples for the whole mesh: a large grid marches in fewer steps (at least 32), so
// that the pass stays a fraction of the still (N57E011's 1.44 million vertices took 1.2 s in
// 128 steps).
constexpr double sample_budget = 128.0 * 200000.0;
constexpr int min_march_steps = 32;
// A vertex whose neighbours' transmittance through the Medium bends by more than this (second
// difference) has the fragments of its four cells read the fine map: interpolated mid-cell, a
// bend b is off by about b / 8 where the shade is smooth and up to b / 4 at a shore's kink.
// Under a fill's lake the shade bends everywhere with the depth of the fog: 0.1 marked 22 % of
// its vertices (a pass of 1.2 s), 0.25 9 % (0.48 s), for the wind view's error 2.7 against 2.8 %.
constexpr float bend_to_refine = 0.25f;
// The fine map: samples a cell (fewer for a grid so large that the map would pass
// max_fine_texels a side; N57E011's 1201: 3), each marched in fine_march_steps steps. On the
// wind view (160x90, combined) 2 / 3 / 4 samples in 32 steps: 3.0 / 2.8 / 2.7 % for 150 / 190 /
// 270 ms; 4 in 128 steps 2.5 % for 2.1 s; interpolated 4.4 %.
constexpr int fine_samples = 3, max_fine_texels = 4096, fine_march_steps = 32;
// And a budget of samples for the fine map, as for the vertices: a grid whose fog has many shores
// marches them in fewer steps (at least 8). N57E011.hgt's derived fog marks 39,603 of its 1.6
// million vertices: 62 million samples in 32 steps, a pass of 1.7 s against 0.33 s without
// the map.
constexpr double fine_sample_budget = 0.5 * sample_budget;
constexpr int min_fine_march_steps = 8;
constexpr int phase0_row = 4096;  // ground_shade.comp's invocations a row in phase 0
constexpr int sun_unit = 0;       // and 1, 2: SunVolume::bind's

}  // namespace

std::optional<GroundShade::Key> GroundShade::key(const SunVolume* sun, const glm::vec3& sun_direction, int vertex_count,
                                                 int mesh)
{
    if (!sun || vertex_count <= 0 || (!sun->medium() && !sun->haze().enabled()))
        return std::nullopt;
    return Key{mesh, vertex_count, sun_march_direction(sun_direction), sun->medium(), sun->updates(), sun->haze()};
}

bool GroundShade::stale(const SunVolume* sun, const glm::vec3& sun_direction, int vertex_count, int mesh) const
{
    const std::optional<Key> k = key(sun, sun_direction, vertex_count, mesh);
    return k && !(built_ && *built_ == *k);
}

bool GroundShade::update(const SunVolume* sun, const glm::vec3& sun_direction, GLuint vertices, int vertex_count,
                         int stride, const Grid& grid, int mesh)
{
    const std::optional<Key> k = key(sun, sun_direction, vertex_count, mesh);
    if (!k) {
        built_.reset();
        ready_ = false;
        return false;
    }
    if (built_ && *built_ == *k)
        return ready_;
    if (!program_)
        program_.emplace(std::initializer_list<std::string_view>{
            "fog_partition.glsl", "froxel_common.glsl", "fog_lighting.glsl", "medium_shell.glsl", "height_fog.glsl",
            "froxel_medium.glsl", "sun_march.glsl", "sun_volume.glsl", "ground_shade.comp"});
    if (!built_ || built_->vertex_count != vertex_count || built_->mesh != mesh || !depths_) {
        depths_ = make_buffer();
        glNamedBufferStorage(depths_.get(), GLsizeiptr(std::size_t(vertex_count) * 4 * sizeof(float)), nullptr, 0);
    }
    const GLsizeiptr marks_bytes =
        GLsizeiptr((1 + std::size_t(std::max(grid.nx, 0)) * std::max(grid.ny, 0)) * sizeof(GLuint));
    if (!marks_ || !(grid == grid_)) {
        marks_ = make_buffer();
        glNamedBufferStorage(marks_.get(), marks_bytes, nullptr, GL_DYNAMIC_STORAGE_BIT);
    }
    const GLuint zero = 0;
    glNamedBufferSubData(marks_.get(), 0, sizeof(GLuint), &zero);
    grid_ = grid;
    const bool on_grid = grid.nx >= 3 && grid.ny >= 3 && grid.columns > 0 &&
        std::size_t(grid.ny + 2 * grid.rings) * std::size_t(grid.columns) == std::size_t(vertex_count);
    fine_scale_ = on_grid ? std::clamp(max_fine_texels / std::max(grid.nx, grid.ny), 1, fine_samples) : 1;

    const ShaderProgram& p = *program_;
    const int steps = std::clamp(int(sample_budget / double(vertex_count)), min_march_steps, most_march_steps);
    sun->bind(p, sun_unit, steps, false);
    p.set("u_sun_direction", k->sun);
    p.set("u_vertices", vertex_count);
    p.set("u_stride", stride);
    p.set("u_grid", glm::ivec4(grid.nx, grid.ny, grid.columns, grid.rings));
    p.set("u_fine", fine_scale_);
    p.set("u_bend", bend_to_refine);
    p.use();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, vertices);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, depths_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, marks_.get());
    const auto groups = [](int n) { return GLuint((n + 7) / 8); };
    p.set("u_phase", 0);  // tau_sun at every vertex, phase0_row a row of invocations
    p.set("u_row", phase0_row);
    glDispatchCompute(groups(phase0_row), groups((vertex_count + phase0_row - 1) / phase0_row), 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    refined_ = 0;
    if (fine_scale_ > 1) {
        p.set("u_phase", 1);  // where it bends
        glDispatchCompute(groups(grid.nx), groups(grid.ny), 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        GLuint refined = 0;  // once per sun and fog: the wait is the pass's own
        const GLuint marks = marks_.get();
        read_buffers_staged({&marks, 1}, sizeof(GLuint), &refined);
        refined_ = int(refined);
    }
    if (refined_ > 0) {
        const glm::ivec2 size = (glm::ivec2(grid.nx, grid.ny) - 1) * fine_scale_ + 1;
        if (!fine_ || size != fine_size_) {
            fine_ = make_texture(GL_TEXTURE_2D);
            glTextureStorage2D(fine_.get(), 1, GL_RG32F, size.x, size.y);
            glTextureParameteri(fine_.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
            glTextureParameteri(fine_.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
            glTextureParameteri(fine_.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
            glTextureParameteri(fine_.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
            fine_size_ = size;
        }
        p.set("u_phase", 2);  // the fine map around the marked vertices
        const int side = 2 * fine_scale_ + 1;
        const double texels = double(refined_) * double(side * side);
        p.set("u_sv_steps", std::clamp(int(fine_sample_budget / texels), min_fine_march_steps, fine_march_steps));
        glBindImageTexture(0, fine_.get(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RG32F);
        glDispatchCompute(groups(side * side), groups(refined_), 1);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        p.set("u_phase", 3);  // the Medium's part carried on below 0 beyond its shade
        glDispatchCompute(groups(side * side), groups(refined_), 1);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    }
    glMemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, 0);
    built_ = k;
    ready_ = true;
    ++updates_;
    return true;
}

void GroundShade::bind_fine(const ShaderProgram& p, int unit) const
{
    p.set("u_gs_fine", unit);
    p.set("u_gs_origin", grid_.origin);
    p.set("u_gs_spacing", grid_.spacing);
    p.set("u_gs_fine_scale", float(fine_scale_));
    glBindTextureUnit(GLuint(unit), fine_.get());
}

}  // namespace kiri::render::detail
