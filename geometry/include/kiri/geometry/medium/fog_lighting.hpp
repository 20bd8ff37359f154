#pragma once
//! \file fog_lighting.hpp
//! The one lighting model of the fog, shared by every renderer (layers, particles, froxels) and
//! by the CPU reference ray marcher, so that their pictures can agree (docs/medium.md).
//!
//! Units follow the terrain's shading: `sun` is the radiance a white Lambertian surface facing
//! the sun reflects (scene sun colour x intensity), so the sun's irradiance is pi sun; the sky
//! is an isotropic radiance `ambient`. Single scattering of the sun plus the sky, with multiple
//! scattering approximated by octaves ([Wrenninge13]):
//! octave i scatters a^i of the light, sees the sun through b^i of the optical depth and has
//! anisotropy c^i g (a = b = c = 1/2). One octave is plain single scattering. Thick fog seen
//! with the sun behind the eye stays white instead of turning grey, as real fog does.
//!
//! The source per unit extinction at a point, towards the eye:
//!
//!   J = albedo [ pi sun visibility sum_{i < octaves} a^i p_HG(cos_theta, c^i g) exp(-b^i tau_sun) + ambient ]
//!
//! cos_theta between the direction to the sun and the direction from the point away from the
//! eye (1: looking into the sun), tau_sun the fog's optical depth from the point towards the
//! sun, visibility in [0, 1] the terrain's shadow. A segment of constant J and extinction
//! sigma_t, length d, adds J (1 - exp(-sigma_t d)) times the transmittance in front of it.
#include <glm/vec3.hpp>

#include "kiri/geometry/medium/medium_options.hpp"

namespace kiri::geometry {

class Medium;

struct FogLight {
    glm::dvec3 sun{3.0};      //!< colour x intensity (SunSpec)
    glm::dvec3 ambient{0.3};  //!< isotropic sky radiance (SunSpec::ambient)
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
    int scattering_octaves = 1;                //!< kiri render passes the Medium's (MediumOptions::scattering_octaves)
    //! false: no sky light at all, for comparisons with renderers set up in a black world: the
    //! ambient is taken as 0 and the sky seen behind the fog is black (`kiri render --no-sky`).
    bool sky = true;
};

//! The sum over the octaves of J above, a^i p_HG(cos_theta, c^i g) exp(-b^i tau_sun) (1/sr);
//! g is clamped strictly inside (-1, 1) by henyey_greenstein, octaves to [1, 8].
double sun_scattering(double cos_theta, double g, double tau_sun, int octaves);

//! The octaves a renderer lights the fog with: the Medium's, MediumOptions' default without one
//! (a height fog alone).
int scattering_octaves_of(const Medium* medium);

}  // namespace kiri::geometry
