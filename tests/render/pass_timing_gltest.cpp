// The per-pass timings of FrameStats are device times a reader can add up: every pass that
// draws took some time, none took longer than the frame that holds it, and the passes (which do
// not overlap) add up to no more than the frame. Timer queries that read 0 for compute passes
// or a raw clock for a draw (llvmpipe's binned scenes) fail here.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "geometry/particle_test_clouds.hpp"
#include "render/froxel_fixture.hpp"

namespace {

namespace g = kiri::geometry;
using kiri::render::Camera;
using kiri::render::FrameStats;
using kiri::render::Renderer;

class PassTimingGl : public kiri::test::GlTest {};

void expect_plausible(const FrameStats& stats, const std::set<std::string>& drawn)
{
    ASSERT_GT(stats.frame_ms, 0.0);
    std::set<std::string> seen;
    double sum = 0.0;
    for (const kiri::render::PassTime& p : stats.passes) {
        seen.insert(p.pass);
        EXPECT_TRUE(std::isfinite(p.gpu_ms) && std::isfinite(p.cpu_ms)) << p.pass;
        EXPECT_GE(p.gpu_ms, 0.0) << p.pass;
        EXPECT_LE(p.gpu_ms, stats.frame_ms) << p.pass << " took longer than its frame";
        if (drawn.count(p.pass)) {
            EXPECT_GT(p.gpu_ms, 0.0) << p.pass << " drew, in no time";
        }
        if (p.pass != "attenuation")  // the buffer's build is a part of the particles' pass
            sum += p.gpu_ms;
    }
    for (const std::string& pass : drawn)
        EXPECT_TRUE(seen.count(pass)) << pass << " not reported";
    EXPECT_LE(sum, stats.frame_ms) << "passes that do not overlap take longer than their frame";
}

TEST_F(PassTimingGl, EveryPassThatDrawsTookTimeAndNoMoreThanItsFrame)
{
    const g::Terrain hill = kiri::test::gaussian_hill();
    const g::Medium fog = kiri::test::slab(0.0, 150.0, 0.01, 640.0);
    g::ParticleCloud cloud = kiri::test::ball_cloud(300, 150.0, 30.0, 0.5);
    for (auto& p : cloud.particles)
        p.position.z -= 600.0;  // over the hill
    Renderer r;
    r.set_terrain(hill);
    r.set_sun(kiri::test::sun());
    g::FroxelOptions o;
    o.width = 20;
    o.height = 12;
    o.slices = 32;
    r.set_froxel_fog(&fog, o);
    r.set_particles(cloud);
    Camera c;
    c.position = {-900.0, -1100.0, 500.0};
    c.target = {0.0, 0.0, 60.0};
    for (int frame = 0; frame < 3; ++frame) {  // the first frame builds (a still); the others move
        c.position.x += 10.0;
        r.draw(c, 160, 96);
        std::set<std::string> drawn = {
            "sky",          "terrain",        "resolve",         "tonemap",          "particles",      "froxel shell",
            "froxel tiles", "froxel density", "froxel lighting", "froxel integrate", "froxel marches", "froxel apply"};
        if (frame > 0)  // the history of a moving view
            drawn.insert("froxel temporal");
        SCOPED_TRACE("frame " + std::to_string(frame));
        expect_plausible(r.last_stats(), drawn);
    }
}

}  // namespace
