#include <gtest/gtest.h>

#include <string>

#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/scene/scene.hpp"

namespace {

using kiri::geometry::parse_scene;
using kiri::geometry::Scene;

std::string error_of(const std::string& json)
{
    try {
        parse_scene(json, "s.json", "/scenes");
    } catch (const kiri::InputError& e) {
        return e.what();
    }
    return "(no error)";
}

const char* minimal = R"({"terrain": {"path": "../t.tif"}})";

TEST(Scene, MinimalSceneTakesDefaultsAndResolvesThePath)
{
    const Scene s = parse_scene(minimal, "s.json", "/scenes");
    EXPECT_EQ(s.terrain.path, std::filesystem::path("/scenes/../t.tif"));
    EXPECT_EQ(s.terrain.exaggeration, 1.0);
    EXPECT_TRUE(s.cameras.empty());
    EXPECT_EQ(s.image.width, 1280);
    EXPECT_EQ(s.image.height, 720);
    EXPECT_FALSE(s.fog.has_value());
}

TEST(Scene, ErrorsNameFilePointerAndReason)
{
    EXPECT_EQ(error_of(R"({"terrain": {"path": "t.tif"}, "sun": {"direction": "up"}})"),
              "s.json: /sun/direction: expected an array of 3 numbers");
    EXPECT_EQ(error_of(R"({"terrain": {"path": "t.tif"}, "sun": {"direction": [1, 2]}})"),
              "s.json: /sun/direction: expected an array of 3 numbers");
    EXPECT_EQ(error_of(R"({"terrain": {"path": "t.tif"}, "sun": {"direction": [0, 0, 0]}})"),
              "s.json: /sun/direction: must not be the zero vector");
    EXPECT_EQ(error_of(R"({"terrain": {"path": 3}})"), "s.json: /terrain/path: expected a string");
    EXPECT_EQ(error_of(R"({"cameras": []})"), "s.json: /terrain: missing (every scene needs a terrain)");
    EXPECT_EQ(error_of(R"({"terrain": {"path": "t.tif", "exaggeration": 0}})"),
              "s.json: /terrain/exaggeration: must be in (0, 100), got 0");
    EXPECT_EQ(error_of(R"({"terrain": {"path": "t.tif"}, "image": {"width": 1.5}})"),
              "s.json: /image/width: expected an integer");
    EXPECT_EQ(error_of(R"({"terrain": {"path": "t.tif"}, "image": {"height": 0}})"),
              "s.json: /image/height: must be in [1, 16384], got 0");
    EXPECT_EQ(
        error_of(
            R"({"terrain": {"path": "t.tif"}, "cameras": [{"position": [0,0,1], "target": [0,0,0], "fov": 180}]})"),
        "s.json: /cameras/0/fov: must be in (0, 180), got 180");
    EXPECT_EQ(error_of(R"({"terrain": {"path": "t.tif"}, "cameras": [{"position": [0,0,1], "target": [0,0,1]}]})"),
              "s.json: /cameras/0/target: equals the position: the view direction is undefined");
    EXPECT_EQ(error_of(R"({"terrain": {"path": "t.tif"}, "cameras": [{"position": [0,0,1]}]})"),
              "s.json: /cameras/0: a camera needs \"position\" and \"target\" (local metres)");
}

TEST(Scene, UnknownKeysAreErrors)
{
    EXPECT_EQ(
        error_of(R"({"terrain": {"path": "t.tif"}, "colour": 1})"),
        "s.json: /colour: unknown key (expected one of: cameras, combined, fog, froxel, image, layers, medium, particles, quality, sun, terrain)");
    EXPECT_EQ(error_of(R"({"terrain": {"path": "t.tif", "exagerration": 2}})"),
              "s.json: /terrain/exagerration: unknown key (expected one of: cell_size, exaggeration, path, "
              "surround, vertical_offset, vertical_scale)");
}

TEST(Scene, MalformedJsonGivesLineAndColumn)
{
    const std::string e = error_of("{\n  \"terrain\": {\"path\": \"t.tif\",}\n}");
    EXPECT_EQ(e.rfind("s.json: malformed JSON: parse error at line 2, column ", 0), 0u) << e;
}

TEST(Scene, RoundTripsThroughJson)
{
    const Scene a = parse_scene(R"({
        "terrain": {"path": "/data/t.tif", "exaggeration": 1.5, "cell_size": 30, "vertical_scale": 0.1},
        "cameras": [{"name": "a", "position": [1, 2, 3], "target": [4, 5, 6], "fov": 30},
                    {"name": "b", "position": [-1, -2, 300], "target": [0, 0, 0]}],
        "sun": {"direction": [0, 0, 2], "color": [1, 0.5, 0.25], "intensity": 2, "ambient": [0.1, 0.2, 0.3]},
        "image": {"width": 64, "height": 32},
        "fog": {"footprint": {"type": "rectangle", "min": [-100, -100], "max": [100, 100]}, "mode": "lake",
                "altitude": 500}})",
                                "s.json", "/x");
    EXPECT_EQ(a.sun.direction, glm::dvec3(0.0, 0.0, 1.0));  // normalised on load
    const Scene b = parse_scene(kiri::geometry::scene_to_json(a), "again.json", "/y");
    EXPECT_EQ(b.terrain.path, a.terrain.path);
    EXPECT_EQ(b.terrain.exaggeration, 1.5);
    EXPECT_EQ(b.terrain.cell_size, 30.0);
    EXPECT_EQ(b.terrain.vertical_scale, 0.1);
    ASSERT_EQ(b.cameras.size(), 2u);
    EXPECT_EQ(b.cameras[1].name, "b");
    EXPECT_EQ(b.cameras[1].position, glm::dvec3(-1.0, -2.0, 300.0));
    EXPECT_EQ(b.cameras[0].fov_y_deg, 30.0);
    EXPECT_EQ(b.sun.color, a.sun.color);
    EXPECT_EQ(b.sun.ambient, a.sun.ambient);
    EXPECT_EQ(b.image.width, 64);
    ASSERT_TRUE(b.fog.has_value());
    EXPECT_EQ(kiri::geometry::scene_to_json(b), kiri::geometry::scene_to_json(a));
}

