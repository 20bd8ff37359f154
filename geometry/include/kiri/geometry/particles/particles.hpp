#pragma once
//! \file particles.hpp
//! The fog as a cloud of particles ([Harris01], [Shimada08]): each particle is a
//! sphere of radius r whose optical depth along a ray at distance rho from its centre is
//! tau f(rho / r), f a Gaussian footprint (particle_footprint.hpp). The particles are sampled
//! inside the Medium, blue noise with a density that follows the Medium's, and carry together
//! the Medium's extinction, so they draw the same fog as the layers and the froxels.
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "kiri/geometry/core/fields.hpp"
#include "kiri/geometry/medium/fog_partition.hpp"
#include "kiri/geometry/medium/medium.hpp"

namespace kiri::geometry {

struct Particle {
    glm::dvec3 position{0.0};    //!< centre, world metres
    double radius = 1.0;         //!< metres: the footprint is zero beyond it
    double optical_depth = 0.5;  //!< tau_k: optical depth of the ray through the centre (may be +inf: opaque)
    double albedo = 0.99;        //!< a_k in [0, 1]
    //! The share of its mass that a billboard draws (footprint_share_between): above the terrain
    //! (or the blanket's floor, below) and under the fog's top (above). The rest lies in the
    //! ground, where no ray sees it, or over the top and under the floor, where the fog has none,
    //! so a billboard draws its visible part with tau_k / this (docs/particles.md, "The mass in
    //! the ground"). 1: wholly within, or no terrain and no fog known.
    double above_ground = 1.0;
    //! Where the fog floats above the ground under the particle (a blanket's bottom), the plane of
    //! that floor over the particle's disc: its height at the centre, metres, and its slope
    //! (dz/dx, dz/dy), fitted to the floor there. A billboard draws only the part of the ball above
    //! that plane (the terrain cuts the ball itself). floor -inf: the fog lies on the ground there.
    double floor = -std::numeric_limits<double>::infinity();
    glm::dvec2 floor_slope{0.0};
    //! The plane of the fog's top over the particle's disc, fitted to the top there as the floor's
    //! is: a billboard draws only the part of the ball under it (a ball near a fog lake's flat top
    //! stood out of it, a veil over the far shore seen level). top +inf: no fog over the disc.
    double top = std::numeric_limits<double>::infinity();
    glm::dvec2 top_slope{0.0};
};

//! How the attenuation buffer's voxel grid is oriented (light_grid.hpp). Its columns always run
//! along the light; its slices are perpendicular to the light (`light`, Shimada's layout) or
//! tilted to the plane that fits the particles best (`sheared`: flat fog under a low sun fills
//! the grid instead of a thin oblique sheet of it); `automatic` takes the one with fewer slices
//! spent on empty space.
enum class LightFrame { automatic, light, sheared };
inline constexpr Choice light_frame_names[] = {
    {"auto", int(LightFrame::automatic)}, {"light", int(LightFrame::light)}, {"sheared", int(LightFrame::sheared)}};
//! The attenuation buffer's storage: R16F (true) or R32F.
inline constexpr Choice buffer_format_names[] = {{"r16f", 1}, {"r32f", 0}};

//! The scene's "particles" section (docs/particles.md).
struct ParticleOptions {
    int count = 20000;     //!< ignored when spacing > 0
    double spacing = 0.0;  //!< 0: use count
    double radius_scale = 1.5;
    double radius_min = 0.0;  //!< 0: radius_scale * the spacing at full density
    double radius_max = 0.0;  //!< 0: twice that (densities below 1/8 get no larger particles)
    double albedo = -1.0;     //!< < 0: the Medium's albedo
    double extinction = 0.0;  //!< 0: the Medium's
    //! c of (7). 0: none, the default: the shared lighting model's multiple scattering carries
    //! the light scattered forward, and the sun's optical depth is then the fog's, as every
    //! renderer reads it. Harris's own model: forward_scattering_fraction(the Medium's g).
    double forward_scattering = 0.0;
    std::uint64_t seed = 1;
    double candidates = 5.0;
    //! Sweeps that even out the particles' spacing across the fog after the elimination
    //! (relax_particles.hpp); 0: the blue noise as eliminated.
    int relax = 15;
    // The attenuation buffer and the billboards (render).
    int resolution = 128;
    bool half_float = true;  //!< storage of log Gamma
    LightFrame frame = LightFrame::automatic;
    //! Metres over which billboards also fade in front of the terrain; 0: each particle shows the
    //! part of its column in front of the terrain and no more (particles.frag).
    double soft_edge = 0.0;
    int near_scale = 2;        //!< the near billboards' target is this many times coarser a side
    double near_pixels = 6.0;  //!< from this radius on screen (pixels) a billboard is near
    //! With the particles alone, the Medium itself is marched within this many times the largest
    //! radius of the eye, and the billboards draw the fog from there on (0: none).
    double near_field = 2.5;
    //! With the particles alone, each ball's density along a ray is weighted by the Medium's
    //! extinction over the density all the balls add up to there (density_ratio.hpp): together
    //! they draw the Medium, not a lumpy copy of it, and are lit by its light (its optical depth
    //! towards the sun, the terrain's shadow where they are lit) as the layers and the froxels
    //! are. false: each ball as sampled, lit through the attenuation buffer.
    bool match_medium = true;
    bool operator==(const ParticleOptions&) const = default;
};

//! The "particles" section. count and spacing are alternatives (at most one is given).
template <fields_of<ParticleOptions> O, class V>
void visit_fields(O& o, V&& v)
{
    v(o.count,
      {.key = "count",
       .range = closed(1, 2000000),
       .doc = "particles to sample",
       .widget = closed(100, 200000),
       .log_widget = true});
    v(o.spacing,
      {.key = "spacing",
       .unit = "m",
       .range = greater_than(0),
       .doc = "instead of `count`: between particles at full density (count = D / spacing^3)",
       .widget = closed(10, 2000),
       .log_widget = true,
       .shown_default = "none",
       .omit_default = true});
    v(o.radius_scale,
      {.key = "radius_scale",
       .range = left_open(0, 100),
       .doc = "radius = radius_scale x the local spacing, clamped to `radius`",
       .widget = closed(0.5, 4)});
    v(o.radius_min,
      {.key = "radius",
       .unit = "m",
       .range = greater_than(0),
       .doc = "the clamp of the radius (automatic: 1.5 and 3 x the spacing at full density)",
       .shown_default = "automatic",
       .omit_default = true,
       .element = 0,
       .elements = 2,
       .shape = "[min, max]"});
    v(o.radius_max,
      {.key = "radius",
       .unit = "m",
       .range = greater_than(0),
       .doc = "the largest radius",
       .shown_default = "automatic",
       .omit_default = true,
       .element = 1,
       .elements = 2,
       .shape = "[min, max]"});
    v(o.albedo,
      {.key = "albedo",
       .range = closed(0, 1),
       .doc = "scattering / extinction",
       .shown_default = "the Medium's",
       .omit_default = true});
    v(o.extinction,
      {.key = "extinction",
       .unit = "1/m",
       .range = closed(0, 1000),
       .doc = "the particles carry at full density",
       .shown_default = "the Medium's",
       .omit_default = true});
    v(o.forward_scattering,
      {.key = "forward_scattering",
       .range = closed(0, 1),
       .doc = "c = p(l,l)/4pi of (7), Harris's light scattered on along the sun's beam; 0: the shared "
              "lighting model's multiple scattering carries that light",
       .shown_default = "0",
       .omit_default = true});
    v(o.seed, {.key = "seed", .range = closed(0, 2147483647), .doc = "the same seed, the same particles"});
    v(o.candidates,
      {.key = "candidates", .range = closed(1, 50), .doc = "candidates per particle for the sample elimination"});
    v(o.relax,
      {.key = "relax",
       .range = closed(0, 1000),
       .doc = "sweeps that even out the particles' spacing across the fog (0: blue noise as eliminated)"});
    v(o.resolution,
      {.key = "resolution",
       .unit = "voxels",
       .range = closed(16, 512),
       .doc = "per side of the attenuation buffer",
       .widget = closed(64, 384)});
    v(o.half_float, {.key = "format", .doc = "the attenuation buffer's storage", .choices = buffer_format_names});
    v(o.frame,
      {.key = "frame",
       .doc = "the buffer's slices: perpendicular to the light, or sheared to the fog (`auto`: the tighter)",
       .choices = light_frame_names});
    v(o.soft_edge,
      {.key = "soft_edge",
       .unit = "m",
       .range = at_least(0),
       .doc = "over which billboards also fade in front of the terrain (0: each shows its column in front of it)",
       .widget = closed(0, 500)});
    v(o.near_scale,
      {.key = "near_scale",
       .range = closed(1, 8),
       .doc = "billboards near the eye are drawn this many times coarser a side (1: full resolution)",
       .widget = closed(1, 4)});
    v(o.near_pixels,
      {.key = "near_pixels",
       .unit = "px",
       .range = greater_than(0),
       .doc = "near: every billboard from here on spans at least this radius on screen",
       .widget = closed(4, 256)});
    v(o.near_field,
      {.key = "near_field",
       .range = closed(0, 100),
       .doc = "the particles alone: within this many largest radii of the eye the Medium itself is marched (0: "
              "billboards to the eye)",
       .widget = closed(0, 8)});
    v(o.match_medium,
      {.key = "match_medium",
       .doc = "the particles alone: each ball's density weighted by the Medium's over the balls' sum where the ray "
              "passes, so together they draw the Medium, lit by its light (false: the balls as sampled, lumps and "
              "all, lit through the attenuation buffer)"});
}

//! \throw InputError(label, "/particles/<key>", reason) for options outside their ranges.
void validate_particle_options(const ParticleOptions& options, const std::string& label = {});

struct ParticleCloud {
    std::vector<Particle> particles;
    //! p(l,l)/4pi of (7): the fraction of the light a particle scatters that stays in the sun's
    //! beam (Harris's forward-scattering term), in [0, 1].
    double forward_scattering = 0.2;
    double anisotropy = 0.8;  //!< Henyey-Greenstein g towards the eye (the Medium's)
    //! The extinction at full density (1/m) and the albedo the particles carry: the Medium's,
    //! unless the "particles" section sets its own.
    double extinction = 0.0, albedo = 0.0;
    //! The (x, y) rectangle that holds the fog (the Medium's grid): no footprint reaches beyond
    //! it, so the fog's wall at a grid's edge stays sharp. Infinite: no such bound.
    glm::dvec2 fog_xy_min{-std::numeric_limits<double>::infinity()},
        fog_xy_max{std::numeric_limits<double>::infinity()};
    //! The Medium's multiple scattering as the shaders take it (shader_octaves, fog_lighting.hpp):
    //! 0 the fitted model, n >= 1 n octaves.
    int scattering_octaves = 0;
    //! What the sampler found (for reports): the Medium's integral of density (m^3), the mean
    //! spacing at full density, the number of candidates drawn and the trials that found them.
    double density_integral = 0.0, spacing = 0.0;
    std::size_t candidate_count = 0, trial_count = 0;
    //! With a HeightShare's depth: the radius (metres) the depth was counted in, which the other
    //! renderers count it in too (FogPartition::particle_radius); 0 without.
    double share_radius = 0.0;
};

//! Harris's read-back solid angle (0.09 sr, [SkyWorks]): the forward cone whose scattered light
//! stays in the beam.
constexpr double harris_forward_solid_angle = 0.09;
//! The fraction of Henyey-Greenstein scattering (anisotropy g) that goes into the forward cone of
//! `solid_angle` steradians: (1 - g^2) / (2 g) ((1 - g)^-1 - (1 + g^2 - 2 g mu0)^-1/2),
//! mu0 = 1 - solid_angle / 2pi; solid_angle / 4pi for g = 0. g = 0.8: 0.228.
double forward_scattering_fraction(double g, double solid_angle = harris_forward_solid_angle);

//! Samples the particles of a Medium: candidates drawn with probability proportional to the
//! density, thinned to the count by sample elimination ([Yuksel15]) with distances measured in
//! units of the local spacing, so the result is blue noise whose density still follows the
//! Medium. Each particle carries the same share of the Medium's extinction integral:
//! tau_k = extinction * density_integral / (count * footprint_area(r_k)). Deterministic for a seed
//! (the same seed, options and Medium give bit-identical particles).
//! With a share the particles stand for the share(h) d of the Medium (combined rendering,
//! fog_partition.hpp: they draw the top band, the other renderers the rest).
//! The candidates are drawn by rejection under an envelope of the density per cell of the
//! Medium's grid, from the lowest height where the share can be non-zero to the cell's top
//! (shell_envelope.hpp): the same distribution as from the Medium's whole box, with a fraction of
//! the trials where the shell follows the terrain or only its top band is drawn.
//! A fog too thin to give count * candidates points in reasonable time (a thin top band in a
//! tall box) gets fewer particles in proportion to the points found, and none when no point held
//! fog: a thin fog is drawn thin, not refused.
//! \throw InputError on bad options; LimitError above 2e6 particles or 2e7 candidates.
struct HeightShare {
    //! The share at height fraction h in [0, 1] of the shell (Medium::height_fraction); clamped
    //! to [0, max], and taken as 0 at h <= from.
    std::function<double(double h)> share;
    double from = 0.0;
    double max = 1.0;
    //! > 0: the share times particle_depth_share (fog_partition.hpp) of the fog's thickness at
    //! the point, `depth` counted in the radius the particles would have at full density without
    //! that factor (a pilot of the sampler finds it: ParticleCloud::share_radius).
    double depth = 0.0;
};
ParticleCloud sample_particles(const Medium& medium, const ParticleOptions& options, const std::string& label = {},
                               const HeightShare& share = {});
//! Each particle's share of its mass above the ground (Particle::above_ground,
//! footprint_share_above) over the Medium's columns of fog: the plane of Particle::floor where the
//! fog floats above the ground (a blanket's bottom, which the billboard cuts), and the terrain
//! z = ground(x, y) where the fog is at least as thick as the particle's radius. There the ground
//! cuts a fog that the particle stands for the bottom of, and the mass it hides is the fog's own.
//! Elsewhere (a thread of fog in a valley narrower or shallower than the particle, the bare
//! ridges beside it) the particle spills out of the fog whether its ball reaches into the ground
//! or not, and a billboard that drew the hidden part over the rest would draw more fog where
//! there is none.
void set_above_ground(ParticleCloud& cloud, const Medium& medium, const std::function<double(double, double)>& ground);
//! Combined rendering's share for the particles (fog_partition.hpp): zero up to the top band,
//! rising to particle_share at the top.
HeightShare particle_height_share(const FogPartition& partition);

//! Binary little-endian PLY of the particles: x y z (float), radius, optical_depth, albedo,
//! with the forward-scattering fraction and the anisotropy in comments. Written atomically.
//! \throw IoError naming the path.
void write_particles_ply(const std::string& path, const ParticleCloud& cloud);

}  // namespace kiri::geometry
