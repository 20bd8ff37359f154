// Fog placed by the terrain from a scene: the keys, their errors, the round trip,
// the placed footprint and lake target, the medium of a fill, the optics' conversions.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "fog_test_terrains.hpp"
#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/placement/fill_medium.hpp"
#include "kiri/geometry/placement/fog_placement.hpp"
#include "kiri/geometry/scene/scene.hpp"
#include "kiri/geometry/scene/pipeline.hpp"

using namespace kiri::geometry;
using kiri::test::make_heightfield;

namespace {

const std::string dem = std::string(KIRI_DATA_DIR) + "/terrains/jacksboro_fault_dem.tif";

std::string scene_text(const std::string& fog, const std::string& extra = "")
{
    return R"({"terrain": {"path": ")" + dem + R"(", "exaggeration": 1.5}, "fog": )" + fog + extra + "}";
}

std::string error_of(const std::string& fog, const std::string& extra = "")
{
    try {
        Scene s = parse_scene(scene_text(fog, extra), "s.json", "/d");
        s.file = "s.json";
        author_scene(s, {Stage::medium});
    } catch (const kiri::InputError& e) {
        return e.what();
    }
    return "accepted";
}

// Two basins joined by a 200 m saddle at the origin (as in fog_fill_test).
Terrain basins()
{
    return Terrain(make_heightfield(201, 101, 10.0, -1000.0, -500.0, [](double x, double y) {
        const double d = std::min((x - 500.0) * (x - 500.0), (x + 500.0) * (x + 500.0));
        return 100.0 + (d + y * y) / 2500.0;
    }));
}

}  // namespace

TEST(FogPlacement, SceneKeysParseAndRoundTrip)
{
    const Scene a = parse_scene(scene_text(R"({"fill": [{"top": 460, "seeds": [[11100, 6600]], "max_thickness": 150},
                                                         {"top": 500, "seeds": "valleys", "valleys": {"threshold": 1.2}}],
                                                "outline": {"margin": 400},
                                                "flow": {"wind": [-3, 4], "duration": 600},
                                                "burn_off": {"time": 9.5, "latitude": 36}})"),
                                "s.json", "/d");
    ASSERT_TRUE(a.fog && a.fog->placement);
    const PlacementSpec& p = *a.fog->placement;
    ASSERT_EQ(p.regions.size(), 2u);
    EXPECT_EQ(p.regions[0].seeds, SeedKind::points);
    EXPECT_EQ(p.regions[1].seeds, SeedKind::valleys);
    EXPECT_DOUBLE_EQ(p.regions[1].valleys.threshold, 1.2);
    EXPECT_DOUBLE_EQ(p.regions[0].max_thickness, 150.0);
    EXPECT_DOUBLE_EQ(p.margin, 400.0);
    ASSERT_TRUE(p.flow && p.burn_off);
    EXPECT_TRUE(p.latitude_given);
    EXPECT_FALSE(p.evaporation_given);
    EXPECT_EQ(a.fog->fit.mode, FitMode::lake);
    // (Twice: the first pass normalises the default sun direction.)
    const std::string text = scene_to_json(parse_scene(scene_to_json(a), "again.json", "/d"));
    EXPECT_EQ(scene_to_json(parse_scene(text, "again.json", "/d")), text);
    EXPECT_NE(text.find("\"seeds\": \"valleys\""), std::string::npos);
    // World units: heights times the exaggeration; the flow's evaporation from the medium.
    const FogSpec w = world_fog_spec(a);
    EXPECT_DOUBLE_EQ(w.placement->regions[0].top, 690.0);
    EXPECT_DOUBLE_EQ(w.placement->flow->evaporation_depth, 1.5 * evaporation_depth_for(a.medium.extinction));
}

