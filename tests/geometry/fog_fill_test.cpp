// Priority-flood fill ([Barnes14]): analytic terrains with known answers, and a brute-force
// minimax oracle for the flood levels.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "fog_test_terrains.hpp"
#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/placement/fog_fill.hpp"

using namespace kiri::geometry;
using kiri::test::make_heightfield;

namespace {

// Two round basins, floors at 100 m, centred at x = -500 and x = +500, joined by a saddle of
// ground 200 m at the origin (the grid has a sample there): any path between them crosses the
// column x = 0, where the ground is 200 + y^2 / 2500 >= 200.
double two_basins(double x, double y)
{
    const double d = std::min((x - 500.0) * (x - 500.0), (x + 500.0) * (x + 500.0));
    return 100.0 + (d + y * y) / 2500.0;
}

Heightfield basins() { return make_heightfield(201, 101, 10.0, -1000.0, -500.0, two_basins); }

FillOptions seeded(double top, glm::dvec2 seed)
{
    FillOptions o;
    o.top = top;
    o.seeds.points = {seed};
    return o;
}

std::size_t count_if_cells(const Heightfield& hf, const std::function<bool(int, int)>& pred)
{
    std::size_t n = 0;
    for (int j = 0; j < hf.ny; ++j)
        for (int i = 0; i < hf.nx; ++i)
            n += pred(i, j);
    return n;
}

}  // namespace

TEST(FogFill, TopJustBelowTheSaddleStaysInItsBasin)
{
    const Heightfield hf = basins();
    const FogFill f = fill_fog(hf, seeded(199.999, {-500.0, 0.0}));
    // Exactly the left basin's cells below the top.
    const std::size_t expected =
        count_if_cells(hf, [&](int i, int j) { return hf.x_of(i) < 0.0 && hf.at(i, j) < 199.999; });
    EXPECT_EQ(f.cells, expected);
    for (int j = 0; j < hf.ny; ++j)
        for (int i = 0; i < hf.nx; ++i) {
            const std::size_t k = std::size_t(j) * hf.nx + i;
            if (hf.x_of(i) >= 0.0) {
                ASSERT_EQ(f.mask[k], 0) << i << " " << j;
            }
            if (f.mask[k]) {
                EXPECT_DOUBLE_EQ(f.thickness[k], 199.999 - hf.z[k]);
            } else {
                EXPECT_EQ(f.thickness[k], 0.0);
            }
        }
    ASSERT_TRUE(f.spills);
    EXPECT_DOUBLE_EQ(f.spill_level, 200.0);
    EXPECT_DOUBLE_EQ(f.spill_point.x, 0.0);
    EXPECT_DOUBLE_EQ(f.spill_point.y, 0.0);
    EXPECT_EQ(f.seed_cells, 1);
    EXPECT_FALSE(f.touches_border);
}

TEST(FogFill, TopExactlyAtTheSaddleDoesNotSpill)
{
    const FogFill f = fill_fog(basins(), seeded(200.0, {-500.0, 0.0}));
    EXPECT_TRUE(f.spills);
    EXPECT_DOUBLE_EQ(f.spill_level, 200.0);
    const Heightfield hf = basins();
    for (int i = 0; i < hf.nx; ++i)
        EXPECT_EQ(f.mask[std::size_t(50) * hf.nx + i], hf.x_of(i) < 0.0 && hf.at(i, 50) < 200.0 ? 1 : 0) << i;
}

TEST(FogFill, TopJustAboveTheSaddleFillsBothBasins)
{
    const Heightfield hf = basins();
    const double top = 200.001;
    const FogFill f = fill_fog(hf, seeded(top, {-500.0, 0.0}));
    double volume = 0.0;
    for (std::size_t k = 0; k < hf.size(); ++k) {
        ASSERT_EQ(f.mask[k], hf.z[k] < top ? 1 : 0) << k;
        volume += hf.z[k] < top ? (top - hf.z[k]) * 100.0 : 0.0;
    }
    EXPECT_NEAR(f.volume_m3, volume, 1e-9 * volume);
    EXPECT_FALSE(f.spills);  // no other basin below the top remains
    // Seeded from the right basin, the same fog.
    EXPECT_EQ(fill_fog(hf, seeded(top, {500.0, 0.0})).mask, f.mask);
}

