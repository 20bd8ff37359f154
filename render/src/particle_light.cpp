#include "particle_light.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include "kiri/geometry/particles/particles.hpp"
#include "kiri/render/attenuation.hpp"
#include "particle_gpu.hpp"
#include "shadow_map_pass.hpp"
#include "sun_volume.hpp"

namespace kiri::render::detail {

namespace {

constexpr int light_unit_sun = 12;         // and 13, 14: SunVolume::bind's
constexpr int light_sun_march_steps = 64;  // where the sun volume cannot be read

//! particle_light.glsl's ParticleLightRecord (std430): grid_visible is written by the compute
//! pass, the window and the offset by the CPU.
struct Record {
    float grid_visible[4];    // the particle's shadow_grid (gx, gy, gw0), terrain visibility at its centre
    std::int32_t window[4];   // first column i, j; columns along i, j
    std::uint32_t offset[4];  // its first entry in the gain table; its own share (float bits, the pass's); 0, 0
};
static_assert(sizeof(Record) == 48);

}  // namespace

ParticleLight::ParticleLight()
    : program_({"particle_footprint.glsl", "fog_partition.glsl", "froxel_common.glsl", "fog_lighting.glsl",
                "terrain_shadow.glsl", "medium_shell.glsl", "height_fog.glsl", "froxel_medium.glsl", "sun_march.glsl",
                "sun_volume.glsl", "particle_light.glsl", "particle_light.comp"})
{}

bool ParticleLight::update(const geometry::ParticleCloud& cloud, const AttenuationBuffer& buffer,
                           const ShadowMapPass* shadow, const SunVolume* sun)
{
    const int shadow_updates = shadow ? shadow->updates() : -1;
    if (sun && !sun->medium())
        sun = nullptr;
    const int sun_updates = sun ? sun->updates() : -1;
    if (buffer.rebuild_count() == buffer_builds_ && shadow == shadow_ && shadow_updates == shadow_updates_ &&
        sun == sun_ && sun_updates == sun_updates_ && records_)
        return false;
    const geometry::LightGrid& grid = buffer.grid();
    const std::vector<std::uint32_t>& index = buffer.particle_order();
    const std::size_t n = index.size();
    // The columns whose centres can lie within a particle's radius of its axis (one more each
    // side than the double says, for the float the GPU computes the distance in), clamped to the
    // grid as the trilinear read's columns are.
    const glm::dmat4 to_grid = relative_to_grid(grid, buffer.particle_centre());
    std::vector<Record> records(std::max<std::size_t>(n, 1), Record{});
    std::size_t floats = 0;
    for (std::size_t k = 0; k < n; ++k) {
        const geometry::Particle& p = cloud.particles[index[k]];
        const glm::dvec4 g = to_grid * glm::dvec4(p.position - buffer.particle_centre(), 1.0);
        const double ru = p.radius / grid.voxel.x, rv = p.radius / grid.voxel.y;
        const auto clamp_column = [](double c, int size) { return int(std::clamp(c, 0.0, double(size - 1))); };
        const int i0 = clamp_column(std::floor(g.x - 0.5 - ru) - 1.0, grid.size[0]);
        const int i1 = clamp_column(std::ceil(g.x - 0.5 + ru) + 1.0, grid.size[0]);
        const int j0 = clamp_column(std::floor(g.y - 0.5 - rv) - 1.0, grid.size[1]);
        const int j1 = clamp_column(std::ceil(g.y - 0.5 + rv) + 1.0, grid.size[1]);
        Record& r = records[k];
        r.window[0] = i0;
        r.window[1] = j0;
        r.window[2] = i1 - i0 + 1;
        r.window[3] = j1 - j0 + 1;
        r.offset[0] = std::uint32_t(std::min(floats, table_limit));
        floats += std::size_t(r.window[2]) * std::size_t(r.window[3]);
    }
    table_floats_ = floats <= table_limit ? floats : 0;
    records_bytes_ = records.size() * sizeof(Record);
    records_ = make_buffer();
    glNamedBufferStorage(records_.get(), GLsizeiptr(records.size() * sizeof(Record)), records.data(), 0);
    table_ = make_buffer();
    glNamedBufferStorage(table_.get(), GLsizeiptr(std::max<std::size_t>(table_floats_, 1) * sizeof(float)), nullptr, 0);

    set_grid_uniforms(program_, grid, cloud.forward_scattering, buffer.particle_centre());
    bind_terrain_shadow(program_, shadow);
    program_.set("u_centre", glm::vec3(buffer.particle_centre()));
    // The own share measured against the Medium (particle_light.comp): the buffer at the centre,
    // the Medium's optical depth towards the sun from the sun volume.
    program_.set("u_calibrate", int(sun != nullptr));
    program_.set("u_sun_direction", glm::vec3(grid.light));
    program_.set("u_sun_march", sun_march_direction(glm::vec3(grid.light)));
    program_.set("u_log_gamma", 0);
    glBindTextureUnit(0, buffer.texture());
    if (sun)
        sun->bind(program_, light_unit_sun, light_sun_march_steps);
    program_.set("u_self_table", int(has_table()));
    glProgramUniform1ui(program_.id(), program_.location("u_count"), GLuint(n));
    program_.use();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer.particle_buffer());
    bind();
    glDispatchCompute(GLuint((n + 63) / 64), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

    buffer_builds_ = buffer.rebuild_count();
    shadow_ = shadow;
    shadow_updates_ = shadow_updates;
    sun_ = sun;
    sun_updates_ = sun_updates;
    ++rebuilds_;
    return true;
}

std::vector<glm::vec2> ParticleLight::sample_log_gamma(const geometry::ParticleCloud& cloud,
                                                       const AttenuationBuffer& buffer,
                                                       const std::vector<glm::vec3>& points,
                                                       const std::vector<std::uint32_t>& slots) const
{
    const std::size_t n = std::min(points.size(), slots.size());
    if (!records_ || n == 0)
        return {};
    if (!sample_)
        sample_ = std::make_unique<ShaderProgram>(std::initializer_list<std::string_view>{
            "particle_footprint.glsl", "fog_lighting.glsl", "particle_light.glsl", "particle_light_sample.comp"});
    std::vector<glm::vec4> queries(n);
    for (std::size_t k = 0; k < n; ++k) {
        float slot = 0.0f;
        std::memcpy(&slot, &slots[k], sizeof slot);
        queries[k] = glm::vec4(points[k], slot);
    }
    Buffer in = make_buffer(), out = make_buffer();
    glNamedBufferStorage(in.get(), GLsizeiptr(n * sizeof(glm::vec4)), queries.data(), 0);
    glNamedBufferStorage(out.get(), GLsizeiptr(n * sizeof(glm::vec2)), nullptr, 0);
    set_grid_uniforms(*sample_, buffer.grid(), cloud.forward_scattering, buffer.particle_centre());
    sample_->set("u_self_table", int(has_table()));
    sample_->set("u_sun_direction", glm::vec3(buffer.grid().light));  // own_share_at's
    sample_->set("u_log_gamma", 0);
    glProgramUniform1ui(sample_->id(), sample_->location("u_count"), GLuint(n));
    sample_->use();
    glBindTextureUnit(0, buffer.texture());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer.particle_buffer());
    bind();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, in.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, out.get());
    glDispatchCompute(GLuint((n + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<glm::vec2> result(n);
    glGetNamedBufferSubData(out.get(), 0, GLsizeiptr(n * sizeof(glm::vec2)), result.data());
    return result;
}

void ParticleLight::bind() const
{
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, records_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, table_.get());
}

}  // namespace kiri::render::detail
