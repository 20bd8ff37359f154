// Terrain-derived defaults (scene/scene_defaults.hpp): the keys a scene file leaves out are
// derived from the terrain by closed-form rules, keys it gives are kept, a scene built in code is
// untouched, and the Pipeline hands the completed scene to its users.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <glm/geometric.hpp>

#include "kiri/geometry/scene/pipeline.hpp"
#include "kiri/geometry/scene/scene_defaults.hpp"

using namespace kiri::geometry;

namespace {

// z = f(x, y) on an nx x ny grid of `cell` metres, centred on the origin.
template <class F>
Heightfield grid(int nx, int ny, double cell, F f)
{
    Heightfield hf;
    hf.nx = nx;
    hf.ny = ny;
    hf.dx = hf.dy = cell;
    hf.x0 = -0.5 * cell * (nx - 1);
    hf.y0 = -0.5 * cell * (ny - 1);
    hf.z.resize(std::size_t(nx) * ny);
    hf.valid.assign(hf.z.size(), 1);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
            hf.z[std::size_t(j) * nx + i] = f(hf.x_of(i), hf.y_of(j));
    return hf;
}

Scene parsed(const std::string& json) { return parse_scene(json, "scene.json", "."); }

const DerivedValue* find(const DerivedDefaults& d, const std::string& key)
{
    for (const DerivedValue& v : d.values)
        if (v.key == key)
            return &v;
    return nullptr;
}

}  // namespace

TEST(SceneDefaults, ParsingRecordsTheGivenKeys)
{
    const Scene s = parsed(R"({"terrain": {"path": "x.tif", "exaggeration": 2},
                               "fog": {"fill": [{"seeds": "all", "top": 5}, {"seeds": "all"}]}})");
    ASSERT_TRUE(s.given);
    EXPECT_TRUE(s.gives("/terrain/exaggeration"));
    EXPECT_TRUE(s.gives("/fog/fill/0/top"));
    EXPECT_FALSE(s.gives("/fog/fill/1/top"));
    EXPECT_FALSE(s.gives("/cameras"));
    EXPECT_TRUE(Scene{}.gives("/cameras")) << "a scene built in code gives every key";
}

TEST(SceneDefaults, ASceneBuiltInCodeIsUntouched)
{
    const Terrain terrain(grid(40, 30, 10.0, [](double x, double) { return 0.01 * x; }));
    Scene s;
    s.fog = FogSpec{};
    DerivedDefaults record;
    EXPECT_EQ(derive_scene_defaults(s, terrain, 1.0, record), s);
    EXPECT_TRUE(record.values.empty());
}

TEST(SceneDefaults, ExaggerationStretchesLowReliefOnly)
{
    // A ramp rising r over 10 km (98 - 2 % quantiles: 0.96 r): stretched until it rises 4 %
    // (400 m), in steps 1.5, 2, 3, 4, 5.
    const auto ramp = [](double rise) {
        return grid(101, 101, 100.0, [rise](double x, double) { return rise * (x / 10000.0 + 0.5); });
    };
    EXPECT_EQ(derive_exaggeration(ramp(1000.0)), 1.0);
    EXPECT_EQ(derive_exaggeration(ramp(300.0)), 1.5);  // 288 m x 1.5 = 432 m
    EXPECT_EQ(derive_exaggeration(ramp(150.0)), 3.0);  // 144 m x 3 = 432 m (x 2: 288 m)
    EXPECT_EQ(derive_exaggeration(ramp(20.0)), 5.0);   // the most
    EXPECT_EQ(derive_exaggeration(ramp(0.0)), 1.0);    // a plain has nothing to stretch
}

TEST(SceneDefaults, FiguresOfACoastCountTheLandOnly)
{
    // Half sea at -500 m, half land rising 0..1000 m: the land's floor is near 0, not -500.
    const Heightfield hf = grid(201, 11, 50.0, [](double x, double) { return x < 0.0 ? -500.0 : 1000.0 * x / 5000.0; });
    const TerrainFigures t = terrain_figures(hf);
    EXPECT_TRUE(t.coast);
    EXPECT_NEAR(t.low, 20.0, 10.0);
    EXPECT_NEAR(t.high, 980.0, 10.0);
}

