// The field lists (core/fields.hpp) of every scene section: keys unique, defaults inside their
// ranges (or standing for "not given"), the preview's slider ranges inside the ranges they
// narrow; the range messages the scene reader and the validators give.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <type_traits>

#include "kiri/geometry/core/fields.hpp"
#include "kiri/geometry/scene/scene.hpp"

namespace kiri::geometry {
namespace {

template <class O, class Fields = MainFields>
void expect_sound(const char* section, Fields fields = {})
{
    const O defaults{};
    std::set<std::string> keys;
    fields(defaults, [&](const auto& m, const FieldInfo& info) {
        using T = std::remove_cvref_t<decltype(m)>;
        const std::string key(info.key);
        EXPECT_FALSE(key.empty()) << section;
        EXPECT_FALSE(info.doc.empty()) << section << "/" << key;
        if (info.element <= 0) {
            EXPECT_TRUE(keys.insert(key).second) << section << "/" << key << " is declared twice";
        }
        if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) {
            if (!info.omit_default) {
                EXPECT_TRUE(info.range.contains(double(m))) << section << "/" << key << ": default outside its range";
            }
            if (info.widget.bounded()) {
                // A slider may reach the default that stands for "not given" (0 = automatic).
                const double lo = info.omit_default ? std::min(info.range.lo.value, double(m)) : info.range.lo.value;
                EXPECT_GE(info.widget.lo.value, lo) << section << "/" << key;
                EXPECT_LE(info.widget.hi.value, info.range.hi.value) << section << "/" << key;
            }
        }
        if constexpr (std::is_enum_v<T>) {
            EXPECT_FALSE(info.choices.empty()) << section << "/" << key << ": an enumeration needs its names";
        }
    });
}

TEST(Fields, EverySectionsListIsSound)
{
    expect_sound<TerrainSpec>("terrain");
    expect_sound<CameraSpec>("cameras");
    expect_sound<SunSpec>("sun");
    expect_sound<ImageSpec>("image");
    expect_sound<FogSpec>("fog");
    expect_sound<FogSpec>("fog/footprint", TerrainFootprintFields{});
    expect_sound<TessellationOptions>("fog/tessellation");
    expect_sound<FillRegionSpec>("fog/fill");
    expect_sound<ValleyOptions>("fog/fill/valleys");
    expect_sound<PlacementSpec>("fog/outline", OutlineFields{});
    expect_sound<FlowOptions>("fog/flow");
    expect_sound<BurnOffOptions>("fog/burn_off");
    expect_sound<LayerOptions>("layers");
    expect_sound<MediumOptions>("medium");
    expect_sound<ParticleOptions>("particles");
    expect_sound<FroxelOptions>("froxel");
    expect_sound<HeightFog>("froxel/height_fog");
    expect_sound<FogPartition>("combined");
}

TEST(Fields, RangeMessagesAreTheScenes)
{
    EXPECT_EQ(range_error(closed(0, 1), 0.5, false), "");
    EXPECT_EQ(range_error(closed(0, 1), 2.0, false), "must be in [0, 1], got 2");
    EXPECT_EQ(range_error(open_range(0, 100), 0.0, false), "must be in (0, 100), got 0");
    EXPECT_EQ(range_error(left_open(0, 86400), -1.0, false), "must be in (0, 86400], got -1");
    EXPECT_EQ(range_error(greater_than(0), 0.0, false), "must be > 0");
    EXPECT_EQ(range_error(at_least(0), -3.0, false), "must be >= 0");
    EXPECT_EQ(range_error(closed(1, 2147483647), 0.0, true), "must be in [1, 2147483647], got 0");
    EXPECT_EQ(range_error(unbounded(), std::numeric_limits<double>::quiet_NaN(), false), "must be a finite number");
    EXPECT_EQ(range_text(closed({3.0, "count"}, 1000), true), "in [count, 1000]");
    EXPECT_EQ(number_text(1e6, false), "1e6");
    EXPECT_EQ(number_text(0.001, false), "0.001");
}

TEST(Fields, ValidatorsNameTheKeyAndTheRange)
{
    LayerOptions layers;
    layers.max_count = 10;  // below count
    try {
        check_fields(layers, "s.json", "/layers");
        FAIL() << "accepted";
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(), "s.json: /layers/max_count: must be in [15, 1000], got 10");
    }
    FroxelOptions froxel;
    froxel.slices = 1;
    try {
        check_fields(froxel, "s.json", "/froxel");
        FAIL() << "accepted";
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(), "s.json: /froxel/size/2: must be in [2, 512], got 1");
    }
    ParticleOptions particles;  // the defaults that stand for "the medium's" are not checked
    EXPECT_NO_THROW(check_fields(particles, "s.json", "/particles"));
}

TEST(Fields, LookupsFindTheMembersInfo)
{
    MediumOptions m;
    EXPECT_EQ(field_of(m, m.detail_scale).key, "detail_scale");
    EXPECT_EQ(field_of(m, m.detail_scale).unit, "m");
    EXPECT_EQ(field_named(m, "visibility").unit, "m");
    EXPECT_THROW(field_named(m, "colour"), std::logic_error);
    LayerOptions layers;
    layers.count = 40;
    EXPECT_EQ(field_of(layers, layers.max_count).range.lo.value, 40.0);  // evaluated with the object's values
}

}  // namespace
}  // namespace kiri::geometry
