#include <gtest/gtest.h>

#include "scene/fog_spec_json.hpp"
#include "kiri/geometry/core/error.hpp"

using namespace kiri::geometry;
using nlohmann::json;

namespace {
std::string error_of(const std::string& text)
{
    try {
        parse_fog_spec(json::parse(text), "s.json");
    } catch (const kiri::InputError& e) {
        return e.what();
    }
    return "no error";
}
}  // namespace

TEST(FogSpecJson, ReadsEveryKey)
{
    const FogSpec s = parse_fog_spec(json::parse(R"({
        "footprint": {"type": "polygon", "points": [[0, 0], [100, 0], [50, 80]]},
        "surface": "gregory", "patch_size": 250, "mode": "lake", "altitude": 420,
        "offset": 5, "smoothing": 300, "clearance": 4, "thickness": 150, "smoothness": 0.2,
        "samples_per_patch": 6, "tessellation": {"tolerance": 0.5, "max_level": 32, "level": 6}})"),
                                     "s.json");
    ASSERT_EQ(s.footprint.polygon.size(), 3u);
    EXPECT_EQ(s.footprint.polygon[2], glm::dvec2(50, 80));
    EXPECT_EQ(s.surface, SurfaceKind::gregory);
    EXPECT_EQ(s.patch_size, 250.0);
    EXPECT_EQ(s.fit.mode, FitMode::lake);
    EXPECT_EQ(s.fit.altitude, 420.0);
    EXPECT_EQ(s.fit.smoothing_length, 300.0);
    EXPECT_EQ(s.fit.clearance, 4.0);
    EXPECT_EQ(s.fit.thickness, 150.0);
    EXPECT_EQ(s.fit.smoothness, 0.2);
    EXPECT_EQ(s.fit.samples_per_patch, 6);
    EXPECT_EQ(s.tessellation.tolerance, 0.5);
    EXPECT_EQ(s.tessellation.max_level, 32);
    EXPECT_EQ(s.tessellation.level, 6);
    // Written back and read again: the same spec.
    const FogSpec t = parse_fog_spec(fog_spec_to_json(s), "s.json");
    EXPECT_EQ(t.footprint.polygon, s.footprint.polygon);
    EXPECT_EQ(t.surface, s.surface);
    EXPECT_EQ(t.fit.altitude, s.fit.altitude);
    EXPECT_EQ(t.tessellation.tolerance, s.tessellation.tolerance);
}

TEST(FogSpecJson, RectangleAndTerrainFootprints)
{
    const FogSpec r =
        parse_fog_spec(json::parse(R"({"footprint": {"type": "rectangle", "min": [-5, -6], "max": [7, 8]}})"), "");
    ASSERT_EQ(r.footprint.polygon.size(), 4u);
    EXPECT_EQ(r.footprint.polygon[2], glm::dvec2(7, 8));
    const FogSpec t = parse_fog_spec(json::parse(R"({"footprint": {"type": "terrain", "margin": 300}})"), "");
    EXPECT_TRUE(t.footprint.polygon.empty());
    EXPECT_EQ(t.margin, 300.0);
}

TEST(FogSpecJson, PreciseErrors)
{
    EXPECT_EQ(
        error_of(R"({"colour": 1})"),
        "s.json: /fog/colour: unknown key (expected one of: altitude, burn_off, clearance, fill, flow, footprint, mode, "
        "offset, outline, patch_size, samples_per_patch, smoothing, smoothness, surface, tessellation, thickness)");
    EXPECT_EQ(error_of(R"({"surface": "nurbs"})"),
              "s.json: /fog/surface: expected \"gregory\" or \"catmull-clark\", got \"nurbs\"");
    EXPECT_EQ(error_of(R"({"patch_size": -3})"), "s.json: /fog/patch_size: must be > 0");
    EXPECT_EQ(error_of(R"({"mode": "lake"})"),
              "s.json: /fog/altitude: lake mode needs the altitude of the fog top (metres)");
    EXPECT_EQ(error_of(R"({"footprint": {"type": "rectangle", "min": [0, 0], "max": [5]}})"),
              "s.json: /fog/footprint/max: expected an array of 2 numbers [x, y] (local metres)");
    EXPECT_EQ(error_of(R"({"footprint": {"type": "polygon", "points": [[0, 0], [1, "a"], [2, 2]]}})"),
              "s.json: /fog/footprint/points/1/1: expected a number");
    EXPECT_EQ(error_of(R"({"tessellation": {"level": 0}})"),
              "s.json: /fog/tessellation/level: must be in [1, 256], got 0");
    EXPECT_NE(error_of(R"({"clearance": 300, "thickness": 100})").find("s.json: /fog/clearance: clearance 300"),
              std::string::npos);
    EXPECT_EQ(error_of(R"({"footprint": {"type": "polygon", "points": [[0, 0], [200, 100], [200, 0], [0, 150]]}})"),
              "s.json: /fog/footprint/points: edges 0 and 2 intersect: the polygon must be simple");
}
