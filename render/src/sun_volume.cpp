#include "sun_volume.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "probe_readback.hpp"

namespace kiri::render::detail {

namespace {

// Columns a side for a grid of n samples a side: a grid finer than max_columns is spread over
// max_columns; a coarser one than min_columns is divided evenly, so that every sample is a column
// (a step in the shell's top between two samples stays between two columns).
int columns(int n, const SunVolumeResolution& r)
{
    const int lo = std::max(r.min_columns, 2), hi = std::max(r.max_columns, lo);
    if (n > hi)
        return hi;
    const int split = (lo - 1 + (n - 2)) / std::max(n - 1, 1);  // ceil((lo - 1) / (n - 1))
    return std::min(std::max(split, 1) * (n - 1) + 1, std::max(hi, n));
}

}  // namespace

glm::vec3 sun_march_direction(glm::vec3 d)
{
    for (int c = 0; c < 3; ++c)
        if (std::abs(d[c]) < 1e-6f)
            d[c] = 1e-6f;
    return glm::normalize(d);
}

SunVolume::SunVolume()
    : fill_({"fog_partition.glsl", "froxel_common.glsl", "fog_lighting.glsl", "medium_shell.glsl", "height_fog.glsl",
             "froxel_medium.glsl", "sun_march.glsl", "sun_volume.glsl", "sun_volume.comp"})
{}

void SunVolume::set(const geometry::Medium* medium, const geometry::HeightFog& haze)
{
    if (medium && !(medium->max_extinction() > 0.0))
        medium = nullptr;
    medium_gpu_.set(medium);
    haze_ = haze;
}

std::optional<SunVolume::Key> SunVolume::key(const glm::vec3& sun) const
{
    const geometry::Medium* medium = medium_gpu_.medium();
    if (!medium)
        return std::nullopt;
    return Key{sun_march_direction(sun), medium,           medium->grid().top.data(),
               medium->options(),        medium->detail(), resolution_};
}

bool SunVolume::stale(const glm::vec3& sun) const
{
    const std::optional<Key> k = key(sun);
    return k && !(built_ && *built_ == *k);
}

bool SunVolume::update(const glm::vec3& sun)
{
    const std::optional<Key> key = this->key(sun);
    if (!key) {
        built_.reset();
        volume_ = {};
        return false;
    }
    if (built_ && *built_ == *key)
        return false;
    const geometry::Medium* medium = key->medium;
    const glm::vec3 sun_direction = key->sun;
    const geometry::MediumGrid& g = medium->grid();
    const glm::ivec3 size(columns(g.nx, resolution_), columns(g.ny, resolution_), std::max(resolution_.levels, 2));
    if (size != size_ || !volume_) {
        volume_ = make_texture(GL_TEXTURE_3D);
        glTextureStorage3D(volume_.get(), 1, GL_RG32F, size.x, size.y, size.z);
        glTextureParameteri(volume_.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(volume_.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
            glTextureParameteri(volume_.get(), wrap, GL_CLAMP_TO_EDGE);
        size_ = size;
    }
    constexpr int grid_unit = 0;
    medium_gpu_.bind(fill_, haze_, grid_unit);
    fill_.set("u_box_min", glm::vec3(medium->bounds().min));
    fill_.set("u_box_max", glm::vec3(medium->bounds().max));
    fill_.set("u_sun_direction", sun_direction);
    fill_.set("u_steps", std::max(resolution_.steps, 1));
    fill_.use();
    glBindImageTexture(0, volume_.get(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RG32F);
    glDispatchCompute(GLuint((size.x + 7) / 8), GLuint((size.y + 7) / 8), GLuint(size.z));
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    built_ = key;
    ++updates_;
    return true;
}

void SunVolume::bind(const ShaderProgram& p, int unit, int march_steps, bool use_volume) const
{
    medium_gpu_.bind(p, haze_, unit);
    const geometry::Medium* medium = medium_gpu_.medium();
    const glm::dvec3 lo = medium ? medium->bounds().min : glm::dvec3(0.0);
    const glm::dvec3 hi = medium ? medium->bounds().max : glm::dvec3(0.0);
    p.set("u_box_min", glm::vec3(lo));
    p.set("u_box_max", glm::vec3(hi));
    p.set("u_sv_steps", std::max(march_steps, 1));
    const bool on = use_volume && ready();
    p.set("u_sv_on", int(on));
    p.set("u_sv_volume", unit + 2);
    if (on)
        glBindTextureUnit(GLuint(unit + 2), volume_.get());
}

std::vector<float> SunVolume::probe(const std::vector<glm::vec3>& points, const glm::vec3& sun, int march_steps,
                                    bool use_volume) const
{
    if (points.empty())
        return {};
    if (!probe_)
        probe_ = std::make_unique<ShaderProgram>(std::initializer_list<std::string_view>{
            "fog_partition.glsl", "froxel_common.glsl", "fog_lighting.glsl", "medium_shell.glsl", "height_fog.glsl",
            "froxel_medium.glsl", "sun_march.glsl", "sun_volume.glsl", "sun_volume_probe.comp"});
    std::vector<glm::vec4> in(points.size());
    for (std::size_t k = 0; k < points.size(); ++k)
        in[k] = glm::vec4(points[k], 1.0f);
    constexpr int unit = 0;
    bind(*probe_, unit, march_steps, use_volume);
    probe_->set("u_sun_direction", sun_march_direction(sun));
    return run_point_probe(*probe_, in.data(), in.size() * sizeof(glm::vec4), in.size());
}

}  // namespace kiri::render::detail