TEST(Scene, CamerasByNameAndAutomaticFraming)
{
    Scene s = parse_scene(R"({"terrain": {"path": "t.tif"},
        "cameras": [{"name": "a", "position": [1, 2, 3], "target": [4, 5, 6]}]})",
                          "s.json", "/");
    EXPECT_EQ(s.camera("", {}, {}).name, "a");
    EXPECT_EQ(s.camera("a", {}, {}).position, glm::dvec3(1, 2, 3));
    try {
        s.camera("b", {}, {});
        FAIL();
    } catch (const kiri::InputError& e) {
        EXPECT_EQ(e.field(), "/cameras");
        EXPECT_NE(std::string(e.what()).find("no camera named \"b\" (cameras: a)"), std::string::npos);
    }
    s.cameras.clear();
    const auto c = s.camera("", {-1000, -1000, 0}, {1000, 1000, 200});
    EXPECT_EQ(c.target, glm::dvec3(0, 0, 100));
    // From the south-west, looking down 35 degrees, far enough to see the whole box in 45 degrees.
    const glm::dvec3 d = c.position - c.target;
    EXPECT_NEAR(d.x, d.y, 1e-9);
    EXPECT_LT(d.x, 0.0);
    EXPECT_NEAR(std::atan2(d.z, std::hypot(d.x, d.y)), 35.0 * M_PI / 180.0, 1e-12);
    EXPECT_NEAR(std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z) * std::sin(22.5 * M_PI / 180.0),
                0.5 * std::sqrt(2000.0 * 2000.0 * 2 + 200.0 * 200.0), 1e-6);
}

TEST(Scene, LoadSceneNamesMissingFile)
{
    try {
        kiri::geometry::load_scene("/no/such/scene.json");
        FAIL();
    } catch (const kiri::InputError& e) {
        EXPECT_STREQ(e.what(), "/no/such/scene.json: no such file");
    }
}

}  // namespace

