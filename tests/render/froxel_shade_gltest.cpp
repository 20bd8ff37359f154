// The shade a canyon's wall casts into the fog in it, seen from inside the fog: the edge of the shade
// crosses each ray somewhere within a slice of the froxels (or a step of a pixel's march), so
// the terrain's visibility of the sun must be taken along the ray through it, not at one point.
#include "render/froxel_fixture.hpp"

namespace {

using namespace kiri::test;

class FroxelShadeGl : public FroxelGl {};

// The canyon filled with fog to 900 m (600 m of visibility), the sun 30 degrees up in the
// west-north-west, the eye in the fog halfway down the canyon looking along it: the shade of its
// western wall falls through the fog, its edge crossing the rays within a slice or a step. With
// the sun's visibility taken at one point of each slice and at every fourth step of a pixel's
// march, the fog came out in bands a slice or four steps apart: 0.89 % off the reference on
// average, p99 7.2 % (now 0.40 %, 2.3 %).
TEST_F(FroxelShadeGl, TheShadeOfACanyonsWallInItsFogHasNoBands)
{
    const g::Terrain terrain = views_bench_canyon();
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
