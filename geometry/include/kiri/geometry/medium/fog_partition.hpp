#pragma once
//! \file fog_partition.hpp
//! Combined rendering (docs/combined.md): the one Medium's extinction is shared out between the
//! renderers, with shares that sum to 1 at every point,
//!
//!   sigma_t(p) = sigma_t(p) [ w_particles(h) + (1 - w_particles(h)) (w_near(d) + w_far(d)) ],
//!   w_near(d) + w_far(d) = 1,
//!
//! so every renderer draws its own share of the fog and the transmittance along any ray is
//! the Medium's exactly (the shares multiply: exp(-a) exp(-b) = exp(-(a + b))). The froxels
//! draw the near share (the inside of the cloud, where the layers would look hollow), the
//! layers the far share (cheap at a distance), the particles the top band of the shell
//! (billowy tops) where the fog is thick enough for them. The distance weights are smooth (a
//! quintic step over [near_start, near_end]), so no seam shows where one renderer hands over to
//! the next.
//!
//! By default the froxels draw every distance (near_start = near_end = fog_partition_everywhere):
//! since they light the height fog at its own points and follow it with their slices they are
//! within 0.5-3.4 % of the reference from every view but the lake's threads, the layers 0.9-11 %
//! (docs/combined.md), at no more cost. Giving near_end (or near_start) hands the far fog to the
//! layers again.
//!
//! The GLSL copies are in render/shaders/fog_partition.glsl.
#include <string>

#include "kiri/geometry/core/fields.hpp"

namespace kiri::geometry {

//! The default hand-over distance: farther than any fog a scene holds (the froxels draw it all).
inline constexpr double fog_partition_everywhere = 1e7;

struct FogPartition {
    double near_start = fog_partition_everywhere;
    double near_end = fog_partition_everywhere;
    double particle_share = 0.5;
    double particle_band = 0.35;
    //! The fog's thickness, in the particles' radii, from which they take their whole share.
    double particle_depth = 8.0;
    //! Not a key: the particles' radius (metres) the depth is counted in, the one their sampler
    //! counted it in (ParticleCloud::share_radius); 0: none known, the particles share every depth.
    double particle_radius = 0.0;
    bool operator==(const FogPartition&) const = default;
};

//! The "combined" section. Given alone, near_start sets near_end to 4 times it, and near_end
//! near_start to a quarter of it (the hand-over's width of the defaults before 2026-11-28: 400
//! and 1600 m).
template <fields_of<FogPartition> O, class V>
void visit_fields(O& o, V&& v)
{
    v(o.near_start,
      {.key = "near_start",
       .unit = "m",
       .range = closed(0, 1e7),
       .doc = "from the eye: the froxels draw all the fog nearer (default: all of it)",
       .widget = closed(0, 10000)});
    v(o.near_end,
      {.key = "near_end",
       .unit = "m",
       .range = closed({o.near_start, "near_start"}, 1e7),
       .doc = "from the eye: the layers draw all the fog farther (default: none)",
       .widget = closed({o.near_start, "near_start"}, 20000)});
    v(o.particle_share,
      {.key = "particle_share",
       .range = closed(0, 1),
       .doc = "the particles' share at the shell's top; 0: no particles"});
    v(o.particle_band,
      {.key = "particle_band", .range = left_open(0, 1), .doc = "the top fraction of the shell the particles share"});
    v(o.particle_depth,
      {.key = "particle_depth",
       .unit = "radii",
       .range = closed(0, 1000),
       .doc = "the fog's thickness, in the particles' radii, from which they take their whole share (none below a "
              "third of it); 0: every thickness",
       .widget = closed(0, 30)});
}

//! Quintic smooth step of x from a to b (0 below, 1 above; C2): a == b gives a step at a.
double smoother_step(double a, double b, double x);

//! The layers' share of the non-particle fog at view distance d: 0 near, 1 far.
double far_share(const FogPartition& p, double distance);
//! The particles' share by the fog's thickness t (metres, top - floor of its column): 0 where
//! the fog is thinner than a third of particle_depth radii, rising to 1 at particle_depth radii
//! (a quintic step); 1 everywhere with particle_depth or particle_radius 0. A particle larger
//! than its fog spills above its top and into the ground (docs/combined.md).
double particle_depth_share(const FogPartition& p, double thickness);
//! The fog's thickness (metres) where that step starts and where it is whole: particle_depth / 3
//! and particle_depth radii; {0, 0} with particle_depth or particle_radius 0 (every thickness).
//! The GPU's twin takes these two (fog_partition.glsl's u_partition_depth).
struct ParticleDepthRange {
    double start = 0.0, full = 0.0;
};
ParticleDepthRange particle_depth_range(const FogPartition& p);
//! The particles' share at height fraction h in [0, 1] of the shell, in fog `thickness` metres
//! thick: 0 below the band, rising to particle_share at the top, times particle_depth_share.
double particle_share(const FogPartition& p, double h, double thickness);

//! What each renderer draws at one point (sums to 1).
struct FogShares {
    double froxels = 0.0, layers = 0.0, particles = 0.0;
};
FogShares fog_shares(const FogPartition& p, double distance, double h, double thickness);

//! \throw InputError(label, "/combined/<key>", reason) for values outside their ranges.
void validate_fog_partition(const FogPartition& p, const std::string& label = {});

}  // namespace kiri::geometry