namespace {

TEST(Scene, MoreErrorClasses)
{
    // JSON has no NaN or Inf, but 1e400 overflows double while parsing: refused, naming the file.
    EXPECT_EQ(error_of(R"({"terrain": {"path": "t.tif", "vertical_offset": 1e400}})"),
              "s.json: malformed JSON: number overflow parsing '1e400' (not a finite number)");
    EXPECT_EQ(error_of(R"({"terrain": {"path": "t.tif"}, "image": {"width": 18446744073709551615}})"),
              "s.json: /image/width: must be in [1, 16384], got 18446744073709551615");
    EXPECT_EQ(error_of(R"({"terrain": {"path": "t.tif"}, "image": {"width": -3}})"),
              "s.json: /image/width: must be in [1, 16384], got -3");
    EXPECT_EQ(error_of(R"({"terrain": {"path": "t.tif"}, "cameras": [
        {"name": "a", "position": [0,0,1], "target": [0,0,0]},
        {"name": "a", "position": [0,0,2], "target": [0,0,0]}]})"),
              "s.json: /cameras/1/name: duplicate camera name \"a\"");
    EXPECT_EQ(error_of(R"({"terrain": {"path": "t.tif"}, "sun": {"color": [1, -0.5, 1]}})"),
              "s.json: /sun/color/1: must be >= 0");
    EXPECT_EQ(error_of(R"({"terrain": {"path": "t.tif"}, "cameras": {"name": "a"}})"),
              "s.json: /cameras: expected an array of cameras");
    EXPECT_EQ(error_of(R"({"terrain": {"path": "t.tif"}, "image": [640, 480]})"), "s.json: /image: expected an object");
    EXPECT_EQ(error_of(R"([1, 2])"), "s.json: /: expected an object");
    EXPECT_EQ(error_of(R"({"terrain": {"path": ""}})"), "s.json: /terrain/path: must not be empty");
    EXPECT_EQ(
        error_of(R"({"terrain": {"path": "t.tif"}, "cameras": [{"position": [0,0,1], "target": [0,0,0], "zoom": 2}]})"),
        "s.json: /cameras/0/zoom: unknown key (expected one of: fov, name, position, target)");
}

TEST(Scene, SunDirectionIsNormalisedAndAbsolutePathsKept)
{
    const Scene s =
        parse_scene(R"({"terrain": {"path": "/data/t.tif"}, "sun": {"direction": [3, 0, 4]}})", "s.json", "/scenes");
    EXPECT_EQ(s.terrain.path, std::filesystem::path("/data/t.tif"));
    EXPECT_DOUBLE_EQ(s.sun.direction.x, 0.6);
    EXPECT_DOUBLE_EQ(s.sun.direction.y, 0.0);
    EXPECT_DOUBLE_EQ(s.sun.direction.z, 0.8);
}

}  // namespace

namespace {

// Every bundled scene parses, its terrain path resolves to an existing file, and it survives a
// write/read round trip unchanged.
TEST(Scene, BundledScenesLoadAndRoundTrip)
{
    int count = 0;
    for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(KIRI_DATA_DIR) / "scenes")) {
        if (entry.path().extension() != ".json")
            continue;
        ++count;
        SCOPED_TRACE(entry.path().string());
        const Scene a = kiri::geometry::load_scene(entry.path());
        EXPECT_TRUE(std::filesystem::is_regular_file(a.terrain.path)) << a.terrain.path;
        EXPECT_FALSE(a.cameras.empty());
        const std::string text = kiri::geometry::scene_to_json(a);
        const Scene b = parse_scene(text, "again.json", "/");
        EXPECT_EQ(kiri::geometry::scene_to_json(b), text);
    }
    EXPECT_GE(count, 1);
}

