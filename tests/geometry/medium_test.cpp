// The Medium (geometry/include/kiri/geometry/medium/medium.hpp): optics conversions, the shared noise,
// the density field against its formula, and the medium of a fitted fog against its layers.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "fog_test_terrains.hpp"
#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/layers/layer_medium.hpp"
#include "kiri/geometry/medium/fog_lighting.hpp"
#include "kiri/geometry/medium/medium.hpp"
#include "kiri/geometry/scene/scene.hpp"

using namespace kiri::geometry;
using kiri::InputError;

// ---- Optics -------------------------------------------------------------------------------

TEST(MediumOptics, KoschmiederBothWays)
{
    EXPECT_DOUBLE_EQ(visibility_from_extinction(0.02), 195.6);
    EXPECT_DOUBLE_EQ(extinction_from_visibility(1000.0), 0.003912);
    for (double v : {0.5, 50.0, 200.0, 1000.0, 1e5})
        EXPECT_NEAR(visibility_from_extinction(extinction_from_visibility(v)), v, v * 1e-15);
    for (double bad : {0.0, -1.0, std::nan(""), HUGE_VAL}) {
        EXPECT_THROW(visibility_from_extinction(bad), std::invalid_argument);
        EXPECT_THROW(extinction_from_visibility(bad), std::invalid_argument);
    }
}

TEST(MediumOptics, LiquidWaterContent)
{
    // 3 Q LWC / (4 rho r), Q = 2: 0.2 g/m^3 of 7 um droplets -> 1.2 / 28 1/m.
    EXPECT_NEAR(extinction_from_liquid_water(0.2, 7.0), 1.2 / 28.0, 1e-15);
    // Linear in LWC, inverse in the radius.
    EXPECT_NEAR(extinction_from_liquid_water(0.4, 7.0), 2.0 * extinction_from_liquid_water(0.2, 7.0), 1e-15);
    EXPECT_NEAR(extinction_from_liquid_water(0.2, 14.0), 0.5 * extinction_from_liquid_water(0.2, 7.0), 1e-15);
    // Real fog ([ValleyFog]): 0.05..0.5 g/m^3 and 4..10 um give visibilities of fog (< 1 km).
    EXPECT_LT(visibility_from_extinction(extinction_from_liquid_water(0.05, 10.0)), 1000.0);
    EXPECT_THROW(extinction_from_liquid_water(0.0, 7.0), std::invalid_argument);
    EXPECT_THROW(extinction_from_liquid_water(0.2, -1.0), std::invalid_argument);
}

TEST(MediumOptics, HenyeyGreensteinIsANormalisedPhase)
{
    const double pi = std::numbers::pi;
    EXPECT_DOUBLE_EQ(henyey_greenstein(0.3, 0.0), 1.0 / (4.0 * pi));
    // (1 - g^2) / (4 pi (1 + g^2 - 2 g c)^1.5) at c = 1: (1 + g) / (4 pi (1 - g)^2).
    EXPECT_NEAR(henyey_greenstein(1.0, 0.8), 1.8 / (4.0 * pi * 0.04), 1e-12);
    for (double g : {-0.9, -0.3, 0.0, 0.5, 0.8, 0.9}) {
        // Integral over the sphere = 2 pi int_{-1}^{1} p(c) dc (Simpson, 20000 intervals).
        const int n = 20000;
        double sum = 0.0;
        for (int k = 0; k <= n; ++k) {
            const double c = -1.0 + 2.0 * k / n;
            sum += (k == 0 || k == n ? 1.0 : k % 2 ? 4.0 : 2.0) * henyey_greenstein(c, g);
        }
        EXPECT_NEAR(2.0 * pi * sum * (2.0 / n) / 3.0, 1.0, 1e-6) << g;
        // Mean cosine = g.
        double mean = 0.0;
        for (int k = 0; k <= n; ++k) {
            const double c = -1.0 + 2.0 * k / n;
            mean += (k == 0 || k == n ? 1.0 : k % 2 ? 4.0 : 2.0) * c * henyey_greenstein(c, g);
        }
        EXPECT_NEAR(2.0 * pi * mean * (2.0 / n) / 3.0, g, 1e-6) << g;
    }
    // |g| -> 1 is clamped: finite at theta = 0.
    EXPECT_TRUE(std::isfinite(henyey_greenstein(1.0, 1.0)));
    EXPECT_TRUE(std::isfinite(henyey_greenstein(-1.0, -1.0)));
    EXPECT_TRUE(std::isfinite(henyey_greenstein(std::nan(""), 0.5)));
    EXPECT_TRUE(std::isfinite(henyey_greenstein(0.5, std::nan(""))));
}

// ---- The shared noise ------------------------------------------------------------------------