TEST(FogFill, ThePlaneFillsTheHalfBelowTheTop)
{
    // z = 50 + 0.1 x over [-500, 500]: the top at 60 m covers x < 100.
    const Heightfield hf =
        make_heightfield(101, 51, 10.0, -500.0, -250.0, [](double x, double) { return 50.0 + 0.1 * x; });
    const FogFill f = fill_fog(hf, seeded(60.0, {-400.0, 0.0}));
    for (int j = 0; j < hf.ny; ++j)
        for (int i = 0; i < hf.nx; ++i) {
            const std::size_t k = std::size_t(j) * hf.nx + i;
            EXPECT_EQ(f.mask[k], hf.z[k] < 60.0 ? 1 : 0);
            if (f.mask[k]) {
                EXPECT_NEAR(f.thickness[k], 60.0 - (50.0 + 0.1 * hf.x_of(i)), 1e-12);
            }
        }
    EXPECT_TRUE(f.touches_border);
    EXPECT_FALSE(f.spills);
    EXPECT_NEAR(f.max_thickness, 60.0 - (50.0 - 50.0), 1e-12);
}

TEST(FogFill, TheConeHoldsItsAnalyticVolume)
{
    // An inverted cone z = r: fog to the top T is a cone of volume pi T^3 / 3 over a disc of
    // area pi T^2 (the grid's sums converge to both as the cells shrink).
    const double top = 400.0;
    const Heightfield hf =
        make_heightfield(401, 401, 2.5, -500.0, -500.0, [](double x, double y) { return std::hypot(x, y); });
    const FogFill f = fill_fog(hf, seeded(top, {0.0, 0.0}));
    EXPECT_NEAR(f.volume_m3 / (M_PI * top * top * top / 3.0), 1.0, 1e-4);
    EXPECT_NEAR(f.area_m2 / (M_PI * top * top), 1.0, 2e-3);
    EXPECT_DOUBLE_EQ(f.max_thickness, top);
    EXPECT_NEAR(f.mean_thickness, top / 3.0, 0.2);
    EXPECT_FALSE(f.touches_border);
}

TEST(FogFill, NodataCellsAreWallsAndNeverFog)
{
    // A flat valley floor at 0 m cut across by a nodata wall at x = 0 (with the loader's filled
    // heights, also 0 m), and a nodata hole left of it.
    Heightfield hf = make_heightfield(41, 21, 10.0, -200.0, -100.0, [](double, double) { return 0.0; });
    for (int j = 0; j < hf.ny; ++j)
        hf.valid[std::size_t(j) * hf.nx + 20] = 0;
    for (int j = 8; j <= 12; ++j)
        for (int i = 5; i <= 9; ++i)
            hf.valid[std::size_t(j) * hf.nx + i] = 0;
    const FogFill f = fill_fog(hf, seeded(30.0, {-190.0, -90.0}));
    EXPECT_EQ(f.cells, std::size_t(20 * 21 - 25));
    for (int j = 0; j < hf.ny; ++j)
        for (int i = 0; i < hf.nx; ++i) {
            const std::size_t k = std::size_t(j) * hf.nx + i;
            EXPECT_EQ(f.mask[k], i < 20 && hf.valid[k] ? 1 : 0);
            EXPECT_TRUE(std::isfinite(f.thickness[k]));
        }
    // A seed on nodata is refused, naming the seed.
    try {
        fill_fog(hf, seeded(30.0, {-130.0, 0.0}), "s.json");
        FAIL();
    } catch (const kiri::InputError& e) {
        EXPECT_EQ(e.field(), "seeds/0");
        EXPECT_NE(std::string(e.what()).find("nodata"), std::string::npos);
    }
}

TEST(FogFill, ThicknessLimits)
{
    const Heightfield hf = basins();
    FillOptions o = seeded(200.001, {-500.0, 0.0});
    o.max_thickness = 40.0;
    const FogFill capped = fill_fog(hf, o);
    EXPECT_DOUBLE_EQ(capped.max_thickness, 40.0);
    for (std::size_t k = 0; k < hf.size(); ++k)
        if (capped.mask[k]) {
            EXPECT_DOUBLE_EQ(capped.thickness[k], std::min(40.0, 200.001 - hf.z[k]));
        }
    // min_thickness 5 m: the 1 mm sheet over the saddle no longer carries the fog across.
    o.max_thickness = 0.0;
    o.min_thickness = 5.0;
    const FogFill thin = fill_fog(hf, o);
    for (std::size_t k = 0; k < hf.size(); ++k)
        EXPECT_EQ(thin.mask[k], hf.z[k] + 5.0 < 200.001 && hf.x_of(int(k % hf.nx)) < 0.0 ? 1 : 0);
    EXPECT_TRUE(thin.spills);
    EXPECT_DOUBLE_EQ(thin.spill_level, 205.0);
}

TEST(FogFill, AllBasinsIsEveryCellBelowTheTop)
{
    const Heightfield hf = basins();
    FillOptions o;
    o.top = 150.0;
    o.seeds.all_basins = true;
    const FogFill f = fill_fog(hf, o);
    for (std::size_t k = 0; k < hf.size(); ++k)
        EXPECT_EQ(f.mask[k], hf.z[k] < 150.0 ? 1 : 0);
    EXPECT_FALSE(f.spills);
    // The seed mask: a cell in each basin seeds both.
    FillOptions m;
    m.top = 150.0;
    m.seeds.mask.assign(hf.size(), 0);
    m.seeds.mask[std::size_t(50) * hf.nx + 50] = m.seeds.mask[std::size_t(50) * hf.nx + 150] = 1;
    EXPECT_EQ(fill_fog(hf, m).mask, f.mask);
}