TEST(FogPlacement, BadKeysGiveOneLineNamingThem)
{
    EXPECT_EQ(error_of(R"({"fill": {"top": 460}})"),
              "s.json: /fog/fill/seeds: missing: seed points [[x, y], ...] (local metres), \"all\", \"valleys\" or "
              "{\"mask\": FILE}");
    EXPECT_EQ(error_of(R"({"fill": {"top": 460, "seeds": [[90000, 0]]}})")
                  .rfind("s.json: /fog/fill/seeds/0: seed (90000, 0) lies outside the terrain", 0),
              0u);
    EXPECT_EQ(
        error_of(R"({"fill": {"top": 200, "seeds": [[11100, 6600]]}})")
            .rfind(
                "s.json: /fog/fill/top: the fog top 200 m is at or below every seed (the lowest seed's ground is 340 m)",
                0),
        0u);
    EXPECT_EQ(error_of(R"({"fill": {"top": 460, "seeds": "all", "valleys": {}}})"),
              "s.json: /fog/fill/valleys: only used with \"seeds\": \"valleys\"");
    EXPECT_EQ(error_of(R"({"fill": {"top": 460, "seeds": "all"}, "mode": "blanket"})")
                  .rfind("s.json: /fog/mode: a fill sets this itself", 0),
              0u);
    EXPECT_EQ(error_of(R"({"flow": {"wind": [1, 0]}})"),
              "s.json: /fog/flow: needs /fog/fill: the fog placed by the terrain that this acts on");
    EXPECT_EQ(error_of(R"({"fill": {"top": 460, "seeds": "all"}, "flow": {"wind": [1, 0], "coupling": 2}})"),
              "s.json: /fog/flow/coupling: must be in [0, 1], got 2");
    EXPECT_EQ(error_of(R"({"fill": {"top": 460, "seeds": "all"}, "burn_off": {"time": 25}})"),
              "s.json: /fog/burn_off/time: must be in [0, 24], got 25");
    EXPECT_EQ(
        error_of(
            R"({"fill": {"top": 460, "seeds": "all"}, "burn_off": {"time": 17, "burn_rate": 2000, "lift_rate": 2000}})")
            .rfind("s.json: /fog/burn_off/time: the fog has burnt off completely by 17", 0),
        0u);
    EXPECT_EQ(error_of(R"({"fill": {"top": 460, "seeds": {"mask": "nothing.png"}}})"),
              "s.json: /fog/fill/seeds/mask: no such mask file: /d/nothing.png");
    EXPECT_EQ(error_of(R"({"fill": {"top": 460, "seeds": "valleys", "valleys": {"threshold": 9}}})"),
              "s.json: /fog/fill/valleys/threshold: no cell of the terrain is a valley at this threshold: lower it");
    EXPECT_EQ(
        error_of(R"({"fill": {"top": 460, "seeds": "all", "colour": 1}})"),
        "s.json: /fog/fill/colour: unknown key (expected one of: max_thickness, min_thickness, profile, seeds, top, "
        "valleys)");
}

