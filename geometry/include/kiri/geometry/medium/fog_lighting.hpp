#pragma once
//! \file fog_lighting.hpp
//! The one lighting model of the fog, shared by every renderer (layers, particles, froxels) and
//! by the CPU reference ray marcher, so that their pictures can agree (docs/medium.md).
//!
//! Units follow the terrain's shading: `sun` is the radiance a white Lambertian surface facing
//! the sun reflects (scene sun colour x intensity), so the sun's irradiance is pi sun; the sky
//! is an isotropic radiance `ambient`. The source per unit extinction at a point, towards the eye:
//!
//!   J = albedo [ pi sun visibility S(cos_theta, tau_sun) + ambient ]
//!
//! cos_theta between the direction to the sun and the direction from the point away from the
//! eye (1: looking into the sun), tau_sun the fog's optical depth from the point towards the
//! sun, visibility in [0, 1] the terrain's shadow. A segment of constant J and extinction
//! sigma_t, length d, adds J (1 - exp(-sigma_t d)) times the transmittance in front of it.
//!
//! S, the sun's phase and transmittance (1/sr), by MultipleScattering:
//! - none: single scattering, p_HG(cos_theta, g) exp(-tau_sun);
//! - octaves ([Wrenninge13]): sum_{i < octaves} a^i p_HG(cos_theta, c^i g) exp(-b^i tau_sun),
//!   a = b = c = 1/2;
//! - fitted (the default): the orders of scattering along the sun's path. Of the sunlight that
//!   crossed optical depth tau, the part scattered n times is taken as Poisson's
//!   exp(-tau) (b tau)^n / n! (b = persistence x albedo: what each scattering keeps on its way),
//!   its phase widening with each order:
//!
//!     S = p_HG(cos_theta, g) exp(-tau) + K s^k [ sum_{1 <= n < N-1} exp(-tau) (b tau)^n / n! p_HG(cos_theta, c^n g)
//!                                               + R p_HG(cos_theta, d g) ]
//!     R = exp(-(1 - b) tau) - sum_{n < N-1} exp(-tau) (b tau)^n / n!      (every higher order)
//!
//!   with N = fitted_orders lobes, s the sine of the sun's elevation (the light scattered more
//!   than once is fed by the sunlight through the fog's top, s of the beam's), and c, d each
//!   raised by e (1 - s) (under a low sun more of it still travels the sun's way). Light
//!   scattered more than once met fog on its way first: where the sun crossed none (tau 0), S
//!   is single scattering, so thin fog stays nearly single scattering; deep in thick fog the
//!   light scattered many times dies out as exp(-(1 - b) tau), not as exp(-tau). K, k, b, c, d
//!   and e (MultipleScatteringFit) were fitted to the path tracer (path_tracer.hpp) on uniform
//!   slabs and thin layers at three sun elevations (docs/medium.md, "Multiple scattering").
//! - baked: single scattering as `none`, and the light scattered more than once read from a
//!   light-transport volume (light_volume.hpp) baked by tracing the sun's light through the fog:
//!   the source gains albedo sun sum_l g^l L_lm Y_lm(towards the eye), not dimmed by the terrain's
//!   shadow V (light reaches the shadow from the sunlit fog beside it). Without a volume, `none`.
#include <memory>

#include <glm/vec3.hpp>

#include "kiri/geometry/medium/air_light.hpp"
#include "kiri/geometry/medium/medium_options.hpp"

