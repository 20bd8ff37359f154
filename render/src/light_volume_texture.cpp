#include "light_volume_texture.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "probe_readback.hpp"

namespace kiri::render::detail {

void LightVolumeTexture::set(std::shared_ptr<const geometry::LightVolume> volume, const geometry::Medium* medium)
{
    if (volume && volume->empty())
        volume.reset();
    grid_.set(volume ? medium : nullptr);
    if (volume == volume_)
        return;
    volume_ = std::move(volume);
    ++updates_;
    texture_ = {};
    floors_ = {};
    parts_ = false;
    groups_ = 0;
    if (!volume_)
        return;
    const geometry::LightVolume& v = *volume_;
    const int moments = v.bands * v.bands, moment_groups = (moments + 3) / 4;
    // The terrain's shadow's tops share the floors' texture, and so its grid (the bake puts both on
    // one); a volume whose grids differ is read without its parts.
    const bool floors = v.floor_nx >= 2 && v.floor_ny >= 2 && v.floors.size() == std::size_t(v.floor_nx) * v.floor_ny;
    parts_ = v.has_shadow_parts() && (!floors || (v.floor_nx == v.shadow_nx && v.floor_ny == v.shadow_ny));
    groups_ = moment_groups + (parts_ ? 1 : 0);
    // Slice q nz + k: moments 4q .. 4q + 3 of level k, rows of cells (i, j); the last group's
    // unused channels 0; then the parts' L_00 (sunlit, shadowed) in a group of their own.
    std::vector<float> texels(std::size_t(groups_) * v.nz * v.ny * v.nx * 4, 0.0f);
    for (int k = 0; k < v.nz; ++k)
        for (int j = 0; j < v.ny; ++j)
            for (int i = 0; i < v.nx; ++i) {
                const std::size_t cell = (std::size_t(k) * v.ny + j) * v.nx + i;
                const double* m = &v.moments[cell * moments];
                for (int q = 0; q < moments; ++q) {
                    const std::size_t layer = std::size_t(q / 4) * v.nz + k;
                    texels[((layer * v.ny + j) * v.nx + i) * 4 + q % 4] = float(m[q]);
                }
                if (parts_) {
                    const std::size_t layer = std::size_t(moment_groups) * v.nz + k;
                    texels[((layer * v.ny + j) * v.nx + i) * 4] = float(v.class_means[cell * 2]);
                    texels[((layer * v.ny + j) * v.nx + i) * 4 + 1] = float(v.class_means[cell * 2 + 1]);
                }
            }
    texture_ = make_texture(GL_TEXTURE_3D);
    glTextureStorage3D(texture_.get(), 1, GL_RGBA32F, v.nx, v.ny, groups_ * v.nz);
    glTextureSubImage3D(texture_.get(), 0, 0, 0, 0, v.nx, v.ny, groups_ * v.nz, GL_RGBA, GL_FLOAT, texels.data());
    // Linear between cell centres, clamped to the outer ones (LightVolume::moments_at); between
    // levels too, the lookup reading within a group's nz slices only.
    glTextureParameteri(texture_.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(texture_.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(texture_.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture_.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture_.get(), GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    if (floors || parts_) {
        // Red: the floors; green: the shadow's tops.
        const int n = floors ? v.floor_nx : v.shadow_nx, m = floors ? v.floor_ny : v.shadow_ny;
        std::vector<float> samples(std::size_t(n) * m * 2, 0.0f);
        for (std::size_t s = 0; s < std::size_t(n) * m; ++s) {
            samples[s * 2] = floors ? float(v.floors[s]) : 0.0f;
            samples[s * 2 + 1] = parts_ ? float(v.shadow_tops[s]) : 0.0f;
        }
        floors_ = make_texture(GL_TEXTURE_2D);
        glTextureStorage2D(floors_.get(), 1, GL_RG32F, n, m);
        glTextureSubImage2D(floors_.get(), 0, 0, 0, n, m, GL_RG, GL_FLOAT, samples.data());
        // Fetched texel by texel (lv_floor_at interpolates as LightVolume::floor_at does).
        glTextureParameteri(floors_.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(floors_.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
}

void LightVolumeTexture::bind(const ShaderProgram& p, int unit, bool on, bool with_grid) const
{
    on = on && ready() && (!with_grid || grid_.medium() != nullptr);
    p.set("u_lv_on", int(on));
    p.set("u_lv_moments", unit);
    p.set("u_lv_floors", unit + 2);
    const bool floors = on && floors_ && volume_->floor_nx >= 2 && volume_->floor_ny >= 2;
    p.set("u_lv_floors_n", floors ? glm::ivec2(volume_->floor_nx, volume_->floor_ny) : glm::ivec2(0));
    p.set("u_lv_shadow_n", on && parts_ ? glm::ivec2(volume_->shadow_nx, volume_->shadow_ny) : glm::ivec2(0));
    p.set("u_lv_parts_group", on && parts_ ? groups_ - 1 : -1);
    p.set("u_lv_groups", std::max(groups_, 1));
    if (with_grid)
        p.set("u_md_grid", unit + 1);
    if (!on)
        return;
    if (with_grid)
        grid_.bind_grid(p, unit + 1);
    const geometry::LightVolume& v = *volume_;
    // The harmonics' norms K_l^m (sqrt(2) K_l^m for m > 0), once: geometry's
    // real_spherical_harmonics of the poles and the equator would give them too, this is plainer.
    static const std::array<float, 64> norms = [] {
        std::array<float, 64> k{};
        for (int l = 0; l < 8; ++l)
            for (int m = 0; m <= l; ++m) {
                double ratio = 1.0;  // (l - m)! / (l + m)!
                for (int q = l - m + 1; q <= l + m; ++q)
                    ratio /= q;
                k[std::size_t(l * 8 + m)] = float(std::sqrt((2.0 * l + 1.0) / (4.0 * std::numbers::pi) * ratio) *
                                                  (m > 0 ? std::numbers::sqrt2 : 1.0));
            }
        return k;
    }();
    glProgramUniform1fv(p.id(), p.location("u_lv_norms[0]"), 64, norms.data());
    p.set("u_lv_rect", glm::vec4(float(v.x0), float(v.y0), float(1.0 / (v.nx * v.dx)), float(1.0 / (v.ny * v.dy))));
    p.set("u_lv_levels", v.nz);
    p.set("u_lv_bands", v.bands);
    p.set("u_lv_column_extinction", float(v.column_extinction));
    p.set("u_lv_haze",
          v.haze_extinction > 0.0
              ? glm::vec4(float(v.haze_extinction), float(v.haze_base), float(v.haze_scale_height), float(v.haze_top))
              : glm::vec4(0.0f));
    glBindTextureUnit(GLuint(unit), texture_.get());
    if (floors_)
        glBindTextureUnit(GLuint(unit + 2), floors_.get());
}

std::vector<float> LightVolumeTexture::probe(const std::vector<Probe>& points) const
{
    if (points.empty())
        return {};
    if (!probe_)
        probe_ = std::make_unique<ShaderProgram>(std::initializer_list<std::string_view>{
            "medium_shell.glsl", "light_volume.glsl", "light_volume_probe.comp"});
    bind(*probe_, 0, true, false);  // the probes give h and the column scale themselves
    return run_point_probe(*probe_, points.data(), points.size() * sizeof(Probe), points.size());
}

}  // namespace kiri::render::detail