TEST(FogNoise, SampledLikeGlLinearRepeat)
{
    const int size = 64;
    const std::vector<float>& tile = fog_noise_tile(size);
    ASSERT_EQ(tile.size(), std::size_t(size * size));
    // Texel centres give the texel; midway between two gives their mean; the tile repeats.
    for (int j : {0, 7, 63})
        for (int i : {0, 30, 63}) {
            const double s = (i + 0.5) / size, t = (j + 0.5) / size;
            const double v = tile[std::size_t(j) * size + i];
            EXPECT_NEAR(sample_fog_noise(s, t, size), v, 1e-12);
            EXPECT_NEAR(sample_fog_noise(s + 3.0, t - 5.0, size), v, 1e-9);
            const double right = tile[std::size_t(j) * size + (i + 1) % size];
            EXPECT_NEAR(sample_fog_noise(s + 0.5 / size, t, size), 0.5 * (v + right), 1e-9);
        }
    for (float v : tile)
        ASSERT_TRUE(v >= 0.0f && v <= 1.0f);
    // Deterministic: a second call returns the same tile.
    EXPECT_EQ(&fog_noise_tile(size), &tile);
    EXPECT_EQ(sample_fog_noise(std::nan(""), 0.0, size), 0.5);
}

// ---- The density field ------------------------------------------------------------------------

namespace {

// A 3 x 3 grid 100 m apart: ground 150, shell from 100 to 300, full coverage.
MediumGrid slab(double ground = 150.0)
{
    MediumGrid g;
    g.nx = g.ny = 3;
    g.x0 = g.y0 = 0.0;
    g.dx = g.dy = 100.0;
    g.bottom.assign(9, 100.0);
    g.top.assign(9, 300.0);
    g.floor.assign(9, std::max(100.0, ground));
    g.coverage.assign(9, 1.0);
    return g;
}

MediumDetail plain()
{
    MediumDetail d;
    d.detail = 0.0;
    return d;
}

}  // namespace

TEST(Medium, DensityFollowsTheLayerProfile)
{
    MediumOptions o;
    o.extinction = 0.05;
    o.top_density = 0.1;
    const Medium m(slab(), o, plain());
    // Below the floor (ground 150), above the top, outside the grid: nothing.
    EXPECT_EQ(m.density({50, 50, 149.9}), 0.0);
    EXPECT_EQ(m.density({50, 50, 300.1}), 0.0);
    EXPECT_EQ(m.density({-1, 50, 200}), 0.0);
    EXPECT_EQ(m.density({50, 201, 200}), 0.0);
    // Inside: 1 - 0.9 h with h from the shell's bottom (100), not the floor.
    for (double z : {150.0, 180.0, 250.0, 300.0}) {
        const double h = (z - 100.0) / 200.0;
        EXPECT_NEAR(m.density({120, 80, z}), 1.0 - 0.9 * h, 1e-15) << z;
        EXPECT_NEAR(m.extinction({120, 80, z}), 0.05 * (1.0 - 0.9 * h), 1e-15);
        EXPECT_NEAR(m.scattering({120, 80, z}), 0.99 * 0.05 * (1.0 - 0.9 * h), 1e-15);
    }
    // Equal to the layers' alpha (2.7) at layer i of 15 over the same shell (ground below it).
    const Medium low(slab(0.0), o, plain());
    for (int i = 0; i <= 15; ++i)
        EXPECT_NEAR(low.density({100, 100, 100.0 + 200.0 * i / 15.0}), layer_alpha(i, 15), 1e-14) << i;
    EXPECT_DOUBLE_EQ(m.max_extinction(), 0.05);
    EXPECT_EQ(m.bounds().min.z, 150.0);
    EXPECT_EQ(m.bounds().max.z, 300.0);
    EXPECT_EQ(m.bounds().max.x, 200.0);
    // Shell volume: 200 m x 200 m x 150 m between the floor and the top.
    EXPECT_NEAR(m.shell_volume(), 200.0 * 200.0 * 150.0, 1e-6);
    // Non-finite points have no fog, never NaN.
    EXPECT_EQ(m.density({std::nan(""), 0, 200}), 0.0);
    EXPECT_EQ(m.density({50, 50, std::nan("")}), 0.0);
}

TEST(Medium, CoverageAndHeightsAreBilinear)
{
    MediumGrid g = slab(0.0);
    g.coverage = {0, 0, 0, 0, 1, 0, 0, 0, 0};  // only the centre sample
    g.top[4] = 500.0;
    const Medium m(g, MediumOptions{}, plain());
    const MediumColumn c = m.column(150, 100);  // half way from the centre to the east sample
    EXPECT_NEAR(c.coverage, 0.5, 1e-15);
    EXPECT_NEAR(c.top, 400.0, 1e-12);
    EXPECT_NEAR(c.bottom, 100.0, 1e-12);
    // Density scales with coverage; h uses the interpolated top.
    EXPECT_NEAR(m.density({150, 100, 250}), 0.5 * (1.0 - 0.9 * 150.0 / 300.0), 1e-15);
    EXPECT_NEAR(m.shell_volume(), 1.0 * 400.0 * 100.0 * 100.0, 1e-6);  // one interior sample, weight 1
}

