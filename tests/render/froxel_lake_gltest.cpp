// The froxel fog against the CPU reference on the bundled fog lake over Jacksboro (label slow:
// the reference of a 320 x 180 view takes seconds).
#include "kiri/geometry/scene.hpp"
#include "kiri/geometry/scene_fog.hpp"
#include "render/froxel_fixture.hpp"

namespace {

using namespace kiri::test;

TEST_F(FroxelGl, JacksboroFogLake)
{
    // The bundled lake scene: fog filling the valleys to the 460 m contour, ridges rising
    // through it, the sun low in the west; its first camera.
    const g::Scene scene = g::load_scene(std::string(KIRI_DATA_DIR) + "/scenes/jacksboro_lake.json");
    const g::Terrain terrain = g::load_scene_terrain(scene);
    const g::SceneFog fog = g::author_scene_fog(scene, terrain);
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
    const Compared r = compare(terrain, &fog.medium, o, c, 320, 180, light);
    EXPECT_GT(r.error.fog_pixels, 5000);
    EXPECT_LT(r.error.mean_relative, 0.02);
    EXPECT_LT(r.error.p99_relative, 0.15);
}

}  // namespace
