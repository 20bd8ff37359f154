#pragma once
//! \file path_tracer.hpp
//! A Monte Carlo volume path tracer in double precision: the exact answer (up to its noise) to
//! the light transport in kiri's fog, every order of scattering included. It judges the lighting
//! model (fog_lighting.hpp, whose multiple scattering is approximated by octaves) the way the
//! CPU reference ray marcher (reference_fog.hpp) judges the renderers. docs/medium.md, "Against
//! a path tracer".
//!
//! What it traces, in the units of fog_lighting.hpp:
//! - the media of a FogVolume: the Medium (extinction, albedo, Henyey-Greenstein g) and the
//!   height fog, each scattering with its own albedo and g ([HG41], g clamped to +-0.999);
//! - the sun, a directional light of irradiance pi sun (FogLighting::sun_radiance), by next-event
//!   estimation at every vertex: the terrain's shadow by the heightfield ray, the fog's by ratio
//!   tracking (FogLighting::terrain_shadows and fog_shadows switch them off, as the reference);
//! - the sky: an isotropic radiance FogLighting::ambient from the upper hemisphere, reached by
//!   paths that leave the scene (so the terrain occludes it and the fog dims it); or none
//!   (FogLighting::sky false, or PathSky::none); PathSky::sphere lights from every direction
//!   (the white furnace);
//! - the ground: the heightfield as a Lambertian surface of the terrain's albedo
//!   (render/shaders/terrain.frag's colour by height and slope), or black (it still occludes).
//!
//! How: free paths by delta tracking ([Woodcock65]) against a majorant per cell of the
//! Medium's grid (the extinction at density 1 times the cell's largest coverage, between the
//! cell's lowest floor and highest top), the height fog's free path sampled exactly by inverting
//! its closed-form optical depth (the first of the two independent collisions is the collision
//! of the sum); transmittance towards the sun by residual ratio tracking ([Novak14]) over the
//! same cells (the control: a lower bound of the extinction where a cell is wholly inside the
//! shell, exact in a uniform slab) times the height fog's closed form; directions by
//! importance sampling the phase function (cosine-weighted at the ground); Russian roulette on
//! the path's throughput after `roulette_after` vertices, and at most `max_bounces` vertices.
//! Each pixel draws from its own random stream ([Blackman21]) seeded by (seed, pixel), so an
//! image is bit-identical for the same seed and options on any number of threads. Rays run
//! through pixel centres, like the reference's.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "kiri/geometry/medium/fog_lighting.hpp"
#include "kiri/geometry/reference/reference_fog.hpp"
#include "kiri/geometry/terrain/heightfield.hpp"

namespace kiri::geometry {

//! Where the sky's radiance FogLighting::ambient comes from.
enum class PathSky {
    hemisphere,  //!< directions above the horizon (z > 0); below it, black
    sphere,      //!< every direction (a white furnace: a closed, uniformly lit world)
    none,        //!< black
};

enum class PathGround {
    lambertian,  //!< the terrain's albedo, lit by the sun, the sky and the fog
    black,       //!< absorbs everything (still ends rays and casts shadows)
};

struct PathTracerOptions {
    int samples = 16;        //!< paths per pixel, >= 1
    int max_bounces = 128;   //!< scattering vertices (fog or ground) a path may have; 0: none
    int roulette_after = 3;  //!< Russian roulette from this many vertices on
    std::uint64_t seed = 1;
    PathSky sky = PathSky::hemisphere;
    PathGround ground = PathGround::lambertian;
    //! The ground beyond the DEM's edge (kiri/geometry/terrain/ground.hpp); false: the bare tile.
    bool surround = true;
    int threads = 0;  //!< 0: every core
    //! Adaptive sampling (render_path_traced only): after `samples` paths a pixel, each block of
    //! noise_block x noise_block pixels whose mean luminance has a relative standard error above
    //! noise_target takes more paths, its count fourfold a round, until the error is under the
    //! target or its pixels have max_samples. Blocks under 1e-6 of the brightest block are left
    //! as they are (no judge counts them). 0: off, every pixel takes `samples` paths.
    double noise_target = 0.0;
    int noise_block = 4;
    int max_samples = 0;  //!< the most paths a pixel takes when adaptive; 0: 64 x samples
};

//! The estimate of one pixel or ray: the mean of its samples and the standard error of that
//! mean (per channel).
struct PathEstimate {
    glm::dvec3 radiance{0.0};
    glm::dvec3 std_error{0.0};
    int samples = 0;
};

struct PathTracedImage {
    int width = 0, height = 0, samples = 0;  //!< samples: the paths every pixel took at least
    std::vector<glm::dvec3> radiance;        //!< row-major, row 0 at the top: linear radiance
    std::vector<glm::dvec3> std_error;       //!< standard error of each pixel's mean
    std::vector<int> pixel_samples;          //!< the paths each pixel traced (more where adaptive)
    int rounds = 1;                          //!< passes over the image, the first included
    double seconds = 0.0;
    long long vertices = 0;  //!< scattering vertices traced (cost)
    long long dropped = 0;   //!< samples dropped for a non-finite value (0 unless something is broken)
};

//! `samples` paths from origin along dir (unit; the first segment ends at t_max, where the sky
//! is seen, as a reference ray ends at the view's depth limit); stream selects the random
//! sequence (a pixel's index in render_path_traced).
PathEstimate path_traced_ray(const FogVolume& fog, const Heightfield* terrain, const glm::dvec3& origin,
                             const glm::dvec3& dir, double t_max, const FogLighting& light,
                             const PathTracerOptions& options = {}, std::uint64_t stream = 0);

//! The path-traced image of `view` (the reference's view: rays through pixel centres, the fog
//! ending at view.max_depth). Rows run in parallel (options.threads). With
//! options.noise_target, the noisy blocks then take more paths (PathTracerOptions); each round's
//! paths come from streams of their own, so the image is still the same on any number of threads.
PathTracedImage render_path_traced(const FogVolume& fog, const Heightfield* terrain, const ReferenceView& view,
                                   const FogLighting& light, const PathTracerOptions& options = {});

}  // namespace kiri::geometry
