#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>

#include "gl_objects.hpp"
#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/particles/particle_footprint.hpp"
#include "kiri/render/attenuation.hpp"
#include "particle_gpu.hpp"
#include "shader_program.hpp"

namespace kiri::render {

using namespace detail;

struct AttenuationBuffer::Impl {
    // Parentheses, not braces: {"a", "b"} in braces would be one string_view(first, last).
    ShaderProgram deposit = ShaderProgram({"particle_footprint.glsl", "attenuation_deposit.comp"});
    ShaderProgram deposit_packed =
        ShaderProgram({"particle_footprint.glsl", "attenuation_deposit.comp"}, "#define KIRI_PACKED 1\n");
    ShaderProgram scan = ShaderProgram({"attenuation_scan.comp"});
    ShaderProgram scan_quad = ShaderProgram({"attenuation_scan.comp"}, "#define KIRI_QUAD 1\n");
    ShaderProgram scan_half = ShaderProgram({"attenuation_scan.comp"}, "#define KIRI_QUAD 1\n#define KIRI_HALF 1\n");
    ShaderProgram scan_packed =
        ShaderProgram({"attenuation_scan.comp"}, "#define KIRI_QUAD 1\n#define KIRI_PACKED 1\n");
    ShaderProgram scan_packed_half =
        ShaderProgram({"attenuation_scan.comp"}, "#define KIRI_QUAD 1\n#define KIRI_PACKED 1\n#define KIRI_HALF 1\n");
    ShaderProgram sample = ShaderProgram({"particle_footprint.glsl", "attenuation_sample.comp"});
    const geometry::ParticleCloud* cloud = nullptr;
    std::uint64_t hash = 0, built_hash = 0, uploaded_hash = 0;
    GpuParticles gpu;  // the particles as uploaded (sorted by radius; positions relative to the centre)
    bool built = false;
    glm::dvec3 built_light{0.0};
    AttenuationOptions built_options;
    geometry::LightGrid grid;
    Buffer particles;      // GpuParticle per particle, uploaded when the particles change
    Buffer sums, scanned;  // fixed-point deposits, then float log Gamma, voxel order
    Texture log_gamma;
    std::array<int, 3> texture_size{0, 0, 0};
    bool texture_half = true;
    double scale = 1.0;
    bool packed = false;
    int rebuilds = 0;
    double build_ms = 0.0;
    AttenuationBuildTimes times;
    Query stage_queries[4] = {make_query(GL_TIMESTAMP), make_query(GL_TIMESTAMP), make_query(GL_TIMESTAMP),
                              make_query(GL_TIMESTAMP)};