TEST(Medium, DetailAndDissipationStayInTheirRanges)
{
    MediumDetail d;
    d.detail = 0.6;
    d.detail_scale = 300.0;
    d.dissipation_half_life = 600.0;
    d.time = 600.0;
    d.wind = {5.0, -2.0};
    Medium m(slab(0.0), MediumOptions{}, d);
    // 0.5^(t / T (1 + h)): a half at the bottom, a quarter at the top.
    EXPECT_NEAR(m.dissipation(0.0), 0.5, 1e-15);
    EXPECT_NEAR(m.dissipation(1.0), 0.25, 1e-15);
    double lo = 1.0, hi = 0.0;
    for (int k = 0; k < 400; ++k) {
        const double f = m.detail_factor(k * 7.3, k * 3.1, (k % 10) / 10.0);
        lo = std::min(lo, f);
        hi = std::max(hi, f);
    }
    EXPECT_GE(lo, 0.4 - 1e-15);
    EXPECT_LE(hi, 1.0);
    EXPECT_LT(lo, 0.7);  // the noise does vary
    EXPECT_GT(hi, 0.9);
    // Wind drift: the pattern at time t + 10 s is the pattern at t moved by wind * 10 s.
    const double before = m.detail_factor(40.0, 60.0, 0.3);
    m.set_time(610.0);
    EXPECT_NEAR(m.detail_factor(90.0, 40.0, 0.3), before, 1e-12);
    EXPECT_LE(m.max_extinction(), MediumOptions{}.extinction);
}

TEST(Medium, RefusesBadGridsAndOptions)
{
    MediumGrid g = slab();
    g.top.pop_back();
    EXPECT_THROW(Medium(g, MediumOptions{}, plain()), InputError);
    MediumOptions o;
    o.anisotropy = 1.0;
    EXPECT_THROW(validate_medium_options(o, "s.json"), InputError);
    o = {};
    o.extinction = 0.0;
    EXPECT_THROW(validate_medium_options(o), InputError);
    o = {};
    o.albedo = 1.5;
    EXPECT_THROW(validate_medium_options(o), InputError);
}

// ---- The medium of a fitted fog ------------------------------------------------------------------

TEST(Medium, OfAFittedFogFollowsItsLayers)
{
    const Terrain terrain{kiri::test::make_heightfield(101, 101, 20.0, -1000.0, -1000.0, kiri::test::hills)};
    BaseSurface surface(build_control_mesh({{{-900, -850}, {880, -700}, {700, 800}, {-600, 650}}}, terrain, {250.0}),
                        SurfaceKind::gregory);
    surface.fit(terrain, FitOptions{});
    const Tessellation tess = tessellate(surface, {6});
    LayerOptions layers;
    layers.count = 10;
    layers.thickness = 150.0;
    MediumOptions smooth;
    smooth.detail = 0.0;
    const LayerBase base = make_layer_base(surface, tess, layers);
    const Medium m = make_medium(base, layers, terrain, smooth);
    const MediumGrid& g = m.grid();
    EXPECT_EQ(g.dx, 20.0);  // the terrain's spacing
    // Every base vertex away from the border: the grid's bottom is the base within the
    // interpolation error of a smooth surface at 20 m, the top one thickness above, full coverage.
    int inside = 0;
    double worst = 0.0;
    for (std::size_t v = 0; v < base.position.size(); ++v) {
        const glm::dvec3 p = base.position[v];
        const MediumColumn c = m.column(p.x, p.y);
        if (c.coverage < 0.999)
            continue;
        ++inside;
        worst = std::max(worst, std::abs(c.bottom - p.z));
        EXPECT_NEAR(c.top - c.bottom, 150.0, 1e-9);
        EXPECT_GE(c.floor, c.bottom - 1e-9);
        EXPECT_GE(c.floor + 1e-9, std::min(terrain.height(p.x, p.y), c.top) - 5.0);  // bilinear ground
    }
    EXPECT_GT(inside, 200);
    EXPECT_LT(worst, 1.0);
    // Outside the footprint's polygon: no fog.
    EXPECT_EQ(m.column(-990, 990).coverage, 0.0);
    EXPECT_EQ(m.density({-990, 990, 500}), 0.0);
    // Every sample with fog has its floor on or above the ground there.
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
            const std::size_t k = std::size_t(j) * g.nx + i;
            ASSERT_TRUE(std::isfinite(g.floor[k]) && std::isfinite(g.top[k]) && std::isfinite(g.bottom[k]));
            if (g.coverage[k] > 0.0) {
                ASSERT_GE(g.floor[k], std::min(terrain.height(g.x0 + i * g.dx, g.y0 + j * g.dy), g.top[k]) - 1e-9);
            }
        }
    EXPECT_GT(m.shell_volume(), 0.0);
}