TEST(FogPlacement, PlacedFogGivesTheFootprintAndTheLakeTarget)
{
    const Terrain t = basins();
    PlacementSpec spec;
    FillRegionSpec r;
    r.top = 199.0;
    r.points = {{-500.0, 0.0}};
    spec.regions = {r};
    const PlacedFog placed = place_fog(t, spec, 100.0);
    EXPECT_TRUE(placed.flat);
    EXPECT_DOUBLE_EQ(placed.top, 199.0);
    ASSERT_EQ(placed.outline.components, 1);
    // The footprint covers the left basin's fog and no fog-free ground below the top in the
    // right basin (it grows over dry ground only).
    const Heightfield& hf = t.heightfield();
    const auto& poly = placed.outline.footprint.polygon;
    auto inside = [&](glm::dvec2 q) {
        bool in = false;
        for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++)
            if ((poly[i].y > q.y) != (poly[j].y > q.y) &&
                q.x < (poly[j].x - poly[i].x) * (q.y - poly[i].y) / (poly[j].y - poly[i].y) + poly[i].x)
                in = !in;
        return in;
    };
    for (int j = 0; j < hf.ny; ++j)
        for (int i = 0; i < hf.nx; ++i) {
            const glm::dvec2 q(hf.x_of(i), hf.y_of(j));
            if (placed.columns.mask[std::size_t(j) * hf.nx + i]) {
                EXPECT_TRUE(inside(q)) << q.x << " " << q.y;
            } else if (hf.at(i, j) < 199.0) {
                EXPECT_FALSE(inside(q)) << q.x << " " << q.y;
            }
        }
    FogSpec fs;
    fs.patch_size = 100.0;
    fs.placement = spec;
    const FogSpec s = placed_fog_spec(fs, placed);
    EXPECT_EQ(s.fit.mode, FitMode::lake);
    EXPECT_DOUBLE_EQ(s.fit.altitude, 199.0);
    EXPECT_DOUBLE_EQ(s.fit.thickness, 99.0);
    EXPECT_FALSE(s.fit.altitude_grid);
    // The fit reproduces the flat top (a plane is fitted exactly).
    BaseSurface surface = fog_control_surface(t, s);
    EXPECT_LT(fit_fog_surface(surface, t, s).max_deviation, 1e-6);
    // Regions may overlap: the same basin from two seeds with different tops gives a top grid.
    FillRegionSpec r2 = r;
    r2.top = 180.0;
    r2.points = {{-450.0, 0.0}};
    spec.regions.push_back(r2);
    const PlacedFog two = place_fog(t, spec, 100.0);
    EXPECT_FALSE(two.flat);
    ASSERT_TRUE(two.top_grid);
    EXPECT_EQ(two.columns.mask, placed.columns.mask);  // the 180 m fog lies inside the 199 m fog
    const std::size_t floor = std::size_t(50) * 201 + 50;
    EXPECT_DOUBLE_EQ(two.columns.top[floor], 199.0);
}

TEST(FogPlacement, TheMediumOfAFillIsItsColumns)
{
    const Terrain t = basins();
    PlacementSpec spec;
    FillRegionSpec r;
    r.top = 199.0;
    r.points = {{-500.0, 0.0}};
    r.profile = 1.0;  // by absolute altitude
    spec.regions = {r};
    const PlacedFog placed = place_fog(t, spec, 100.0);
    const Medium m = fill_medium(t, placed, MediumOptions{}, MediumDetail{.detail = 0.0});
    // At the basin's floor the fog spans ground .. top with full density at the floor.
    const MediumColumn c = m.column(-500.0, 0.0);
    EXPECT_DOUBLE_EQ(c.top, 199.0);
    EXPECT_DOUBLE_EQ(c.floor, 100.0);
    EXPECT_DOUBLE_EQ(m.density({-500.0, 0.0, 100.0 + 1e-9}), 1.0 - 0.9 * 1e-9 / 99.0);
    // Absolute profile: the same altitude has the same density over the floor and on the shore.
    EXPECT_NEAR(m.density({-500.0, 0.0, 180.0}), m.density({-500.0, 350.0, 180.0}), 1e-12);
    // No fog right of the saddle.
    EXPECT_EQ(m.density({500.0, 0.0, 150.0}), 0.0);
    // Its volume is the fill's.
    EXPECT_NEAR(m.shell_volume() / placed.figures.volume_m3, 1.0, 1e-9);
}

