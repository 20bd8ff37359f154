// The baked light-transport volume as the renderers read it (render/src/light_volume_texture.hpp,
// light_volume.glsl) against geometry::LightVolume::in_scattered, the CPU reference's lookup:
// the moments trilinear between cell centres (clamped to the outer ones), the real harmonics and
// g^l of every band, the column scale, and the sunlit and shadowed parts' L_00 on each side of the
// terrain's shadow's tops (LightVolume::in_scattered_at). Read back through a compute probe.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "kiri/geometry/medium/light_volume.hpp"
#include "light_volume_texture.hpp"
#include "render/render_fixture.hpp"

namespace {

namespace g = kiri::geometry;
using kiri::render::detail::LightVolumeTexture;

class LightVolumeGpu : public kiri::test::GlTest {};

// Moments of a plausible diffuse light: a positive mean (l = 0) and smaller higher bands, all
// different from cell to cell.
std::shared_ptr<g::LightVolume> random_volume(int bands, std::uint32_t seed)
{
    auto v = std::make_shared<g::LightVolume>();
    v->nx = 5;
    v->ny = 4;
    v->nz = 3;
    v->bands = bands;
    v->x0 = -250.0;
    v->y0 = 100.0;
    v->dx = 100.0;
    v->dy = 150.0;
    v->column_extinction = 0.01;
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const int nc = bands * bands;
    v->moments.resize(std::size_t(v->nx) * v->ny * v->nz * nc);
    for (std::size_t c = 0; c < v->moments.size(); c += std::size_t(nc))
        for (int q = 0; q < nc; ++q)
            v->moments[c + std::size_t(q)] = q == 0 ? 2.0 + u(random) : 0.4 * u(random) / (1.0 + std::sqrt(q));
    return v;
}

// The terrain's shadow over the volume: random tops on the shadow's grid (four samples a cell, the
// fewest the bake takes) between 0 and 100 m, and each cell's parts' L_00 a random share of the cell's.
void add_random_parts(g::LightVolume& v, std::uint32_t seed)
{
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    v.shadow_nx = 4 * v.nx + 1;
    v.shadow_ny = 4 * v.ny + 1;
    for (int k = 0; k < v.shadow_nx * v.shadow_ny; ++k)
        v.shadow_tops.push_back(100.0 * u(random));
    const int nc = v.bands * v.bands;
    for (std::size_t c = 0; c < std::size_t(v.nx) * v.ny * v.nz; ++c) {
        v.class_means.push_back(v.moments[c * nc] * (0.5 + u(random)));
        v.class_means.push_back(v.moments[c * nc] * 0.1 * u(random));
    }
}

void expect_gpu_equals_cpu(int bands, bool parts = false)
{
    const auto volume = random_volume(bands, 17u + std::uint32_t(bands));
    if (parts) {
        add_random_parts(*volume, 5u + std::uint32_t(bands));
        ASSERT_TRUE(volume->has_shadow_parts());
    }
    LightVolumeTexture texture;
    texture.set(volume, nullptr);
    ASSERT_TRUE(texture.ready());
    std::mt19937 random(3);
    std::uniform_real_distribution<double> x(-400.0, 400.0), y(0.0, 800.0), unit(0.0, 1.0), sym(-1.0, 1.0);
    std::vector<LightVolumeTexture::Probe> probes;
    std::vector<double> expected;
    for (int k = 0; k < 2000; ++k) {
        LightVolumeTexture::Probe p;
        // Inside the grid and beyond it (clamped to the outer cells), h from the floor to the top.
        p.xyh = glm::vec3(float(x(random)), float(y(random)), float(unit(random)));
        p.scale = float(0.05 + unit(random));
        glm::dvec3 d(sym(random), sym(random), sym(random));
        if (glm::length(d) < 1e-3)
            d = {0.0, 0.0, 1.0};
        p.towards = glm::vec3(glm::normalize(d));
        p.g = float(k % 7 == 0 ? 0.0 : 0.95 * sym(random));
        p.z = float(120.0 * unit(random) - 10.0);
        p.parts = parts ? 1.0f : 0.0f;
        probes.push_back(p);
        std::vector<double> weights(std::size_t(bands * bands));
        volume->phase_weights(glm::dvec3(p.towards), p.g, weights.data());
        expected.push_back(parts
                               ? volume->in_scattered_at(p.xyh.x, p.xyh.y, p.z, p.xyh.z, weights.data(), p.scale)
                               : volume->in_scattered(p.xyh.x, p.xyh.y, p.xyh.z, glm::dvec3(p.towards), p.g, p.scale));
    }
    const std::vector<float> got = texture.probe(probes);
    ASSERT_EQ(got.size(), expected.size());
    double worst = 0.0, scale = 0.0;
    for (double e : expected)
        scale = std::max(scale, e);
    ASSERT_GT(scale, 0.5);
    for (std::size_t k = 0; k < got.size(); ++k) {
        ASSERT_TRUE(std::isfinite(got[k])) << k;
        worst = std::max(worst, std::abs(got[k] - expected[k]));
    }
    std::printf("    %d bands: largest difference %.3g of values up to %.3g\n", bands, worst, scale);
    // Float moments and weights against double: a few parts in a million of the largest value.
    EXPECT_LT(worst, 1e-4 * scale) << bands << " bands";
}

TEST_F(LightVolumeGpu, EveryBandAsTheCpuLookupTakesIt)
{
    for (int bands : {1, 2, 6, 8})
        expect_gpu_equals_cpu(bands);
}

TEST_F(LightVolumeGpu, EachPartOfTheTerrainsShadowAsTheCpuLookupTakesIt)
{
    for (int bands : {1, 8})
        expect_gpu_equals_cpu(bands, true);
}

TEST_F(LightVolumeGpu, NoVolumeAddsNothing)
{
    LightVolumeTexture texture;
    texture.set(nullptr, nullptr);
    EXPECT_FALSE(texture.ready());
    const std::vector<float> got =
        texture.probe({LightVolumeTexture::Probe{{0.0f, 0.0f, 0.5f}, 1.0f, {0, 0, 1}, 0.5f, 0.0f, 0.0f, {}}});
    ASSERT_EQ(got.size(), 1u);
    EXPECT_EQ(got[0], 0.0f);
    // An empty volume is no volume.
    texture.set(std::make_shared<g::LightVolume>(), nullptr);
    EXPECT_FALSE(texture.ready());
}

}  // namespace