TEST(MediumJson, UnitsAndRefusals)
{
    const std::string head = R"({"terrain": {"path": "t.tif"}, "medium": )";
    auto parse = [&](const std::string& medium) { return parse_scene(head + medium + "}", "s.json", "."); };
    EXPECT_NEAR(parse(R"({"visibility": 200})").medium.extinction, 3.912 / 200.0, 1e-18);
    EXPECT_NEAR(parse(R"({"liquid_water_content": 0.2, "droplet_radius": 7})").medium.extinction, 1.2 / 28.0, 1e-15);
    EXPECT_NEAR(parse(R"({"liquid_water_content": 0.2})").medium.extinction, 1.2 / 28.0, 1e-15);
    const Scene s = parse(R"({"extinction": 0.031, "albedo": 0.9, "anisotropy": -0.2, "top_density": 0.5})");
    EXPECT_EQ(s.medium.extinction, 0.031);
    EXPECT_EQ(s.medium.anisotropy, -0.2);
    const Scene back = parse_scene(scene_to_json(s), "s.json", ".");
    EXPECT_EQ(back.medium.extinction, 0.031);
    EXPECT_EQ(back.medium.albedo, 0.9);
    EXPECT_EQ(back.medium.top_density, 0.5);
    auto refused = [&](const std::string& medium, const std::string& pointer) {
        try {
            parse(medium);
            ADD_FAILURE() << medium;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(pointer), std::string::npos) << e.what();
        }
    };
    refused(R"({"extinction": 0.02, "visibility": 100})", "/medium");
    refused(R"({"visibility": 0})", "/medium/visibility");
    refused(R"({"anisotropy": 1})", "/medium/anisotropy");
    refused(R"({"albedo": -0.1})", "/medium/albedo");
    refused(R"({"droplet_radius": 5})", "/medium/droplet_radius");
    refused(R"({"extinction": 1e9})", "/medium");
    refused(R"({"fog_colour": 1})", "/medium/fog_colour");
    refused(R"([1, 2])", "/medium");
}

// ---- The lighting model ------------------------------------------------------------------------

TEST(FogLighting, OctavesOfScattering)
{
    const FogLight light{{3.0, 2.0, 1.0}, {0.2, 0.3, 0.4}};
    MediumOptions o;
    o.albedo = 0.9;
    o.anisotropy = 0.8;
    o.multiple_scattering = MultipleScattering::octaves;
    o.scattering_octaves = 1;  // plain single scattering
    const double pi = std::numbers::pi;
    const glm::dvec3 single = fog_source(light, o, 0.3, 2.0);
    const double s1 = pi * henyey_greenstein(0.3, 0.8) * std::exp(-2.0);
    EXPECT_NEAR(single.x, 0.9 * (3.0 * s1 + 0.2), 1e-15);
    EXPECT_NEAR(single.z, 0.9 * (1.0 * s1 + 0.4), 1e-15);
    o.scattering_octaves = 3;
    const double s3 = pi *
        (henyey_greenstein(0.3, 0.8) * std::exp(-2.0) + 0.5 * henyey_greenstein(0.3, 0.4) * std::exp(-1.0) +
         0.25 * henyey_greenstein(0.3, 0.2) * std::exp(-0.5));
    EXPECT_NEAR(fog_source(light, o, 0.3, 2.0).y, 0.9 * (2.0 * s3 + 0.3), 1e-15);
    // In the terrain's shadow only the sky lights the fog; non-finite inputs stay finite.
    EXPECT_NEAR(fog_source(light, o, 0.3, 2.0, 0.0).x, 0.9 * 0.2, 1e-15);
    for (const glm::dvec3 j : {fog_source(light, o, std::nan(""), 1.0), fog_source(light, o, 0.5, HUGE_VAL),
                               fog_source(light, o, 0.5, std::nan("")), fog_source(light, o, 1.0, -5.0, 2.0)})
        EXPECT_TRUE(std::isfinite(j.x) && std::isfinite(j.y) && std::isfinite(j.z) && j.x >= 0.0);
    // Deep in the fog (tau_sun large) the octaves carry the light further than single scattering.
    MediumOptions one = o;
    one.scattering_octaves = 1;
    EXPECT_GT(fog_source(light, o, -0.5, 6.0).x - 0.9 * 0.2, 10.0 * (fog_source(light, one, -0.5, 6.0).x - 0.9 * 0.2));
}