TEST(FogPlacement, TheMediumsGridSpansTheFogsBounds)
{
    // A flat terrain of 201 x 201 samples 10 m apart; fog 50 m deep over samples i 5..24,
    // j 3..12 (a corner). The grid spans them with one sample of margin: i 4..26, j 2..14.
    Heightfield hf;
    hf.nx = hf.ny = 201;
    hf.dx = hf.dy = 10.0;
    hf.x0 = hf.y0 = -1000.0;
    hf.z.assign(std::size_t(201) * 201, 0.0);
    hf.valid.assign(hf.z.size(), 1);
    const Terrain t(hf);
    const auto placed_at = [&](const std::vector<std::pair<int, int>>& extra) {
        PlacedFog p;
        p.columns.nx = p.columns.ny = 201;
        p.columns.mask.assign(hf.z.size(), 0);
        p.columns.bottom.assign(hf.z.size(), 0.0);
        p.columns.top.assign(hf.z.size(), 0.0);
        p.medium_bottom.assign(hf.z.size(), 0.0);
        const auto fog = [&](int i, int j) {
            const std::size_t k = std::size_t(j) * 201 + i;
            p.columns.mask[k] = 1;
            p.columns.top[k] = 50.0;
        };
        for (int j = 3; j <= 12; ++j)
            for (int i = 5; i <= 24; ++i)
                fog(i, j);
        for (const auto& [i, j] : extra)
            fog(i, j);
        return p;
    };
    const MediumDetail plain{.detail = 0.0};
    const Medium corner = fill_medium(t, placed_at({}), MediumOptions{}, plain);
    EXPECT_EQ(corner.grid().nx, 23);
    EXPECT_EQ(corner.grid().ny, 13);
    EXPECT_DOUBLE_EQ(corner.grid().x0, hf.x_of(4));
    EXPECT_DOUBLE_EQ(corner.grid().y0, hf.y_of(2));
    // The same fog with a speck at the far corner spans samples 4..200: inside the corner's fog
    // and around it, both media are the same.
    const Medium whole = fill_medium(t, placed_at({{200, 200}}), MediumOptions{}, plain);
    EXPECT_EQ(whole.grid().nx, 197);
    for (double x = hf.x_of(2); x <= hf.x_of(28); x += 3.7)
        for (double y = hf.y_of(0); y <= hf.y_of(16); y += 4.1)
            for (double z : {1.0, 25.0, 49.0})
                EXPECT_EQ(corner.density({x, y, z}), whole.density({x, y, z})) << x << " " << y << " " << z;
    // The memory budget counts the fog's bounds: 40 samples a side keep the corner's 10 m
    // spacing, where the whole terrain needs every 6th sample.
    MediumOptions budget;
    budget.max_grid_side = 40;
    EXPECT_DOUBLE_EQ(fill_medium(t, placed_at({}), budget, plain).grid().dx, 10.0);
    EXPECT_DOUBLE_EQ(fill_medium(t, placed_at({{200, 200}}), budget, plain).grid().dx, 60.0);
}

TEST(FogPlacement, OpticsConversions)
{
    // Koschmieder (medium.hpp): V = 3.912 / sigma; the engines' equivalents of sigma.
    const double sigma = extinction_from_visibility(200.0);
    EXPECT_DOUBLE_EQ(sigma, 3.912 / 200.0);
    EXPECT_DOUBLE_EQ(visibility_from_extinction(sigma), 200.0);
    const EngineFog e = engine_fog(sigma);
    EXPECT_DOUBLE_EQ(e.hdrp_attenuation_distance_m, 200.0 / 3.912);
    EXPECT_DOUBLE_EQ(e.godot_density, sigma);
    // Unreal: transmittance exp2(-ln2 * FogDensity / 1000 * L_cm) over L metres equals exp(-sigma L).
    const double L = 123.0;
    EXPECT_NEAR(std::exp2(-std::log(2.0) * e.unreal_fog_density / 1000.0 * L * 100.0), std::exp(-sigma * L), 1e-12);
    // Liquid water: 0.2 g/m^3 of 7 um droplets is sigma 0.043 (medium.hpp), and the flow's
    // evaporation depth is LWC / (9.8e-3 K/m * 0.45 g/m^3/K).
    const double s2 = extinction_from_liquid_water(0.2, 7.0);
    EXPECT_NEAR(s2, 3.0 * 2.0 * 0.2 / (4.0 * 1e6 * 7e-6), 1e-15);
    EXPECT_NEAR(evaporation_depth_for(s2), 0.2 / (9.8e-3 * 0.45), 1e-9);
}
