#pragma once
//! \file air_light.hpp
//! The air between the eye and what it sees (aerial perspective): a uniform medium of extinction
//! beta whose source is the sky's horizon colour H, so that a point of radiance L at distance d
//! is seen as
//!
//!   L e^(-beta d) + H (1 - e^(-beta d)).
//!
//! It keeps far ridges reading as far. It is not the fog: it takes no light from the sun and
//! casts no shadow, so it is applied where each renderer knows a distance: to the terrain, and
//! to each piece of fog, whose source J becomes J e^(-beta d) + H (1 - e^(-beta d)). Along a ray
//! through fog pieces of opacity a_i at distances d_i in front of a surface at D this sums to
//! the exact transfer through the air and the fog together while beta is small over a piece
//! (1/150 km here against pieces of metres to hundreds of metres): every renderer and the CPU
//! reference apply it alike, so they draw the same picture.
#include <glm/vec3.hpp>

namespace kiri::geometry {

struct AirLight {
    double extinction = 0.0;   //!< beta (1/m); 0: no air
    glm::dvec3 radiance{0.0};  //!< H: the sky's horizon colour

    //! 1 - e^(-beta d): how much of H a point at distance d takes on (0 without air).
    double haze(double distance) const;
    //! L seen through `distance` metres of air.
    glm::dvec3 seen(const glm::dvec3& radiance_at_point, double distance) const;
};

//! The sky's colour at the horizon for the sky light `ambient`: mix(3 ambient, white, 0.3).
glm::dvec3 sky_horizon(const glm::dvec3& ambient);

//! The air over a terrain whose extent (x, y) has the diagonal `across` (m): beta = 1 /
//! max(150 km, 3 across), so the far side of a DEM of up to 50 km is hazed by about a fifth
//! and a wider one as a 50 km one is (instead of fading to the horizon's grey); H the sky's
//! horizon colour. `sky` false (a black world, `kiri render --no-sky`): no air at all.
AirLight scene_air(double across, const glm::dvec3& ambient, bool sky = true);

}  // namespace kiri::geometry
