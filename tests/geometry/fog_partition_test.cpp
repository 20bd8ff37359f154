// The combined renderers' shares of the Medium (fog_partition.hpp): they sum to 1 everywhere,
// hand over smoothly (no seam), and bad values are refused with the key named.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/medium/fog_partition.hpp"

namespace kiri::geometry {
namespace {

FogPartition partition()
{
    FogPartition p;
    p.near_start = 300.0;
    p.near_end = 1500.0;
    p.particle_share = 0.6;
    p.particle_band = 0.4;
    p.particle_depth = 12.0;
    p.particle_radius = 50.0;  // whole from 600 m of fog, none below 200 m
    return p;
}

TEST(FogPartition, SharesSumToOneEverywhere)
{
    const FogPartition p = partition();
    for (double d : {0.0, 100.0, 300.0, 777.0, 1500.0, 4e4, std::numeric_limits<double>::infinity()})
        for (double h : {0.0, 0.3, 0.6, 0.8, 1.0})
            for (double t : {0.0, 150.0, 333.0, 600.0, 1e4, std::nan("")}) {
                const FogShares s = fog_shares(p, d, h, t);
                EXPECT_NEAR(s.froxels + s.layers + s.particles, 1.0, 1e-15) << d << " " << h << " " << t;
                EXPECT_GE(s.froxels, 0.0);
                EXPECT_GE(s.layers, 0.0);
                EXPECT_GE(s.particles, 0.0);
            }
}

TEST(FogPartition, NearIsFroxelsFarIsLayersTopIsParticles)
{
    const FogPartition p = partition();
    EXPECT_EQ(fog_shares(p, 100.0, 0.0, 1000.0).froxels, 1.0);
    EXPECT_EQ(fog_shares(p, 2000.0, 0.0, 1000.0).layers, 1.0);
    EXPECT_DOUBLE_EQ(fog_shares(p, 2000.0, 1.0, 1000.0).particles, 0.6);
    EXPECT_DOUBLE_EQ(fog_shares(p, 2000.0, 1.0, 1000.0).layers, 0.4);
    EXPECT_EQ(fog_shares(p, 2000.0, 0.6, 1000.0).particles, 0.0);  // the band starts at 1 - 0.4
    // Halfway through the hand-over the quintic step is exactly 1/2.
    EXPECT_DOUBLE_EQ(far_share(p, 900.0), 0.5);
    // Sky rays (infinite distance) are the layers'.
    EXPECT_EQ(far_share(p, std::numeric_limits<double>::infinity()), 1.0);
}

TEST(FogPartition, TheParticlesShareOnlyFogThickForThem)
{
    // particle_depth 12 radii of 50 m: none in fog thinner than 200 m, all of the band's share
    // from 600 m, the quintic step between (1/2 at 400 m, no kink at either end).
    FogPartition p = partition();
    EXPECT_EQ(particle_depth_share(p, 0.0), 0.0);
    EXPECT_EQ(particle_depth_share(p, 200.0), 0.0);
    EXPECT_DOUBLE_EQ(particle_depth_share(p, 400.0), 0.5);
    EXPECT_EQ(particle_depth_share(p, 600.0), 1.0);
    EXPECT_EQ(particle_depth_share(p, std::nan("")), 0.0);  // no fog known: none
    const double e = 1e-3;
    EXPECT_NEAR((particle_depth_share(p, 200.0 + e) - particle_depth_share(p, 200.0)) / e, 0.0, 1e-6);
    EXPECT_NEAR((particle_depth_share(p, 600.0) - particle_depth_share(p, 600.0 - e)) / e, 0.0, 1e-6);
    // At the top of fog 400 m thick the particles draw half their share, the froxels the rest.
    EXPECT_DOUBLE_EQ(fog_shares(p, 100.0, 1.0, 400.0).particles, 0.3);
    EXPECT_DOUBLE_EQ(fog_shares(p, 100.0, 1.0, 400.0).froxels, 0.7);
    // No radius known (no particles sampled yet), or depth 0: every thickness.
    p.particle_radius = 0.0;
    EXPECT_EQ(particle_depth_share(p, 10.0), 1.0);
    p.particle_radius = 50.0;
    p.particle_depth = 0.0;
    EXPECT_EQ(particle_depth_share(p, 10.0), 1.0);
}

TEST(FogPartition, HandOverIsSmoothAndMonotone)
{
    const FogPartition p = partition();
    double previous = -1.0;
    for (double d = 0.0; d <= 2000.0; d += 1.0) {
        const double w = far_share(p, d);
        EXPECT_GE(w, previous);
        previous = w;
    }
    // No kink where it starts and ends: the slope (finite differences) is 0 there, and its
    // largest value is the quintic's 15/8 over the band's width.
    const double e = 1e-3;
    EXPECT_NEAR((far_share(p, 300.0 + e) - far_share(p, 300.0)) / e, 0.0, 1e-6);
    EXPECT_NEAR((far_share(p, 1500.0) - far_share(p, 1500.0 - e)) / e, 0.0, 1e-6);
    EXPECT_NEAR((far_share(p, 900.0 + e) - far_share(p, 900.0 - e)) / (2 * e), 15.0 / 8.0 / 1200.0, 1e-9);
}

TEST(FogPartition, NoParticlesMeansNoParticleShare)
{
    FogPartition p = partition();
    p.particle_share = 0.0;
    EXPECT_EQ(particle_share(p, 1.0, 1000.0), 0.0);
    const FogShares s = fog_shares(p, 900.0, 1.0, 1000.0);
    EXPECT_DOUBLE_EQ(s.froxels, 0.5);
    EXPECT_DOUBLE_EQ(s.layers, 0.5);
}

TEST(FogPartition, EqualEndsGiveAStepNotANaN)
{
    FogPartition p = partition();
    p.near_start = p.near_end = 500.0;
    EXPECT_EQ(far_share(p, 499.0), 0.0);
    EXPECT_EQ(far_share(p, 500.0), 1.0);
    EXPECT_EQ(particle_share(p, std::nan(""), 1000.0), 0.0);
}

TEST(FogPartition, BadValuesNameTheirKey)
{
    auto field_of = [](FogPartition p) {
        try {
            validate_fog_partition(p, "scene.json");
        } catch (const InputError& e) {
            return e.field();
        }
        return std::string("accepted");
    };
    EXPECT_EQ(field_of(partition()), "accepted");
    FogPartition p = partition();
    p.near_start = -1.0;
    EXPECT_EQ(field_of(p), "/combined/near_start");
    p = partition();
    p.near_end = 100.0;
    EXPECT_EQ(field_of(p), "/combined/near_end");
    p = partition();
    p.particle_share = 1.5;
    EXPECT_EQ(field_of(p), "/combined/particle_share");
    p = partition();
    p.particle_band = 0.0;
    EXPECT_EQ(field_of(p), "/combined/particle_band");
    p = partition();
    p.near_end = std::nan("");
    EXPECT_EQ(field_of(p), "/combined/near_end");
}

}  // namespace
}  // namespace kiri::geometry
