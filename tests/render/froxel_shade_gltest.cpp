// The shade a ridge casts into the fog beside it, seen from inside the fog: the edge of the shade
// crosses each ray somewhere within a slice of the froxels (or a step of a pixel's march), so
// the terrain's visibility of the sun must be taken along the ray through it, not at one point.
#include "render/froxel_fixture.hpp"

namespace {

using namespace kiri::test;

// The views bench's canyon (apps/kiri/bench/views_bench.cpp): a meandering canyon 300 m deep in a
// plateau rising northwards, 2.39 km by 1.79 km on 10 m cells, centred on the origin.
g::Terrain canyon()
{
    g::Heightfield hf;
    hf.nx = 240;
    hf.ny = 180;
    hf.dx = hf.dy = 10.0;
    hf.x0 = -0.5 * (hf.nx - 1) * hf.dx;
    hf.y0 = -0.5 * (hf.ny - 1) * hf.dy;
    hf.z.resize(std::size_t(hf.nx) * std::size_t(hf.ny));
    hf.valid.assign(hf.z.size(), 1);
    for (int j = 0; j < hf.ny; ++j)
        for (int i = 0; i < hf.nx; ++i) {
            const double x = double(i) / (hf.nx - 1), y = double(j) / (hf.ny - 1);
            const double axis = 0.5 + 0.1 * std::sin(6.0 * y);
            hf.z[std::size_t(j) * std::size_t(hf.nx) + std::size_t(i)] = 900.0 -
                300.0 * std::exp(-(x - axis) * (x - axis) / 0.008) + 60.0 * y + 20.0 * std::sin(9.0 * x + 3.0 * y);
        }
    return g::Terrain(std::move(hf));
}

class FroxelShadeGl : public FroxelGl {};

// The canyon filled with fog to 900 m (600 m of visibility), the sun 30 degrees up in the
// west-north-west, the eye in the fog halfway down the canyon looking along it: the shade of its
// western wall falls through the fog, its edge crossing the rays within a slice or a step. With
// the sun's visibility taken at one point of each slice and at every fourth step of a pixel's
// march, the fog came out in bands a slice or four steps apart: 0.89 % off the reference on
// average, p99 7.2 % (now 0.40 %, 2.3 %).
TEST_F(FroxelShadeGl, TheShadeOfACanyonsWallInItsFogHasNoBands)
{
    const g::Terrain terrain = canyon();
    const g::Medium fog = slab(500.0, 900.0, 0.005, 1300.0, 0.8);
    g::FroxelOptions o = small(64, 36);
    o.far = 3000.0;
    SunLight light = sun();
    light.direction = {-0.785, 0.366, 0.5};
    Camera c;
    c.position = {232.0, -358.0, 760.0};
    c.target = {-105.0, 179.0, 750.0};
    c.fov_y_deg = 60.0;
    const Compared r = compare(terrain, &fog, o, c, 64, 36, light);
    EXPECT_GT(r.error.fog_pixels, 64 * 36 * 3 / 4);
    EXPECT_LT(r.error.mean_relative, 0.006);
    EXPECT_LT(r.error.p99_relative, 0.04);
}

}  // namespace
