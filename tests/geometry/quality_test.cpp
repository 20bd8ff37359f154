// Quality presets and the "combined" section (quality.hpp, fog_partition.hpp): a preset sets
// what the scene leaves unset, the scene's own keys win, saved scenes read back equal, and bad
// values are one-line errors naming the key.
#include <gtest/gtest.h>

#include <string>

#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/medium/fog_partition.hpp"
#include "kiri/geometry/scene/scene.hpp"

namespace kiri::geometry {
namespace {

Scene parse(const std::string& extra)
{
    return parse_scene(R"({"terrain": {"path": "dem.tif"})" + extra + "}", "s.json", "/d");
}

std::string field_of(const std::string& extra)
{
    try {
        parse(extra);
    } catch (const InputError& e) {
        return e.field();
    }
    return "accepted";
}

TEST(Quality, NoPresetKeepsTheSectionsDefaults)
{
    const Scene s = parse("");
    EXPECT_FALSE(s.quality);
    EXPECT_EQ(s.layers.count, LayerOptions{}.count);
    EXPECT_EQ(s.froxel.width, FroxelOptions{}.width);
    EXPECT_EQ(s.combined.particle_share, FogPartition{}.particle_share);
}

TEST(Quality, HighIsTheDefaults)
{
    const Scene s = parse(R"(, "quality": "high")");
    EXPECT_EQ(s.layers.count, LayerOptions{}.count);
    EXPECT_EQ(s.layers.resolution, LayerOptions{}.resolution);
    EXPECT_EQ(s.particles.count, ParticleOptions{}.count);
    EXPECT_EQ(s.particles.resolution, ParticleOptions{}.resolution);
    EXPECT_EQ(s.froxel.width, FroxelOptions{}.width);
    EXPECT_EQ(s.froxel.height, FroxelOptions{}.height);
    EXPECT_EQ(s.froxel.slices, FroxelOptions{}.slices);
    EXPECT_EQ(s.froxel.pixel_steps, FroxelOptions{}.pixel_steps);
    EXPECT_EQ(s.combined.particle_share, FogPartition{}.particle_share);
}

TEST(Quality, PresetsRiseAndTheScenesKeysWin)
{
    const Scene low = parse(R"(, "quality": "low")");
    const Scene ultra = parse(R"(, "quality": "ultra")");
    ASSERT_TRUE(low.quality);
    EXPECT_EQ(*low.quality, Quality::low);
    EXPECT_LT(low.layers.count, ultra.layers.count);
    EXPECT_LT(low.froxel.slices, ultra.froxel.slices);
    EXPECT_LT(low.particles.resolution, ultra.particles.resolution);
    EXPECT_EQ(low.combined.particle_share, 0.0);  // low draws no particles
    // The scene's own key wins over the preset; the preset fills the rest of that section.
    const Scene mixed = parse(R"(, "quality": "low", "layers": {"count": 40}, "froxel": {"distribution": "log2"})");
    EXPECT_EQ(mixed.layers.count, 40);
    EXPECT_EQ(mixed.layers.resolution, low.layers.resolution);
    EXPECT_EQ(mixed.froxel.width, low.froxel.width);
    EXPECT_EQ(mixed.froxel.distribution, SliceDistribution::log2);
}

TEST(Quality, SavedScenesReadBackEqual)
{
    const Scene a =
        parse(R"(, "quality": "medium", "combined": {"near_start": 250, "near_end": 900, "particle_band": 0.5})");
    EXPECT_EQ(a.combined.near_start, 250.0);
    EXPECT_EQ(a.combined.near_end, 900.0);
    EXPECT_EQ(a.combined.particle_band, 0.5);
    // (The first write normalises the sun's direction; from then on it is a fixed point.)
    const Scene b = parse_scene(scene_to_json(a), "again.json", "/d");
    const std::string text = scene_to_json(b);
    EXPECT_EQ(scene_to_json(parse_scene(text, "third.json", "/d")), text);
    EXPECT_EQ(b.layers.count, a.layers.count);
    EXPECT_EQ(b.froxel.slices, a.froxel.slices);
    EXPECT_EQ(b.combined.near_end, 900.0);
    ASSERT_TRUE(b.quality);
    EXPECT_EQ(*b.quality, Quality::medium);
}

TEST(Quality, TheFroxelsDrawEveryDistanceUnlessAHandOverIsGiven)
{
    // By default the froxels draw every distance and the layers nothing; one end of a hand-over
    // given alone sets the other: a hand-over 4 times as far as it starts.
    const Scene none = parse("");
    EXPECT_EQ(none.combined.near_start, fog_partition_everywhere);
    EXPECT_EQ(none.combined.near_end, fog_partition_everywhere);
    EXPECT_EQ(fog_shares(none.combined, 5e4, 0.0, 100.0).froxels, 1.0);  // 50 km off: still theirs
    const Scene end = parse(R"(, "combined": {"near_end": 1600})");
    EXPECT_EQ(end.combined.near_start, 400.0);
    EXPECT_EQ(end.combined.near_end, 1600.0);
    EXPECT_EQ(fog_shares(end.combined, 2000.0, 0.0, 100.0).layers, 1.0);
    const Scene start = parse(R"(, "combined": {"near_start": 300})");
    EXPECT_EQ(start.combined.near_start, 300.0);
    EXPECT_EQ(start.combined.near_end, 1200.0);
    const Scene far = parse(R"(, "combined": {"near_start": 5e6})");
    EXPECT_EQ(far.combined.near_end, fog_partition_everywhere);
}

TEST(Quality, BadValuesNameTheirKey)
{
    EXPECT_EQ(field_of(R"(, "quality": "best")"), "/quality");
    EXPECT_EQ(field_of(R"(, "quality": 3)"), "/quality");
    EXPECT_EQ(field_of(R"(, "combined": {"near_start": -5})"), "/combined/near_start");
    EXPECT_EQ(field_of(R"(, "combined": {"near_start": 500, "near_end": 100})"), "/combined/near_end");
    EXPECT_EQ(field_of(R"(, "combined": {"particle_share": 2})"), "/combined/particle_share");
    EXPECT_EQ(field_of(R"(, "combined": {"particle_band": 0})"), "/combined/particle_band");
    EXPECT_EQ(field_of(R"(, "combined": {"far": 1})"), "/combined/far");
    EXPECT_EQ(field_of(R"(, "layers": {"resolution": 0.05})"), "/layers/resolution");
    // A preset under a section of the wrong type leaves the error to that section's reader.
    EXPECT_EQ(field_of(R"(, "quality": "low", "layers": 7)"), "/layers");
}

}  // namespace
}  // namespace kiri::geometry
