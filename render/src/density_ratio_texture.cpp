#include "density_ratio_texture.hpp"

#include "kiri/geometry/medium/medium.hpp"
#include "kiri/geometry/particles/particle_footprint.hpp"
#include "kiri/geometry/particles/particles.hpp"

namespace kiri::render::detail {

void DensityRatioTexture::update(const geometry::ParticleCloud& cloud, std::uint64_t cloud_hash,
                                 const geometry::Medium* medium, const glm::dvec3& centre)
{
    if (built_ && medium == medium_ && cloud_hash == hash_)
        return;
    built_ = true;
    medium_ = medium;
    hash_ = cloud_hash;
    ready_ = false;
    if (!medium)
        return;
    const geometry::DensityRatioGrid g = geometry::density_ratio_grid(cloud, *medium);
    if (g.empty())
        return;
    ratio_ = make_texture(GL_TEXTURE_3D);
    glTextureStorage3D(ratio_.get(), 1, GL_R32F, g.nx, g.ny, g.levels);
    glTextureSubImage3D(ratio_.get(), 0, 0, 0, 0, g.nx, g.ny, g.levels, GL_RED, GL_FLOAT, g.balls.data());
    glTextureParameteri(ratio_.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(ratio_.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        glTextureParameteri(ratio_.get(), wrap, GL_CLAMP_TO_EDGE);
    xy_ = glm::vec4(float(g.x0 - centre.x), float(g.y0 - centre.y), float(1.0 / (g.nx * g.dx)),
                    float(1.0 / (g.ny * g.dy)));
    max_ratio_ = float(g.max_ratio);
    ready_ = true;
}

void DensityRatioTexture::bind(const ShaderProgram& p, int unit) const
{
    p.set("u_ratio", unit);
    p.set("u_ratio_xy", xy_);
    p.set("u_ratio_max", max_ratio_);
    // A billboard widened beyond its ball draws its footprint's mass: R is the Medium over the
    // balls' mass, which is less (geometry::ball_mass).
    p.set("u_ratio_footprint", float(geometry::ball_mass() / geometry::footprint_area()));
    if (ready_)
        glBindTextureUnit(GLuint(unit), ratio_.get());
}

}  // namespace kiri::render::detail