TEST(SceneDefaults, AFillWithoutTopCoversThirtyPercentOfTheLand)
{
    // z = x over [-5000, 5000] (+5000): quantiles 2, 30, 98 % at 200, 3000, 9800 m; 3000 m is
    // more than a fifth of the relief up (200 + 1920).
    const Terrain terrain(grid(101, 51, 100.0, [](double x, double) { return x + 5000.0; }));
    const Scene s = parsed(R"({"terrain": {"path": "x.tif", "exaggeration": 1},
                               "fog": {"fill": {"seeds": "all"}}, "cameras": [], "sun": {"direction": [0, 0, 1]}})");
    DerivedDefaults record;
    const Scene out = derive_scene_defaults(s, terrain, 1.0, record);
    EXPECT_EQ(out.fog->placement->regions[0].top, 3000.0);
    // A single peak on a plain: 30 % of the land is the plain, so the fifth of the relief wins.
    const Terrain peak(grid(101, 101, 100.0, [](double x, double y) {
        return 100.0 + 1000.0 * std::exp(-(x * x + y * y) / (2000.0 * 2000.0));
    }));
    const TerrainFigures f = terrain_figures(peak.heightfield());
    const Scene on_peak = derive_scene_defaults(s, peak, 1.0, record);
    EXPECT_EQ(on_peak.fog->placement->regions[0].top, std::round(f.low + 0.2 * f.relief()));
    EXPECT_GT(f.low + 0.2 * f.relief(), f.fill_level);
    ASSERT_NE(find(record, "/fog/fill/top"), nullptr);
    EXPECT_EQ(find(record, "/terrain/exaggeration"), nullptr) << "given";
    EXPECT_EQ(find(record, "/sun/direction"), nullptr) << "given";
    EXPECT_TRUE(out.cameras.empty()) << "given (empty)";
    EXPECT_EQ(out.sun.direction, s.sun.direction);
}

TEST(SceneDefaults, GivenKeysAreKept)
{
    const Terrain terrain(grid(101, 51, 100.0, [](double x, double) { return x + 5000.0; }));
    const Scene s = parsed(R"({"terrain": {"path": "x.tif"},
                               "fog": {"patch_size": 777, "offset": 12, "tessellation": {"level": 3}},
                               "medium": {"visibility": 5000}})");
    DerivedDefaults record;
    const Scene out = derive_scene_defaults(s, terrain, 1.0, record);
    EXPECT_EQ(out.fog->patch_size, 777.0);
    EXPECT_EQ(out.fog->tessellation.level, 3);
    EXPECT_EQ(out.fog->fit.offset, 12.0);
    EXPECT_EQ(out.fog->fit.thickness, FitOptions{}.thickness) << "offset and thickness are derived together";
    EXPECT_EQ(out.medium.extinction, s.medium.extinction);
}

TEST(SceneDefaults, PatchesFollowCellsWithinTheBudgets)
{
    // 30 m cells: 8 cells a patch, rounded up to 250 m.
    const Scene s = parsed(R"({"terrain": {"path": "x.tif"}, "fog": {"mode": "blanket"}})");
    DerivedDefaults record;
    const Terrain fine(grid(101, 101, 30.0, [](double x, double y) { return 100.0 + 0.1 * x + 0.05 * y; }));
    EXPECT_EQ(derive_scene_defaults(s, fine, 1.0, record).fog->patch_size, 250.0);
    // 3601 x 3601 cells of 30 m: the patch budget wins, and the triangles stay in theirs.
    Heightfield big;
    big.nx = big.ny = 3601;
    big.dx = big.dy = 30.0;
    big.z.assign(std::size_t(3601) * 3601, 0.0);
    for (std::size_t k = 0; k < big.z.size(); ++k)
        big.z[k] = double(k % 3601);
    big.valid.assign(big.z.size(), 1);
    const double side = 30.0 * 3600;
    const Scene out = derive_scene_defaults(s, Terrain(std::move(big)), 1.0, record);
    const double patches = (side / out.fog->patch_size) * (side / out.fog->patch_size);
    EXPECT_LE(patches, double(max_patches));
    EXPECT_GT(patches, 0.2 * max_patches) << "no coarser than the budget needs";
    EXPECT_LE(2.0 * patches * out.fog->tessellation.level * out.fog->tessellation.level, double(max_triangles));
}

TEST(SceneDefaults, BlanketAndVisibilityFromTheRelief)
{
    // Relief 2000 m: a blanket 240 m thick (0.12 relief), offset 72 m; the default medium's
    // optical depth through 240 m (0.02 x 240 = 4.8) is inside [0.8, 6]: kept.
    const Terrain terrain(grid(101, 101, 100.0, [](double x, double) { return 1000.0 + x / 5000.0 * 1000.0 / 0.96; }));
    const Scene s = parsed(R"({"terrain": {"path": "x.tif"}, "fog": {"mode": "blanket"}})");
    DerivedDefaults record;
    const Scene out = derive_scene_defaults(s, terrain, 1.0, record);
    EXPECT_NEAR(out.fog->fit.thickness, 240.0, 1e-9);
    EXPECT_NEAR(out.fog->fit.offset, 72.0, 1e-9);
    EXPECT_EQ(out.medium.extinction, MediumOptions{}.extinction);
    // Exaggerated 5 times, the same blanket is 1200 m deep in world metres: 24 optical depths,
    // an opaque plate; the visibility is raised to make it 6.
    const Terrain stretched(
        grid(101, 101, 100.0, [](double x, double) { return 5.0 * (1000.0 + x / 5000.0 * 1000.0 / 0.96); }));
    const Scene far = derive_scene_defaults(s, stretched, 5.0, record);
    const double tau = far.medium.extinction * far.fog->fit.thickness * 5.0;
    EXPECT_NEAR(tau, 6.0, 0.1) << "two significant digits of visibility";
    ASSERT_NE(find(record, "/medium/visibility"), nullptr);
}