    void ensure_textures(const std::array<int, 3>& size, bool half);
    void build(const glm::dvec3& light, const AttenuationOptions& options);
};

void AttenuationBuffer::Impl::ensure_textures(const std::array<int, 3>& size, bool half)
{
    if (size == texture_size && half == texture_half && sums)
        return;
    const GLsizeiptr bytes = GLsizeiptr(std::size_t(size[0]) * size[1] * size[2] * 4);
    sums = make_buffer();
    glNamedBufferStorage(sums.get(), bytes, nullptr, 0);
    scanned = make_buffer();
    glNamedBufferStorage(scanned.get(), bytes, nullptr, 0);
    log_gamma = make_texture(GL_TEXTURE_3D);
    glTextureStorage3D(log_gamma.get(), 1, half ? GL_R16F : GL_R32F, size[0], size[1], size[2]);
    glTextureParameteri(log_gamma.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(log_gamma.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        glTextureParameteri(log_gamma.get(), wrap, GL_CLAMP_TO_EDGE);
    texture_size = size;
    texture_half = half;
}

void AttenuationBuffer::Impl::build(const glm::dvec3& light, const AttenuationOptions& options)
{
    const auto start = std::chrono::steady_clock::now();
    const geometry::ParticleCloud& c = *cloud;
    grid = geometry::make_light_grid(c, light, {options.resolution, options.frame, options.depth_resolution});
    // The fixed point. 32 bits a voxel: the largest power of two for which every column's sum of
    // log G (at most the sum of every particle's strongest |log G| <= min(tau, 16)) fits an int.
    // Two columns a word (16 bits each, half the atomics) when the scale that keeps every voxel's
    // sum below 2^16 still resolves log G to 1.2e-4 (a receiver behind 140 occluders then carries
    // a rounding noise of ~4e-4 in log Gamma).
    scale = std::exp2(
        std::clamp(std::floor(std::log2(0.9 * 2147483647.0 / std::max(gpu.strongest_log_gain_sum, 1e-30))), 4.0, 24.0));
    const double packed_scale = grid.size[0] % 4 == 0 ? packed_fixed_point_scale(c, grid) : 0.0;
    packed = packed_scale >= 8192.0 && packed_scale * gpu.strongest_log_gain_sum < 2e9;
    if (packed)
        scale = packed_scale;
    ensure_textures(grid.size, options.half_float);
    const GLint zero = 0;
    const auto setup_done = std::chrono::steady_clock::now();
    glQueryCounter(stage_queries[0].get(), GL_TIMESTAMP);
    glClearNamedBufferData(sums.get(), GL_R32I, GL_RED_INTEGER, GL_INT, &zero);

    const std::size_t n = gpu.particles.size();
    const ShaderProgram& d = packed ? deposit_packed : deposit;
    set_grid_uniforms(d, grid, c.forward_scattering, gpu.centre);
    d.set("u_scale", float(scale));
    glProgramUniform1ui(d.id(), d.location("u_count"), GLuint(n));
    d.use();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, particles.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, sums.get());
    glDispatchCompute(GLuint((n + 63) / 64), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glQueryCounter(stage_queries[1].get(), GL_TIMESTAMP);

    // Four columns per invocation where the width allows; half floats packed by the scan (the
    // GL's own float -> half conversion of the upload costs more than the whole build on llvmpipe).
    const bool quad = grid.size[0] % 4 == 0, half = quad && options.half_float;
    const ShaderProgram& s = packed ? (half ? scan_packed_half : scan_packed)
        : half                      ? scan_half
        : quad                      ? scan_quad
                                    : scan;
    const int columns = grid.size[0] * grid.size[1] / (quad ? 4 : 1);
    glProgramUniform3i(s.id(), s.location("u_size"), grid.size[0], grid.size[1], grid.size[2]);
    s.set("u_inverse_scale", float((packed ? -1.0 : 1.0) / scale));
    s.use();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, sums.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, scanned.get());
    glDispatchCompute(GLuint((columns + 63) / 64), 1, 1);
    glMemoryBarrier(GL_PIXEL_BUFFER_BARRIER_BIT);
    glQueryCounter(stage_queries[2].get(), GL_TIMESTAMP);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, scanned.get());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 2);
    glTextureSubImage3D(log_gamma.get(), 0, 0, 0, 0, grid.size[0], grid.size[1], grid.size[2], GL_RED,
                        half ? GL_HALF_FLOAT : GL_FLOAT, nullptr);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    glQueryCounter(stage_queries[3].get(), GL_TIMESTAMP);
    glFinish();
    build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    GLuint64 stamp[4] = {0, 0, 0, 0};
    for (int q = 0; q < 4; ++q)
        glGetQueryObjectui64v(stage_queries[q].get(), GL_QUERY_RESULT, &stamp[q]);
    times.setup_ms = std::chrono::duration<double, std::milli>(setup_done - start).count();
    times.deposit_ms = double(stamp[1] - stamp[0]) * 1e-6;
    times.scan_ms = double(stamp[2] - stamp[1]) * 1e-6;
    times.upload_ms = double(stamp[3] - stamp[2]) * 1e-6;
    built = true;
    built_hash = hash;
    built_light = light;
    built_options = options;
    ++rebuilds;
}

AttenuationBuffer::AttenuationBuffer() : impl_(std::make_unique<Impl>()) {}
AttenuationBuffer::~AttenuationBuffer() = default;

