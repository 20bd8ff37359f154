#pragma once
//! \file reference_fog.hpp
//! The CPU reference ray marcher: the judge of every fog renderer of kiri (froxels, layers,
//! particles). Per pixel, in double precision, it integrates single scattering through the
//! Medium (and the optional height fog) exactly as docs/froxel.md states the lighting model:
//!
//!   L = L_surface T(D) + integral_0^D T(t) [ sigma_s(x) (E_sun V(x) T_sun(x) p(w.s) + L_amb) ] dt
//!   T(t) = exp(-integral_0^t sigma_t),   T_sun(x) = exp(-integral_0^inf sigma_t(x + u s) du)
//!
//! with E_sun the sun's colour times intensity, s the direction towards the sun, w the view
//! direction, V the terrain's shadow (is the sun visible from x over the heightfield), p the
//! Henyey-Greenstein phase (g clamped strictly inside (-1, 1)) and L_amb the isotropic sky
//! ambient. Each medium scatters with its own albedo and g. The fog and the ground are seen
//! through the air the renderers draw (FogLighting::air, air_light.hpp).
//!
//! How: the shell's entry and exit along each ray are found exactly (roots of quadratics per
//! grid cell), inside the shell the ray is cut into steps of at most `optical_step` optical
//! depth and of the medium's feature sizes, each step integrated with two-point Gauss for the
//! optical depth and the exact exponential for the in-scattering. The terrain is hit exactly
//! (the heightfield's triangles). The sun term is evaluated at knots along the ray and
//! interpolated (T_sun is continuous along a ray; the terrain shadow's edges are found by
//! bisection).
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "kiri/geometry/medium/fog_lighting.hpp"
#include "kiri/geometry/volume/height_fog.hpp"
#include "kiri/geometry/terrain/heightfield.hpp"
#include "kiri/geometry/medium/medium.hpp"

namespace kiri::geometry {

//! What the volume renderers draw: the authored Medium (may be absent) and a height fog.
struct FogVolume {
    const Medium* medium = nullptr;
    HeightFog height_fog;
    bool empty() const { return (!medium || !(medium->max_extinction() > 0.0)) && !height_fog.enabled(); }
};

//! A pinhole view like render::Camera: rays through pixel centres, row 0 at the top.
struct ReferenceView {
    glm::dvec3 eye{0.0, -1000.0, 1000.0};
    glm::dvec3 target{0.0};
    glm::dvec3 up{0.0, 0.0, 1.0};
    double fov_y_deg = 45.0;
    int width = 160, height = 90;
    //! The fog ends at this view depth (distance along the view axis), as the froxel volume
    //! ends at its far plane; 0: no limit (sky rays stop at 1e6 m).
    double max_depth = 0.0;

    //! Unit direction of the ray through the centre of pixel (x, y).
    glm::dvec3 ray(int x, int y) const;
    //! Unit direction of the ray through image point (x, y): pixel (i, j) spans [i, i + 1] x
    //! [j, j + 1], row 0 at the top.
    glm::dvec3 ray_through(double x, double y) const;
    glm::dvec3 forward() const;
};

struct ReferenceOptions {
    double optical_step = 0.02;         //!< largest optical depth of one step along a view ray
    double knot_optical_step = 0.1;     //!< sun-term knots: at most this optical depth apart
    double shadow_optical_step = 0.05;  //!< steps of the sun's optical depth
    double feature_fraction = 0.25;     //!< steps at most this fraction of the medium's features
    double shadow_feature_fraction = 1.0;
    double min_transmittance = 1e-5;  //!< the view ray stops when T falls below
    //! The sun's light is 0 beyond this optical depth towards the sun (e^-12 = 6e-6) divided by
    //! the lighting model's sun_scattering_decay (fitted: 52, three octaves: 48).
    double sun_cutoff = 12.0;
    int threads = 0;  //!< 0: every core
    //! false: the terrain is black (it still ends rays and casts shadows), so the picture holds
    //! the fog's light alone (`kiri render --black-ground`).
    bool shade_terrain = true;
    //! The ground beyond the DEM's edge (kiri/geometry/terrain/ground.hpp); false: the bare tile.
    bool surround = true;
};

//! The fog along one ray.
struct RayFog {
    glm::dvec3 inscatter{0.0};  //!< radiance the fog adds
    double transmittance = 1.0;
    double distance = 0.0;  //!< where the ray ended: the terrain, the depth limit or 1e6 m
    bool hit_terrain = false;
    glm::dvec3 surface{0.0};  //!< radiance of what ends the ray: lit terrain, or sky
    //! The sunlight the fog's shade takes from that terrain, as seen through the air: what it
    //! would add to `surface` without the fog (the ground under the fog lies in its shade).
    glm::dvec3 fog_shade{0.0};
    //! The sun's transmittance through the fog at that terrain, e^-tau_sun (1: sky, or a ground
    //! turned from the sun), whether or not the terrain hides the sun there.
    double ground_sun = 1.0;
    int steps = 0;  //!< fine steps taken (cost)
    int sun_knots = 0;
};

struct ReferenceImage {
    int width = 0, height = 0;
    std::vector<glm::dvec3> inscatter;  //!< row-major, row 0 at the top
    std::vector<double> transmittance;
    std::vector<glm::dvec3> background;  //!< the surface's radiance (terrain or sky), unfogged
    std::vector<glm::dvec3> fog_shade;   //!< RayFog::fog_shade (empty: none)
    std::vector<double> ground_sun;      //!< RayFog::ground_sun (empty: 1)
    std::vector<double> depth;           //!< view depth of the terrain hit, +inf for sky
    double seconds = 0.0;
    long long steps = 0, sun_knots = 0;

    glm::dvec3 composed(std::size_t k) const { return background[k] * transmittance[k] + inscatter[k]; }
};

//! The fog along origin + t dir (dir unit) up to t_max, with the terrain (may be null) ending it.
RayFog reference_ray(const FogVolume& fog, const Heightfield* terrain, const glm::dvec3& origin, const glm::dvec3& dir,
                     double t_max, const FogLighting& light, const ReferenceOptions& options = {});

//! The reference image of `view`. Pixels run in parallel (options.threads).
ReferenceImage render_reference_fog(const FogVolume& fog, const Heightfield* terrain, const ReferenceView& view,
                                    const FogLighting& light, const ReferenceOptions& options = {});

//! The rays of `view` through image points (ReferenceView::ray_through), as an image of one row:
//! a judge's rays through a multisampled frame's samples where a pixel straddles two surfaces.
ReferenceImage render_reference_rays(const FogVolume& fog, const Heightfield* terrain, const ReferenceView& view,
                                     const FogLighting& light, const std::vector<glm::dvec2>& points,
                                     const ReferenceOptions& options = {});

//! Relative luminance (Rec. 709 weights).
double luminance(const glm::dvec3& rgb);

}  // namespace kiri::geometry