namespace kiri::geometry {

class Medium;
struct LightVolume;

//! The fitted model's lobes: single scattering, the orders 1 .. N-2, and the rest.
inline constexpr int fitted_orders = 4;

//! The fitted model's constants (of the file comment); the defaults are the fit (docs/medium.md,
//! "Multiple scattering"), repeated in the shaders' fitted_sun_scattering.
struct MultipleScatteringFit {
    double amplitude = 3.09;               //!< K
    double sun_power = 0.454;              //!< k
    double low_sun_eccentricity = 0.471;   //!< e
    double persistence = 0.768;            //!< b / albedo
    double eccentricity = 0.491;           //!< c
    double diffuse_eccentricity = -0.439;  //!< d: the light scattered many times comes back up
};

struct FogLight {
    glm::dvec3 sun{3.0};              //!< colour x intensity (SunSpec)
    glm::dvec3 ambient{0.3};          //!< isotropic sky radiance (SunSpec::ambient)
    double sun_elevation_sine = 1.0;  //!< s of the fitted model: the sun's direction's z
};

//! J of the file comment (radiance per unit of (1 - transmittance)); finite and >= 0 for any input.
glm::dvec3 fog_source(const FogLight& light, const MediumOptions& optics, double cos_theta, double tau_sun,
                      double visibility = 1.0);

//! How a volume renderer (the froxels, the CPU reference) is lit: the sun's direction, the
//! FogLight values and which shadows it draws. The source is J above, with the sun's part
//! pi sun_radiance V sun_scattering(cos_theta, g, tau_sun, scattering_octaves) (tests check it
//! against fog_source).
struct FogLighting {
    glm::dvec3 sun_direction{0.5, -0.3, 0.6};  //!< towards the sun (normalised where used)
    glm::dvec3 sun_radiance{3.0};              //!< FogLight::sun: the scene's sun colour times intensity
    glm::dvec3 ambient{0.25, 0.3, 0.38};       //!< FogLight::ambient: isotropic sky radiance
    bool terrain_shadows = true;               //!< visibility: the terrain hides the sun
    bool fog_shadows = true;                   //!< tau_sun: the fog dims the sun on its way
    //! kiri render passes the Medium's (MediumOptions::multiple_scattering, scattering_octaves);
    //! octaves with 1 octave is single scattering.
    MultipleScattering multiple_scattering = MultipleScattering::octaves;
    int scattering_octaves = 1;
    MultipleScatteringFit fit{};
    //! The multiple scattering `baked` reads (bake_light_volume, for this sun); null: none.
    std::shared_ptr<const LightVolume> light_volume;
    //! false: no sky light at all, for comparisons with renderers set up in a black world: the
    //! ambient is taken as 0, the sky seen behind the fog is black and there is no air
    //! (`kiri render --no-sky`).
    bool sky = true;
    //! The air between the eye and the fog and terrain (air_light.hpp); none by default. The
    //! renderers' is the scene's (scene_air), and the reference judging them takes the same.
    AirLight air;
};

//! The sum over the octaves of J above, a^i p_HG(cos_theta, c^i g) exp(-b^i tau_sun) (1/sr);
//! g is clamped strictly inside (-1, 1) by henyey_greenstein, octaves to [1, 8].
double sun_scattering(double cos_theta, double g, double tau_sun, int octaves);

//! S of the file comment for the fitted model (1/sr): finite and >= 0 for any input.
double fitted_sun_scattering(double cos_theta, double g, double albedo, double tau_sun, double sun_elevation_sine,
                             const MultipleScatteringFit& fit = {});

//! S of the file comment in the model `kind` (octaves: `octaves` of them).
double sun_scattering(MultipleScattering kind, int octaves, double cos_theta, double g, double albedo, double tau_sun,
                      double sun_elevation_sine, const MultipleScatteringFit& fit = {});

//! The slowest rate at which the model's S falls with tau_sun: S(tau) <= S_max exp(-rate tau)
//! (none and baked's single scattering: 1; octaves: 2^-(octaves - 1), the last octave's; fitted:
//! 1 - persistence, the orders' sum exp(-(1 - b) tau) at albedo 1). An optical depth towards the
//! sun may be cut off where e^-(rate tau) is negligible, not where e^-tau is: the fitted model
//! still lights fog 12 deep in tau_sun with 2 % of its sun.
double sun_scattering_decay(MultipleScattering kind, int octaves, const MultipleScatteringFit& fit = {});

//! The octaves a renderer lights the fog with: the Medium's, MediumOptions' default without one
//! (a height fog alone).
int scattering_octaves_of(const Medium* medium);
//! The model a renderer lights the fog with: the Medium's, MediumOptions' default without one.
MultipleScattering multiple_scattering_of(const Medium* medium);
//! The shaders' `u_octaves`: 0 for the fitted model, else the octaves (none: 1).
int shader_octaves(MultipleScattering kind, int octaves);
int shader_octaves(const MediumOptions& optics);

}  // namespace kiri::geometry
