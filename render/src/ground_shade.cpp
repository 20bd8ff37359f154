#include "ground_shade.hpp"

#include <algorithm>

#include "sun_volume.hpp"

namespace kiri::render::detail {
namespace {

// Each vertex marches its tau_sun through the Medium, once per sun and fog. The sun volume's
// columns (100 m and more) cannot follow the ground's ridges and valleys under the fog: read at
// the ground there, the sun's transmittance was 0.066 off the reference's (mean |dT| where the
// fog shades, the default scene), marched in 64 steps 0.014, in 128 0.006. Between the
// vertices (Jacksboro's 75 m grid) it is interpolated: 0.010 (the default scene) and 0.048
// (the wind scene, whose fill's shore crosses a cell within metres; 0.015 at twice the grid's
// resolution, for ten times the cost in a texture the terrain's fragments read).
constexpr int march_steps = 128;
// A budget of samples for the whole mesh: a large grid marches in fewer steps (at least 32), so
// that the pass stays a fraction of the still (N57E011's 1.44 million vertices took 1.2 s in
// 128 steps).
constexpr double sample_budget = 128.0 * 200000.0;
constexpr int min_march_steps = 32;
constexpr int sun_unit = 0;  // and 1, 2: SunVolume::bind's

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
                         int stride, int mesh)
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
        glNamedBufferStorage(depths_.get(), GLsizeiptr(std::size_t(vertex_count) * sizeof(float)), nullptr, 0);
    }
    const ShaderProgram& p = *program_;
    const int steps = std::clamp(int(sample_budget / double(vertex_count)), min_march_steps, march_steps);
    sun->bind(p, sun_unit, steps, false);
    p.set("u_sun_direction", k->sun);
    p.set("u_vertices", vertex_count);
    p.set("u_stride", stride);
    p.use();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, vertices);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, depths_.get());
    glDispatchCompute(GLuint((vertex_count + 63) / 64), 1, 1);
    glMemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, 0);
    built_ = k;
    ready_ = true;
    ++updates_;
    return true;
}

}  // namespace kiri::render::detail
