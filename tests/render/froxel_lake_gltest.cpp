// The froxel fog against the CPU reference on the bundled fog lake over Jacksboro (label slow:
// the reference of a 320 x 180 view takes seconds).
#include "kiri/geometry/scene/scene.hpp"
#include "kiri/geometry/scene/pipeline.hpp"
#include "render/froxel_fixture.hpp"

namespace {

using namespace kiri::test;

TEST_F(FroxelGl, JacksboroFogLake)
{
    // The bundled lake scene: fog filling the valleys to the 460 m contour, ridges rising
    // through it, the sun low in the west; its first camera.
    const g::Scene scene = g::load_scene(std::string(KIRI_DATA_DIR) + "/scenes/jacksboro_lake.json");
    const g::PipelineProducts fog = g::author_scene(scene, {g::Stage::medium});
    const g::Terrain& terrain = *fog.terrain;
    const g::Bounds3 b = terrain.bounds();
    const g::CameraSpec cam = scene.camera("", b.min, b.max);
    Camera c;
    c.position = cam.position;
    c.target = cam.target;
    c.fov_y_deg = cam.fov_y_deg;
    SunLight light;
    light.direction = scene.sun.direction;
    light.color = scene.sun.color;
    light.intensity = scene.sun.intensity;
    light.ambient = scene.sun.ambient;
    g::FroxelOptions o = small(160, 90);
    o.far = 60000.0;
    o.shadow_map_size = scene.froxel.shadow_map_size;  // 4096: narrow valleys in the low sun's shadow
    const Compared r = compare(terrain, fog.medium.get(), o, c, 320, 180, light);
    EXPECT_GT(r.error.fog_pixels, 5000);
    // The lake's medium is dense (visibility 150 m): the fog's sunlit skin is metres deep and
    // the narrow valleys' shadows are finer than the shadow map, so this is a guard against
    // regressions at what is reached, not the 2 % goal, which the thin-layer, homogeneous and
    // height-fog tests meet (docs/froxel.md). Measured: mean 3.5 %, p99 54 % (pixels of fog in
    // a valley's shadow that the ESM lights); with a 512 shadow map instead, 4.6 % and 73 %.
    EXPECT_LT(r.error.mean_relative, 0.045);
    EXPECT_LT(r.error.p99_relative, 0.65);
}

}  // namespace