TEST(SceneDefaults, TheOverviewFramesTheTerrainAndTheSunIsLow)
{
    const Terrain terrain(grid(
        81, 61, 50.0, [](double x, double y) { return 300.0 + 200.0 * std::sin(x / 700.0) * std::cos(y / 500.0); }));
    const Scene s =
        parsed(R"({"terrain": {"path": "x.tif"}, "fog": {"mode": "blanket"}, "image": {"width": 160, "height": 90}})");
    DerivedDefaults record;
    const Scene out = derive_scene_defaults(s, terrain, 1.0, record);
    ASSERT_EQ(out.cameras.size(), 3u);
    EXPECT_EQ(out.cameras[0].name, "overview");
    EXPECT_EQ(out.camera("", {}, {}).name, "overview") << "the first camera is the default view";
    EXPECT_EQ(out.cameras[1].name, "valley");
    EXPECT_EQ(out.cameras[2].name, "inside");
    // The ground's corners lie inside the frame's width, and one of them touches its edge.
    const CameraSpec& c = out.cameras[0];
    const glm::dvec3 f = glm::normalize(c.target - c.position);
    const glm::dvec3 r = glm::normalize(glm::cross(f, glm::dvec3(0, 0, 1)));
    const double tx = 160.0 / 90.0 * std::tan(0.5 * c.fov_y_deg * M_PI / 180.0);
    const Bounds3 b = terrain.bounds();
    double widest = 0.0;
    for (double x : {b.min.x, b.max.x})
        for (double y : {b.min.y, b.max.y}) {
            const glm::dvec3 v = glm::dvec3(x, y, c.target.z) - c.position;
            widest = std::max(widest, std::abs(glm::dot(v, r)) / (tx * glm::dot(v, f)));
        }
    EXPECT_LE(widest, 1.0);
    EXPECT_GT(widest, 0.9) << "the terrain fills the frame's width";
    EXPECT_LT(f.z, -0.3) << "oblique";
    EXPECT_GT(f.z, -0.7);
    // The sun between 12 and 30 degrees high.
    const double elevation = std::asin(glm::normalize(out.sun.direction).z) * 180.0 / M_PI;
    EXPECT_GE(elevation, 11.99);
    EXPECT_LE(elevation, 30.01);
    // The inside camera is in the fog: below the blanket's top over its ground.
    const CameraSpec& in = out.cameras[2];
    const double ground = terrain.height(in.position.x, in.position.y);
    EXPECT_GT(in.position.z, ground);
    EXPECT_LT(in.position.z, ground + out.fog->fit.offset);
}

TEST(SceneDefaults, APointFileIsATerrain)
{
    // Points of the plane z = 100 + 0.1 x + 0.2 y on a jittered 21 x 21 lattice of 50 m: the
    // triangulation reproduces a plane exactly, at about one point a cell (1000 m / 21 -> 48 m).
    const std::filesystem::path file = std::filesystem::temp_directory_path() / "kiri_scene_defaults_points.xyz";
    {
        std::ofstream out(file);
        out.precision(17);
        for (int j = 0; j <= 20; ++j)
            for (int i = 0; i <= 20; ++i) {
                const double x = 1000.0 + 50.0 * i + ((i * 7 + j * 3) % 5 - 2) * (0 < i && i < 20 ? 3.0 : 0.0);
                const double y = 2000.0 + 50.0 * j + ((i * 3 + j * 7) % 5 - 2) * (0 < j && j < 20 ? 3.0 : 0.0);
                out << x << "," << y << "," << 100.0 + 0.1 * x + 0.2 * y << "\n";
            }
    }
    const Scene s =
        parse_scene(R"({"terrain": {"path": ")" + file.string() + R"(", "exaggeration": 1}})", "scene.json", ".");
    const Terrain terrain = load_scene_terrain(s);
    const Heightfield& hf = terrain.heightfield();
    EXPECT_EQ(hf.dx, 48.0);
    // Local coordinates are centred on the grid: input x = origin_x + local x.
    const double ox = hf.georef.origin_x, oy = hf.georef.origin_y;
    EXPECT_NEAR(ox, 1000.0 + 0.5 * 48.0 * (hf.nx - 1), 1e-9);
    for (const glm::dvec2 p : {glm::dvec2(0.0, 0.0), glm::dvec2(-300.0, 250.0), glm::dvec2(420.0, -380.0)})
        EXPECT_NEAR(terrain.height(p.x, p.y), 100.0 + 0.1 * (ox + p.x) + 0.2 * (oy + p.y), 1e-9);
    DerivedDefaults record;
    derive_scene_defaults(s, terrain, 1.0, record);
    ASSERT_NE(find(record, "/terrain/cell_size"), nullptr);
    EXPECT_EQ(find(record, "/terrain/cell_size")->value, "48");
    std::filesystem::remove(file);
}