void AttenuationBuffer::set_particles(const geometry::ParticleCloud& cloud)
{
    Impl& m = *impl_;
    m.cloud = &cloud;
    m.hash = hash_particles(cloud);
    if (m.hash == m.uploaded_hash && m.particles)
        return;
    m.gpu = gpu_particles(cloud);
    m.particles = make_buffer();
    glNamedBufferStorage(m.particles.get(),
                         GLsizeiptr(std::max<std::size_t>(m.gpu.particles.size(), 1) * sizeof(GpuParticle)),
                         m.gpu.particles.empty() ? nullptr : m.gpu.particles.data(), 0);
    m.uploaded_hash = m.hash;
}

void AttenuationBuffer::clear()
{
    impl_->cloud = nullptr;
    impl_->built = false;
}

bool AttenuationBuffer::has_particles() const { return impl_->cloud && !impl_->cloud->particles.empty(); }

bool AttenuationBuffer::update(const glm::dvec3& light, const AttenuationOptions& options)
{
    Impl& m = *impl_;
    if (!has_particles())
        return false;
    if (m.built && m.built_hash == m.hash && m.built_light == light && m.built_options == options)
        return false;
    m.build(light, options);
    return true;
}

void AttenuationBuffer::rebuild(const glm::dvec3& light, const AttenuationOptions& options)
{
    if (!has_particles())
        throw Error("AttenuationBuffer::rebuild: no particles");
    impl_->build(light, options);
}

int AttenuationBuffer::rebuild_count() const { return impl_->rebuilds; }
double AttenuationBuffer::last_build_ms() const { return impl_->build_ms; }
const AttenuationBuildTimes& AttenuationBuffer::last_build_times() const { return impl_->times; }
const geometry::LightGrid& AttenuationBuffer::grid() const { return impl_->grid; }
std::size_t AttenuationBuffer::texture_bytes() const
{
    const auto& s = impl_->texture_size;
    return std::size_t(s[0]) * s[1] * s[2] * (impl_->texture_half ? 2 : 4);
}
std::size_t AttenuationBuffer::scratch_bytes() const
{
    const auto& s = impl_->texture_size;
    return std::size_t(s[0]) * s[1] * s[2] * 8;
}
double AttenuationBuffer::fixed_point_scale() const { return impl_->scale; }
bool AttenuationBuffer::packed_deposit() const { return impl_->packed; }
unsigned AttenuationBuffer::texture() const { return impl_->log_gamma.get(); }
unsigned AttenuationBuffer::particle_buffer() const { return impl_->particles.get(); }
const glm::dvec3& AttenuationBuffer::particle_centre() const { return impl_->gpu.centre; }
const std::vector<std::uint32_t>& AttenuationBuffer::particle_order() const { return impl_->gpu.index; }

std::vector<float> AttenuationBuffer::gamma_at_particles() const
{
    const Impl& m = *impl_;
    if (!m.built || !m.cloud)
        return {};
    const std::size_t n = m.gpu.particles.size();
    Buffer out = make_buffer();
    glNamedBufferStorage(out.get(), GLsizeiptr(std::max<std::size_t>(n, 1) * sizeof(float)), nullptr, 0);
    set_grid_uniforms(m.sample, m.grid, m.cloud->forward_scattering, m.gpu.centre);
    glProgramUniform1ui(m.sample.id(), m.sample.location("u_count"), GLuint(n));
    m.sample.set("u_log_gamma", 0);
    m.sample.use();
    glBindTextureUnit(0, m.log_gamma.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, m.particles.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, out.get());
    glDispatchCompute(GLuint((n + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<float> sorted(n), gamma(n);
    glGetNamedBufferSubData(out.get(), 0, GLsizeiptr(n * sizeof(float)), sorted.data());
    for (std::size_t k = 0; k < n; ++k)  // back to the cloud's order
        gamma[m.gpu.index[k]] = sorted[k];
    return gamma;
}

std::vector<float> AttenuationBuffer::read_log_gamma() const
{
    const Impl& m = *impl_;
    if (!m.built)
        return {};
    std::vector<float> v(m.grid.voxel_count());
    glGetTextureImage(m.log_gamma.get(), 0, GL_RED, GL_FLOAT, GLsizei(v.size() * sizeof(float)), v.data());
    return v;
}

}  // namespace kiri::render
