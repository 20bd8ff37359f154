#include "froxel_medium.hpp"

#include "render_origin.hpp"

#include <algorithm>
#include <vector>

#include "kiri/geometry/medium/medium.hpp"

namespace kiri::render::detail {
namespace {
constexpr int noise_size = 256;  // the tile geometry::Medium samples
}

FroxelMedium::FroxelMedium() : noise_(make_texture(GL_TEXTURE_2D))
{
    // Float, not the layers' 8-bit copy: the density agrees with the reference to float precision.
    const std::vector<float>& tile = geometry::fog_noise_tile(noise_size);
    glTextureStorage2D(noise_.get(), 1, GL_R32F, noise_size, noise_size);
    glTextureSubImage2D(noise_.get(), 0, 0, 0, noise_size, noise_size, GL_RED, GL_FLOAT, tile.data());
    glTextureParameteri(noise_.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(noise_.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(noise_.get(), GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(noise_.get(), GL_TEXTURE_WRAP_T, GL_REPEAT);
}

bool FroxelMedium::set(const geometry::Medium* medium)
{
    medium_ = medium;
    if (!medium || medium->grid().nx < 2) {
        uploaded_ = nullptr;
        return false;
    }
    const geometry::MediumGrid& g = medium->grid();
    if (uploaded_ == g.top.data() && grid_)
        return false;
    std::vector<float> texels(std::size_t(g.nx) * g.ny * 4);
    for (std::size_t k = 0; k < std::size_t(g.nx) * g.ny; ++k) {
        texels[4 * k + 0] = float(g.floor[k]);
        texels[4 * k + 1] = float(g.bottom[k]);
        texels[4 * k + 2] = float(g.top[k]);
        texels[4 * k + 3] = float(g.coverage[k]);
    }
    grid_ = make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(grid_.get(), 1, GL_RGBA32F, g.nx, g.ny);
    glTextureSubImage2D(grid_.get(), 0, 0, 0, g.nx, g.ny, GL_RGBA, GL_FLOAT, texels.data());
    glTextureParameteri(grid_.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(grid_.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(grid_.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(grid_.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    uploaded_ = g.top.data();
    return true;
}

void FroxelMedium::bind_height_fog(const ShaderProgram& p, const geometry::HeightFog& haze)
{
    p.set("u_hf",
          glm::vec4(float(haze.enabled() ? haze.extinction : 0.0), float(haze.base), float(haze.scale_height), 0.0f));
    const auto bounded = [](double v) { return float(std::clamp(v, -1e30, 1e30)); };
    p.set("u_hf_extent", glm::vec4(bounded(haze.min.x), bounded(haze.min.y), bounded(haze.max.x), bounded(haze.max.y)));
}

bool FroxelMedium::bind_grid(const ShaderProgram& p, int unit) const
{
    if (!medium_ || !uploaded_)
        return false;
    const geometry::MediumGrid& g = medium_->grid();
    p.set("u_md_grid", unit);
    p.set("u_md_origin", glm::vec2(float(g.x0), float(g.y0)));
    p.set("u_md_last", glm::vec2(float(g.x0 + (g.nx - 1) * g.dx), float(g.y0 + (g.ny - 1) * g.dy)));
    p.set("u_md_cells", glm::vec2(float(g.nx), float(g.ny)));
    p.set("u_md_ceiling", float(medium_->bounds().max.z));
    glBindTextureUnit(GLuint(unit), grid_.get());
    return true;
}

void FroxelMedium::bind(const ShaderProgram& p, const geometry::HeightFog& haze, int unit) const
{
    bind_height_fog(p, haze);
    const bool on = medium_ && uploaded_ && medium_->max_extinction() > 0.0;
    p.set("u_md_on", int(on));
    p.set("u_partitioned", int(partitioned_));
    p.set("u_partition", partition_);
    p.set("u_partition_depth", partition_depth_);
    if (!on)
        return;
    const geometry::MediumOptions& o = medium_->options();
    const geometry::MediumDetail& d = medium_->detail();
    bind_grid(p, unit);
    p.set("u_md_noise", unit + 1);
    p.set("u_md_extinction", float(o.extinction));
    p.set("u_md_top_density", float(o.top_density));
    p.set("u_md_detail", float(d.detail));
    p.set("u_md_tile", float(8.0 * d.detail_scale));
    p.set("u_md_layers", float(d.layers));
    p.set("u_md_drift", glm::vec2(noise_drift(d.wind, d.time, d.noise_shift, 8.0 * d.detail_scale)));
    p.set("u_md_time", float(d.time));
    p.set("u_md_half_life", float(d.dissipation_half_life));
    glBindTextureUnit(GLuint(unit + 1), noise_.get());
}

}  // namespace kiri::render::detail
