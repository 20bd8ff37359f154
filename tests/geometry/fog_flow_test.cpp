// Flow of fog over a pass: conservation, positivity, any time step, determinism,
// the spill into the next basin, and evaporation on the way down.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "fog_test_terrains.hpp"
#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/placement/fog_columns.hpp"
#include "kiri/geometry/placement/fog_fill.hpp"
#include "kiri/geometry/placement/fog_flow.hpp"

using namespace kiri::geometry;
using kiri::test::make_heightfield;

namespace {

// Two basins (floors 100 m at x = -500 and +500) and a saddle of 200 m at the origin, the
// whole inside a rim that keeps everything on the grid (it rises to 400 m at the border).
double basins(double x, double y)
{
    const double d = std::min((x - 500.0) * (x - 500.0), (x + 500.0) * (x + 500.0));
    const double bowl = 100.0 + (d + y * y) / 2500.0;
    const double r = std::max(std::abs(x) / 1000.0, std::abs(y) / 600.0);
    return std::max(bowl, 400.0 * std::pow(r, 8.0));
}

struct Case {
    Heightfield hf = make_heightfield(201, 121, 10.0, -1000.0, -600.0, basins);
    FogColumns fog;
    Case(double top)
    {
        FillOptions o;
        o.top = top;
        o.seeds.points = {{-500.0, 0.0}};
        fog = fill_columns(hf, fill_fog(hf, o));
    }
    double volume(const std::vector<double>& h) const
    {
        double v = 0.0;
        for (double t : h)
            v += t * hf.dx * hf.dy;
        return v;
    }
    double volume_right(const std::vector<double>& h) const
    {
        double v = 0.0;
        for (int j = 0; j < hf.ny; ++j)
            for (int i = 0; i < hf.nx; ++i)
                v += hf.x_of(i) > 50.0 ? h[std::size_t(j) * hf.nx + i] * hf.dx * hf.dy : 0.0;
        return v;
    }
};

FlowOptions wind_east(double evaporation)
{
    FlowOptions o;
    o.wind = {6.0, 0.0};
    o.inversion_strength = 2.0;
    o.evaporation_depth = evaporation;
    return o;
}

}  // namespace

TEST(FogFlow, WithoutEvaporationTheVolumeIsKeptAndNeverNegative)
{
    const Case c(195.0);                      // 5 m below the saddle
    for (double dt : {10.0, 60.0, 3600.0}) {  // the last one crosses the whole grid in one step
        const FlowOptions o = wind_east(0.0);
        FlowState st = make_flow_state(c.hf, c.fog, o);
        const double v0 = c.volume(flow_thickness(c.hf, st, o));
        for (int s = 0; s < 40; ++s) {
            flow_step(c.hf, st, o, dt);
            const std::vector<double> h = flow_thickness(c.hf, st, o);
            for (double t : h)
                ASSERT_GE(t, 0.0);
            ASSERT_NEAR((c.volume(h) + st.outflow_m3) / v0, 1.0, 1e-9) << "dt " << dt << " step " << s;
        }
        EXPECT_EQ(st.evaporated_m3, 0.0);
        EXPECT_GT(st.spilled_m3, 0.0) << dt;
    }
}

TEST(FogFlow, WindBlowsFogOverTheSaddleIntoTheNextBasin)
{
    const Case c(195.0);
    FlowOptions o = wind_east(0.0);
    o.duration = 3 * 3600.0;
    FlowReport calm_report, windy;
    FlowOptions calm = o;
    calm.wind = {0.0, 0.0};
    calm.min_thickness = 0.0;
    const FogColumns still = flow_fog(c.hf, c.fog, calm, &calm_report);
    // No wind: the pool stays as filled (same volume, nothing over the saddle).
    EXPECT_EQ(calm_report.spilled_m3, 0.0);
    for (std::size_t k = 0; k < c.fog.mask.size(); ++k)
        EXPECT_NEAR(still.top[k] - still.bottom[k], c.fog.thickness(k), 1e-9);
    const FogColumns blown = flow_fog(c.hf, c.fog, o, &windy);
    std::vector<double> h(c.fog.mask.size());
    for (std::size_t k = 0; k < h.size(); ++k)
        h[k] = blown.top[k] - blown.bottom[k];
    EXPECT_GT(windy.max_tilt_m, 5.0);  // the set-up lifts the downwind end above the saddle
    EXPECT_GT(c.volume_right(h), 0.01 * windy.volume_before_m3);
    // Evaporation on the way down leaves less in the lee basin.
    FlowReport dry;
    FlowOptions wet = wind_east(20.0);
    wet.duration = o.duration;
    const FogColumns evaporating = flow_fog(c.hf, c.fog, wet, &dry);
    std::vector<double> he(h.size());
    for (std::size_t k = 0; k < h.size(); ++k)
        he[k] = evaporating.top[k] - evaporating.bottom[k];
    EXPECT_GT(dry.evaporated_m3, 0.0);
    EXPECT_LT(c.volume_right(he), c.volume_right(h));
}

TEST(FogFlow, TheSameInputGivesTheSameBytes)
{
    const Case c(195.0);
    const FlowOptions o = wind_east(30.0);
    const FogColumns a = flow_fog(c.hf, c.fog, o), b = flow_fog(c.hf, c.fog, o);
    ASSERT_EQ(a.top.size(), b.top.size());
    EXPECT_EQ(std::memcmp(a.top.data(), b.top.data(), a.top.size() * sizeof(double)), 0);
    EXPECT_EQ(a.mask, b.mask);
}

TEST(FogFlow, RefusesOptionsOutOfRange)
{
    const Case c(195.0);
    FlowOptions o;
    o.time_step = 0.0;
    EXPECT_THROW(flow_fog(c.hf, c.fog, o), kiri::InputError);
    o = FlowOptions{};
    o.wind = {200.0, 0.0};
    try {
        flow_fog(c.hf, c.fog, o, nullptr, "s.json");
        FAIL();
    } catch (const kiri::InputError& e) {
        EXPECT_EQ(e.field(), "flow/wind");
    }
}
