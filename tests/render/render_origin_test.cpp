// The renderer's origin (render/src/render_origin.hpp) without GL: which origin a scene gets,
// the noise's drift reduced to one tile, and every moved copy the same fog at the moved point.
#include <gtest/gtest.h>

#include <cmath>

#include "render_origin.hpp"

namespace {

namespace g = kiri::geometry;
using kiri::render::detail::moved;
using kiri::render::detail::noise_drift;
using kiri::render::detail::render_origin_for;

g::Medium noisy_slab(glm::dvec2 centre)
{
    g::MediumGrid grid;
    grid.nx = grid.ny = 5;
    grid.dx = grid.dy = 250.0;
    grid.x0 = centre.x - 500.0;
    grid.y0 = centre.y - 500.0;
    for (int k = 0; k < 25; ++k) {
        grid.floor.push_back(10.0 + k);
        grid.bottom.push_back(10.0 + k);
        grid.top.push_back(150.0 + 3.0 * k);
        grid.coverage.push_back(k % 7 == 0 ? 0.5 : 1.0);
    }
    g::MediumOptions o;
    o.extinction = 0.01;
    o.detail = 0.6;
    o.detail_scale = 300.0;
    o.wind = {3.0, -2.0};
    o.time = 1234.5;
    return g::Medium(std::move(grid), o, g::medium_detail(o));
}

TEST(RenderOrigin, ZeroNearTheWorldsOriginElseTheCentreToTheKilometre)
{
    EXPECT_EQ(render_origin_for({{-30000.0, -20000.0, 0.0}, {30000.0, 20000.0, 900.0}}), glm::dvec3(0.0));
    EXPECT_EQ(render_origin_for({{60000.0, 0.0, 0.0}, {70000.0, 10.0, 0.0}}), glm::dvec3(0.0));  // centre 65 km
    EXPECT_EQ(render_origin_for({{1e7 - 2000.0, 1e7 - 1400.0, 0.0}, {1e7 + 2600.0, 1e7 + 1400.0, 50.0}}),
              glm::dvec3(1e7, 1e7, 0.0));
    EXPECT_EQ(render_origin_for({{-7.3e6, 1000.0, 0.0}, {-7.3e6 + 900.0, 1000.0, 0.0}}),
              glm::dvec3(-7.3e6, 1000.0, 0.0));
    // An empty or broken box keeps the origin.
    const double inf = INFINITY;
    EXPECT_EQ(render_origin_for({{-inf, -inf, 0.0}, {inf, inf, 0.0}}), glm::dvec3(0.0));
}

TEST(RenderOrigin, TheNoisesDriftIsReducedToOneTile)
{
    // The noise repeats every tile: the drift the shaders subtract keeps its value modulo the
    // tile, within [0, tile), whatever the time or the shift.
    const double tile = 2400.0;
    for (const glm::dvec2 shift : {glm::dvec2(0.0), glm::dvec2(1e7, -1e7), glm::dvec2(-3.5e6, 12.25)})
        for (const double time : {0.0, 3600.0, 1e6}) {
            const glm::dvec2 wind(3.0, -2.0);
            const glm::dvec2 d = noise_drift(wind, time, shift, tile), plain = wind * time - shift;
            for (int axis = 0; axis < 2; ++axis) {
                EXPECT_GE(d[axis], 0.0);
                EXPECT_LT(d[axis], tile);
                const double turns = (plain[axis] - d[axis]) / tile;
                EXPECT_NEAR(turns, std::round(turns), 1e-9) << shift.x << " " << time;
            }
        }
    EXPECT_EQ(noise_drift({1.0, 1.0}, NAN, {0.0, 0.0}, 100.0), glm::dvec2(0.0));
    EXPECT_EQ(noise_drift({1.0, 1.0}, 1.0, {0.0, 0.0}, 0.0), glm::dvec2(0.0));
}

TEST(RenderOrigin, AMovedMediumIsTheSameFogAtTheMovedPoint)
{
    // Density, noise included, and columns: the moved copy at p - origin equals the Medium at
    // p. Without the noise's shift the noise would be that of another place (the check fails).
    const glm::dvec2 centre(1e7 + 250.0, 1e7 - 130.0);
    const g::Medium world = noisy_slab(centre);
    const glm::dvec3 origin = render_origin_for(world.bounds());
    ASSERT_EQ(origin, glm::dvec3(1e7, 1e7, 0.0));
    const g::Medium local = moved(world, origin);
    int compared = 0;
    for (int i = 0; i <= 20; ++i)
        for (int j = 0; j <= 20; ++j)
            for (const double z : {20.0, 80.0, 140.0}) {
                const glm::dvec3 p(centre.x - 500.0 + 50.0 * i, centre.y - 500.0 + 50.0 * j, z);
                const double expected = world.density(p);
                EXPECT_NEAR(local.density(p - origin), expected, 1e-9 * (1.0 + expected)) << p.x << " " << p.y;
                compared += expected > 0.0;
                const g::MediumColumn a = world.column(p.x, p.y), b = local.column(p.x - origin.x, p.y - origin.y);
                EXPECT_DOUBLE_EQ(a.top, b.top);
                EXPECT_DOUBLE_EQ(a.coverage, b.coverage);
            }
    EXPECT_GT(compared, 500);
    EXPECT_EQ(local.bounds().min.x, world.bounds().min.x - origin.x);
}

TEST(RenderOrigin, EveryMovedCopyMovesByMinusTheOrigin)
{
    const glm::dvec3 origin(1e7, -2e6, 0.0);
    g::Heightfield hf;
    hf.nx = hf.ny = 2;
    hf.x0 = 1e7 - 10.0;
    hf.y0 = -2e6 + 5.0;
    hf.z = {1.0, 2.0, 3.0, 4.0};
    const g::Heightfield h = moved(hf, origin);
    EXPECT_EQ(h.x0, -10.0);
    EXPECT_EQ(h.y0, 5.0);
    EXPECT_EQ(h.z, hf.z);

    g::HeightFog haze;
    haze.base = 40.0;
    const g::HeightFog everywhere = moved(haze, origin);
    EXPECT_TRUE(std::isinf(everywhere.min.x) && everywhere.min.x < 0.0);
    EXPECT_TRUE(std::isinf(everywhere.max.y) && everywhere.max.y > 0.0);
    haze.min = {1e7 - 500.0, -2e6 - 500.0};
    haze.max = {1e7 + 500.0, -2e6 + 500.0};
    const g::HeightFog boxed = moved(haze, origin);
    EXPECT_EQ(boxed.min, glm::dvec2(-500.0, -500.0));
    EXPECT_EQ(boxed.max, glm::dvec2(500.0, 500.0));
    EXPECT_EQ(boxed.base, 40.0);

    g::ParticleCloud cloud;
    cloud.particles.push_back({{1e7 + 1.5, -2e6 - 2.5, 80.0}, 3.0, 0.5, 0.9});
    EXPECT_EQ(moved(cloud, origin).particles[0].position, glm::dvec3(1.5, -2.5, 80.0));

    g::LayerBase base;
    base.position = {{1e7 + 7.0, -2e6 + 8.0, 9.0}};
    base.centre = {1e7, -2e6};
    base.min = {1e7 - 1.0, -2e6 - 1.0, 0.0};
    base.max = {1e7 + 1.0, -2e6 + 1.0, 10.0};
    const g::LayerBase b = moved(base, origin);
    EXPECT_EQ(b.position[0], glm::dvec3(7.0, 8.0, 9.0));
    EXPECT_EQ(b.centre, glm::dvec2(0.0));
    EXPECT_EQ(b.min, glm::dvec3(-1.0, -1.0, 0.0));

    g::LightVolume v;
    v.x0 = 1e7 - 300.0;
    v.y0 = -2e6 + 300.0;
    const g::LightVolume lv = moved(v, origin);
    EXPECT_EQ(lv.x0, -300.0);
    EXPECT_EQ(lv.y0, 300.0);

    kiri::render::Camera c;
    c.position = {1e7 + 1.0, -2e6 + 2.0, 300.0};
    c.target = {1e7, -2e6, 0.0};
    const kiri::render::Camera m = moved(c, origin);
    EXPECT_EQ(m.position, glm::dvec3(1.0, 2.0, 300.0));
    EXPECT_EQ(m.target, glm::dvec3(0.0, 0.0, 0.0));
}

}  // namespace