TEST(Scene, DefaultSceneHasTheDocumentedCameras)
{
    const Scene s = kiri::geometry::load_scene(std::filesystem::path(KIRI_DATA_DIR) / "scenes/jacksboro.json");
    EXPECT_EQ(s.cameras.front().name, "default");
    EXPECT_EQ(s.camera("top", {}, {}).name, "top");
    EXPECT_EQ(s.image.width, 1280);
    EXPECT_EQ(s.image.height, 720);
    // A low sun from the side: well above the horizon but below 30 degrees, for relief.
    const double elevation = std::asin(s.sun.direction.z) * 180.0 / M_PI;
    EXPECT_GT(elevation, 5.0);
    EXPECT_LT(elevation, 30.0);
    EXPECT_TRUE(s.fog.has_value());
}

}  // namespace

TEST(Scene, FogVerticalQuantitiesFollowTheExaggeration)
{
    const Scene s = parse_scene(R"({"terrain": {"path": "t.tif", "exaggeration": 1.5},
        "fog": {"mode": "lake", "altitude": 420, "offset": 40, "clearance": 10, "thickness": 100,
                "smoothing": 300}})",
                                "s.json", "/");
    const kiri::geometry::FogSpec w = kiri::geometry::world_fog_spec(s);
    EXPECT_EQ(w.fit.altitude, 630.0);
    EXPECT_EQ(w.fit.offset, 60.0);
    EXPECT_EQ(w.fit.clearance, 15.0);
    EXPECT_EQ(w.fit.thickness, 150.0);
    EXPECT_EQ(w.fit.smoothing_length, 300.0);  // horizontal: unchanged
    EXPECT_EQ(s.fog->fit.altitude, 420.0);     // the scene keeps what the user wrote
    const Scene none = parse_scene(minimal, "s.json", "/");
    EXPECT_THROW(kiri::geometry::world_fog_spec(none), kiri::InputError);
}

namespace {

// The fog's motion is the medium's; the layers' old names of its keys still read, as the medium's.
TEST(Scene, TheMediumOwnsTheFogsMotion)
{
    const Scene s = parse_scene(
        R"({"terrain": {"path": "t.tif"}, "medium": {"detail": 0.3, "wind": [1, -2], "time": 5, "detail_scale": 800,
            "detail_layers": 22, "dissipation_half_life": 60}})",
        "s.json", "/scenes");
    EXPECT_EQ(s.medium.detail, 0.3);
    EXPECT_EQ(s.medium.wind, glm::dvec2(1, -2));
    EXPECT_EQ(s.medium.time, 5.0);
    const std::string text = kiri::geometry::scene_to_json(s);
    EXPECT_EQ(parse_scene(text, "s.json", "/scenes").medium, s.medium);
    // Written under "medium" (sections in key order: layers, medium, particles).
    const std::size_t layers = text.find("\"layers\""), medium = text.find("\"medium\""),
                      particles = text.find("\"particles\""), detail = text.find("\"detail\"");
    EXPECT_TRUE(layers < medium && medium < detail && detail < particles) << text;
    const Scene old =
        parse_scene(R"({"terrain": {"path": "t.tif"}, "layers": {"detail": 0.3, "time": 5}})", "s.json", "/scenes");
    EXPECT_EQ(old.medium.detail, 0.3);
    EXPECT_EQ(old.medium.time, 5.0);
    EXPECT_EQ(error_of(R"({"terrain": {"path": "t.tif"}, "layers": {"time": 5}, "medium": {"time": 6}})"),
              "s.json: /layers/time: the old name of /medium/time, which the scene gives too: give only that");
    EXPECT_EQ(error_of(R"({"terrain": {"path": "t.tif"}, "layers": {"detail": 2}})"),
              "s.json: /layers/detail: must be in [0, 1], got 2");
    const kiri::geometry::MediumDetail d = kiri::geometry::medium_detail(s.medium);
    EXPECT_EQ(d.detail, 0.3);
    EXPECT_EQ(d.detail_scale, 800.0);
    EXPECT_EQ(d.layers, 22.0);
    EXPECT_EQ(d.wind, glm::dvec2(1, -2));
    EXPECT_EQ(d.dissipation_half_life, 60.0);
}

}  // namespace
