// The stress suite (ctest -L stress): the froxel fog at the edges of what a scene may ask, each
// case finite, free of GL errors (GlTest's teardown) and held to the CPU reference ray marcher
// or a closed form: an empty fog, a fog of 1e4 per km (from inside, and its sunlit top from
// above), g at the edge of (-1, 1) with its
// documented clamp, coordinates near 1e7 m (drawn as at home), a fog thinner than one froxel slice, the sun on the
// horizon and below it. The layer stack with the eye on a base vertex (a patch corner) is
// layer_stack_gpu_gltest's EyeOnAVertexIsFinite.
#include <cmath>
#include <numbers>

#include "render/froxel_fixture.hpp"

namespace {

using namespace kiri::test;

// The fixture's slab over [x0 - half, x0 + half] x [y0 - half, y0 + half], coverage c.
g::Medium slab_at(double bottom, double top, double sigma, double half, glm::dvec2 origin, double coverage = 1.0,
                  double g_aniso = 0.6)
{
    g::MediumGrid grid;
    grid.nx = grid.ny = 3;
    grid.x0 = origin.x - half;
    grid.y0 = origin.y - half;
    grid.dx = grid.dy = half;
    grid.floor.assign(9, bottom);
    grid.bottom.assign(9, bottom);
    grid.top.assign(9, top);
    grid.coverage.assign(9, coverage);
    g::MediumOptions o;
    o.extinction = sigma;
    o.albedo = 0.9;
    o.anisotropy = g_aniso;
    o.top_density = 1.0;
    o.scattering_octaves = 1;
    g::MediumDetail d;
    d.detail = 0.0;
    return g::Medium(std::move(grid), o, d);
}

g::Terrain flat_ground_at(glm::dvec2 origin, double half = 2000.0, double spacing = 50.0)
{
    g::Heightfield hf;
    hf.nx = hf.ny = int(std::lround(2.0 * half / spacing)) + 1;
    hf.dx = hf.dy = spacing;
    hf.x0 = origin.x - half;
    hf.y0 = origin.y - half;
    hf.z.assign(std::size_t(hf.nx) * hf.ny, 0.0);
    hf.valid.assign(hf.z.size(), 1);
    return g::Terrain(std::move(hf));
}

Camera looking_at_slab(glm::dvec2 origin = {0.0, 0.0})
{
    Camera c;
    c.position = {origin.x, origin.y - 1800.0, 150.0};
    c.target = {origin.x, origin.y, 100.0};
    return c;
}

class Stress : public FroxelGl {};

TEST_F(Stress, EmptyFogDrawsNothing)
{
    // Coverage 0 everywhere: a legal fog with no density. Transmittance 1, no in-scattering,
    // as the closed form says.
    const g::Terrain ground = flat_ground();
    const g::Medium fog = slab_at(0.0, 300.0, 0.01, 2000.0, {0.0, 0.0}, 0.0);
    const Compared r = compare(ground, &fog, small(16, 9), looking_at_slab(), 64, 36);
    float lowest_transmittance = 1.0f, most_light = 0.0f;
    for (std::size_t k = 0; k < r.gpu.rgba.size(); k += 4) {
        lowest_transmittance = std::min(lowest_transmittance, r.gpu.rgba[k + 3]);
        most_light = std::max({most_light, r.gpu.rgba[k], r.gpu.rgba[k + 1], r.gpu.rgba[k + 2]});
    }
    EXPECT_GE(lowest_transmittance, 0.9999f);
    EXPECT_LE(most_light, 1e-5f);
    EXPECT_EQ(r.error.fog_pixels, 0);
}

TEST_F(Stress, FogOfTenThousandPerKilometre)
{
    // sigma = 10 per metre: opaque after a few decimetres; the froxels see a wall of fog.
    const g::Terrain ground = flat_ground();
    const g::Medium fog = slab_at(0.0, 300.0, 10.0, 2000.0, {0.0, 0.0});
    const Compared r = compare(ground, &fog, small(16, 9), looking_at_slab(), 64, 36);
    EXPECT_GT(r.error.fog_pixels, 64 * 36 / 4);
    EXPECT_LT(r.error.mean_transmittance_error, 0.02);  // the wall's transmittance is exact
    // The eye inside it: each ray's light is its first decimetres', under 150 m of fog whose
    // optical depth towards the sun is 3000, so the sky's alone. 0.04 % measured; 10.7 % while
    // the reference's march towards the sun stopped at an optical depth of 12, where the fitted
    // model's light scattered many times is still 2.4 % of the sun's (its cutoff now 12 over the
    // model's slowest fall, sun_scattering_decay).
    EXPECT_LT(r.error.mean_relative, 0.01);
}

TEST_F(Stress, DenseFogsSunlitTopSeenFromAbove)
{
    // From above, a fog's light comes from its sunlit skin: 1 / sigma deep, a third of a metre at
    // 3 per metre, where the march's steps are metres and its light points four steps apart. In
    // single scattering the closed form of a half-space under a flat top: albedo (pi sun
    // p(theta) / (1 + |w_z| / s_z) + ambient), w the view ray, s the sun. The reference is held to
    // it, and the froxels to the reference in each lighting model. Before, 100 m visibility
    // (0.03 per metre) was 2 % / 7 % off (single scattering / fitted), 1 per metre 40 % / 29 %,
    // 10 per metre 42 % / 66 %: the top's light was read between levels of the sun volume that
    // straddled the top, a millimetre-thin skin lit a third of a metre inside, and the share of
    // the sun drawn linear across a skin or between light points four steps apart.
    const g::Terrain ground = flat_ground();
    Camera c;
    c.position = {0.0, -900.0, 800.0};
    c.target = {0.0, 0.0, 300.0};
    const SunLight light = sun();
    const glm::dvec3 s = glm::normalize(light.direction);
    for (double sigma : {0.03, 1.0, 10.0})
        for (auto kind : {g::MultipleScattering::none, g::MultipleScattering::octaves, g::MultipleScattering::fitted}) {
            g::Medium slab = slab_at(0.0, 300.0, sigma, 2000.0, {0.0, 0.0});
            g::MediumOptions o = slab.options();
            o.multiple_scattering = kind;
            o.scattering_octaves = 3;
            const g::Medium fog(g::MediumGrid(slab.grid()), o, slab.detail());
            const Compared r = compare(ground, &fog, small(16, 9), c, 64, 36, light);
            EXPECT_GT(r.error.fog_pixels, 64 * 36 / 2) << sigma;
            // 0.05 to 0.8 % measured.
            EXPECT_LT(r.error.mean_relative, 0.015) << sigma << " " << int(kind);
            EXPECT_LT(r.error.p99_relative, 0.03) << sigma << " " << int(kind);
            if (kind != g::MultipleScattering::none)
                continue;
            const g::ReferenceView view = kiri::render::reference_view(c, 64, 36, small(16, 9).far);
            const g::AirLight air = lighting(light, small(16, 9), &fog, ground).air;  // the scene's, over its ground
            for (glm::ivec2 px : {glm::ivec2(32, 18), glm::ivec2(10, 30), glm::ivec2(55, 8)}) {
                const glm::dvec3 w = view.ray(px.x, px.y);
                const double p = g::henyey_greenstein(glm::dot(w, s), o.anisotropy);
                const glm::dvec3 skin = o.albedo *
                    (std::numbers::pi * light.color * light.intensity * p / (1.0 + std::abs(w.z) / s.z) +
                     light.ambient);
                const double haze = air.haze((c.position.z - 300.0) / std::abs(w.z));  // the air to the top
                const glm::dvec3 expected = skin * (1.0 - haze) + haze * air.radiance;
                const glm::dvec3 got = r.reference.inscatter[std::size_t(px.y) * 64 + px.x];
                for (int k = 0; k < 3; ++k)
                    EXPECT_NEAR(got[k], expected[k], 2e-3 * expected[k]) << sigma << " pixel " << px.x << ", " << px.y;
            }
        }
}

TEST_F(Stress, AnisotropyAtTheEdgeIsClampedAsDocumented)
{
    // g in (-1, 1) is accepted; both the GPU and the reference clamp it to +-0.999 (medium.hpp),
    // so g = +-0.999999 draws exactly what +-0.999 draws.
    const g::Terrain ground = flat_ground();
    SunLight light = sun();
    light.direction = {0.0, 1.0, 0.12};  // low, straight ahead: the forward peak in view
    for (double edge : {0.999999, -0.999999}) {
        const g::Medium at_edge = slab_at(0.0, 300.0, 0.004, 2000.0, {0.0, 0.0}, 1.0, edge);
        const g::Medium clamped = slab_at(0.0, 300.0, 0.004, 2000.0, {0.0, 0.0}, 1.0, edge > 0 ? 0.999 : -0.999);
        const Compared a = compare(ground, &at_edge, small(16, 9), looking_at_slab(), 64, 36, light);
        const Compared b = compare(ground, &clamped, small(16, 9), looking_at_slab(), 64, 36, light);
        ASSERT_EQ(a.gpu.rgba.size(), b.gpu.rgba.size());
        double largest = 0.0;
        for (std::size_t k = 0; k < a.gpu.rgba.size(); ++k)
            largest = std::max(largest, double(std::abs(a.gpu.rgba[k] - b.gpu.rgba[k])));
        EXPECT_EQ(largest, 0.0) << edge;
        // Under the fitted multiple scattering: 3.9 % (+g) and 1.1 % (-g) measured.
        EXPECT_LT(a.error.mean_relative, 0.05) << edge;
    }
}

TEST_F(Stress, CoordinatesNearTenMillionMetres)
{
    // The same slab and view as at the origin, moved to (1e7, 1e7): float world coordinates
    // there have a 1 m step, so the renderer must not lose the fog to them.
    const glm::dvec2 far_away(1.0e7, 1.0e7);
    const g::Terrain ground = flat_ground_at(far_away);
    const g::Medium fog = slab_at(0.0, 300.0, 0.004, 2000.0, far_away);
    const Compared moved = compare(ground, &fog, small(16, 9), looking_at_slab(far_away), 64, 36);
    const g::Terrain home_ground = flat_ground();
    const g::Medium home_fog = slab_at(0.0, 300.0, 0.004, 2000.0, {0.0, 0.0});
    const Compared home = compare(home_ground, &home_fog, small(16, 9), looking_at_slab(), 64, 36);
    // The renderer measures what it hands the GPU from the terrain's centre (Renderer::origin):
    // the fog near 1e7 m is the fog at home. Before, with float world coordinates, its edges
    // were lost to 1 m steps (1203 fog pixels and 1088 silhouettes against 2291 and 0 at home,
    // mean 2.4 % against 1.5 %). Every renderer: render_origin_gltest.
    EXPECT_NEAR(moved.error.fog_pixels, home.error.fog_pixels, 0.01 * home.error.fog_pixels);
    EXPECT_LE(moved.error.silhouette_pixels, home.error.silhouette_pixels + 5);
    EXPECT_NEAR(moved.error.mean_relative, home.error.mean_relative, 0.002);
    EXPECT_LT(moved.error.mean_relative, 0.03);
}

TEST_F(Stress, FogThinnerThanOneSlice)
{
    // 0.5 m of ground fog seen from 3 m up over 1 km: thinner than any of the 64 slices there.
    const g::Terrain ground = flat_ground(1200.0, 10.0);
    const g::Medium fog = slab_at(0.0, 0.5, 0.2, 600.0, {0.0, 0.0});
    Camera c;
    c.position = {0.0, -500.0, 3.0};
    c.target = {0.0, 0.0, 0.0};
    g::FroxelOptions o = small(16, 9);
    o.far = 1500.0;
    const Compared r = compare(ground, &fog, o, c, 64, 36);
    EXPECT_GT(r.error.fog_pixels, 64 * 36 / 4);
    EXPECT_LT(r.error.mean_relative, 0.06);  // 4.2 % measured
}

TEST_F(Stress, SunOnTheHorizonAndBelowIt)
{
    const g::Terrain ground = flat_ground();
    const g::Medium fog = slab_at(0.0, 300.0, 0.004, 2000.0, {0.0, 0.0});
    for (double z : {0.0, -0.2}) {
        SunLight light = sun();
        light.direction = {0.6, 0.8, z};
        const Compared r = compare(ground, &fog, small(16, 9), looking_at_slab(), 64, 36, light);
        EXPECT_GT(r.error.fog_pixels, 64 * 36 / 4) << z;
        // 1.4 % and 0.9 % measured. On the horizon the fog's light is its top's skin: lit where
        // a froxel's light was taken in the air above the top, 10.6 %. Below it the ground beyond
        // the grid, flat to the horizon, shadows every point: with the map of the grid alone
        // saying lit, 18.8 %.
        EXPECT_LT(r.error.mean_relative, 0.03) << z;
        EXPECT_LT(r.error.p99_relative, 0.15) << z;
    }
}

}  // namespace