TEST(FogFill, FloodLevelsEqualTheMinimaxOracle)
{
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 100.0);
    Heightfield hf = make_heightfield(37, 23, 5.0, 0.0, 0.0, [&](double, double) { return u(rng); });
    hf.valid[100] = hf.valid[101] = hf.valid[140] = 0;
    FillSeeds seeds;
    seeds.points = {{10.0, 10.0}, {150.0, 90.0}};
    const FloodLevels fl = flood_levels(hf, seeds);
    // Oracle: relax level(n) = max(z(n), min over neighbours level) until nothing changes.
    std::vector<double> level(hf.size(), INFINITY);
    for (std::uint32_t s : seed_cells(hf, seeds))
        level[s] = hf.z[s];
    for (bool changed = true; changed;) {
        changed = false;
        for (int j = 0; j < hf.ny; ++j)
            for (int i = 0; i < hf.nx; ++i) {
                const std::size_t k = std::size_t(j) * hf.nx + i;
                if (!hf.valid[k])
                    continue;
                for (int b = std::max(0, j - 1); b <= std::min(hf.ny - 1, j + 1); ++b)
                    for (int a = std::max(0, i - 1); a <= std::min(hf.nx - 1, i + 1); ++a) {
                        const double via = std::max(hf.z[k], level[std::size_t(b) * hf.nx + a]);
                        if (hf.valid[std::size_t(b) * hf.nx + a] && via < level[k]) {
                            level[k] = via;
                            changed = true;
                        }
                    }
            }
    }
    for (std::size_t k = 0; k < hf.size(); ++k) {
        EXPECT_EQ(fl.reached[k], std::isfinite(level[k]) ? 1 : 0) << k;
        if (fl.reached[k]) {
            EXPECT_EQ(fl.level[k], level[k]) << k;
        }
    }
    // The fill at any top is the set of levels below it.
    for (double top : {20.0, 50.0, 80.0}) {
        FillOptions o;
        o.top = top;
        o.seeds = seeds;
        try {
            const FogFill f = fill_fog(hf, o);
            for (std::size_t k = 0; k < hf.size(); ++k)
                EXPECT_EQ(f.mask[k], fl.reached[k] && fl.level[k] < top ? 1 : 0);
            // The spill level: the lowest flood level of a reachable cell below the top that
            // the fog did not reach (another basin).
            double spill = INFINITY;
            for (std::size_t k = 0; k < hf.size(); ++k)
                if (fl.reached[k] && !f.mask[k] && hf.z[k] < top)
                    spill = std::min(spill, fl.level[k]);
            EXPECT_EQ(f.spills, std::isfinite(spill)) << top;
            if (f.spills) {
                EXPECT_EQ(f.spill_level, spill) << top;
            }
        } catch (const kiri::InputError&) {
            EXPECT_GE(std::min(hf.z[seed_cells(hf, seeds)[0]], hf.z[seed_cells(hf, seeds)[1]]), top);
        }
    }
}

TEST(FogFill, BadInputIsRefusedWithTheField)
{
    const Heightfield hf = basins();
    auto field_of = [&](const FillOptions& o) {
        try {
            fill_fog(hf, o, "scene.json");
        } catch (const kiri::InputError& e) {
            EXPECT_EQ(e.file(), "scene.json");
            return e.field() + ": " + e.reason();
        }
        return std::string("accepted");
    };
    EXPECT_EQ(field_of(seeded(150.0, {5000.0, 0.0})).rfind("seeds/0: seed (5000, 0) lies outside the terrain", 0), 0u);
    EXPECT_EQ(field_of(seeded(90.0, {-500.0, 0.0})).rfind("top: the fog top 90 m is at or below every seed", 0), 0u);
    EXPECT_EQ(field_of(seeded(NAN, {-500.0, 0.0})).rfind("top:", 0), 0u);
    FillOptions o = seeded(150.0, {-500.0, 0.0});
    o.min_thickness = -1.0;
    EXPECT_EQ(field_of(o).rfind("min_thickness:", 0), 0u);
    o.min_thickness = 10.0;
    o.max_thickness = 5.0;
    EXPECT_EQ(field_of(o).rfind("max_thickness:", 0), 0u);
    FillOptions none;
    none.top = 150.0;
    EXPECT_EQ(field_of(none).rfind("seeds: no seed", 0), 0u);
    none.seeds.mask.assign(7, 1);
    EXPECT_EQ(field_of(none).rfind("seeds/mask:", 0), 0u);
}
