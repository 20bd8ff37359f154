#pragma once
//! \file medium.hpp
//! The fog as a participating medium: extinction (1/m), albedo and Henyey-Greenstein anisotropy
//! as a field over the fog volume. Every renderer of kiri reads this one description (layers,
//! particles, froxels, the CPU reference ray marcher), so they draw the same fog.
//!
//! The volume is a shell between two height grids over (x, y): `bottom` and `top`, clipped
//! below by the ground (`floor` = max(bottom, ground)). Over the authored fog (docs/fog.md) the
//! bottom is the layer stack's base and the top the base plus the stack's thickness; a fill
//! (docs/placement.md) gives bottom = ground and top = the fog-top altitude. Inside, the density is
//!
//!   d(p) = coverage(x, y) * profile(h) * detail(x, y, h, t) * dissipation(h, t),
//!   h = (z - bottom) / (top - bottom) in [0, 1],
//!   profile(h) = 1 - (1 - top_density) h          (the layer alphas (2.7): 1 at the base, 0.1 at the top)
//!
//! and sigma_t(p) = extinction * d(p). coverage is the layers' border fade ([Thesis] 2.2.2),
//! detail the layers' drifting noise at the height of layer i = h l0, dissipation the layers'
//! 0.5^(t / half_life (1 + h)): a layer of the stack and the medium at its height agree.
//! Grids are sampled bilinearly (the GPU's linear filtering of the same values).
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "kiri/geometry/medium/medium_options.hpp"
#include "kiri/geometry/terrain/terrain.hpp"

namespace kiri::geometry {

// ---- Optics ([Koschmieder24], [ValleyFog]) ----------------------------------------------------

//! Koschmieder: the visibility V (m) of a medium of extinction sigma (1/m), V = 3.912 / sigma
//! (contrast threshold 2 %). \throw std::invalid_argument unless sigma > 0 and finite.
double visibility_from_extinction(double sigma);
//! sigma = 3.912 / V. \throw std::invalid_argument unless V > 0 and finite.
double extinction_from_visibility(double visibility);
//! Extinction of a cloud of water droplets: sigma = 3 Q LWC / (4 rho_w r_e) with the
//! extinction efficiency Q = 2 of droplets much larger than the wavelength, LWC in g/m^3,
//! r_e the effective droplet radius in micrometres, rho_w = 1e6 g/m^3. LWC 0.2 g/m^3 with
//! 7 um droplets gives 0.043 1/m (visibility 91 m). \throw std::invalid_argument unless both > 0.
double extinction_from_liquid_water(double lwc_g_per_m3, double droplet_radius_um);

//! Parameters of the same fog in the engines users take it to (docs/placement.md): HDRP's fog
//! attenuation distance (the mean free path 1 / sigma, metres), Unreal's Exponential Height
//! Fog density (it divides by 1000, works in centimetres and integrates with exp2, so
//! FogDensity = sigma / (0.1 (ln 2)^2) at zero height falloff), Godot's fog and volumetric fog
//! density (an extinction per metre: sigma). Zeros unless sigma > 0 and finite.
struct EngineFog {
    double hdrp_attenuation_distance_m = 0.0;
    double unreal_fog_density = 0.0;
    double godot_density = 0.0;
};
EngineFog engine_fog(double extinction);

//! Henyey-Greenstein phase function (1/sr) for cos(theta) between the propagation direction
//! and the direction scattered into; g is clamped to [-0.999, 0.999] so it stays finite.
double henyey_greenstein(double cos_theta, double g);

// ---- Options: medium_options.hpp ------------------------------------------------------------

//! What moves the density over time and space: the medium's noise, wind, time and dissipation,
//! and the layer count the noise is shifted by (so the layers and the medium draw the same fog).
struct MediumDetail {
    double detail = 0.6;                 //!< noise strength, [0, 1]
    double detail_scale = 1500.0;        //!< metres: largest noise feature; the tile repeats every 8x
    double layers = 15.0;                //!< the noise's shift with height h: h layers x (0.137, 0.071) tiles
    glm::dvec2 wind{0.0};                //!< m/s: drift of the noise
    double time = 0.0;                   //!< seconds
    double dissipation_half_life = 0.0;  //!< seconds; 0: none
    //! Metres added to (x, y) before the noise is looked up: a Medium moved by -o keeps its
    //! noise in place with noise_shift o (the renderer's origin, render/src/render_origin.hpp).
    glm::dvec2 noise_shift{0.0};
    bool operator==(const MediumDetail&) const = default;
};
//! The medium's detail, its noise shifted with height per `detail_layers` (the options' own: the
//! layers' count does not change the fog).
MediumDetail medium_detail(const MediumOptions& medium);

//! \throw InputError(label, "/medium/<key>", reason) for options outside their ranges.
void validate_medium_options(const MediumOptions& options, const std::string& label = {});

// ---- The shell --------------------------------------------------------------------------------

//! Regular grid over (x, y): sample (i, j) at (x0 + i dx, y0 + j dy), index j nx + i.
struct MediumGrid {
    int nx = 0, ny = 0;
    double x0 = 0.0, y0 = 0.0, dx = 1.0, dy = 1.0;
    std::vector<double> floor;     //!< max(bottom, ground): nothing lies below it
    std::vector<double> bottom;    //!< h = 0
    std::vector<double> top;       //!< h = 1; equal to bottom where there is no fog
    std::vector<double> coverage;  //!< [0, 1]: the border fade; 0 where there is no fog
    bool operator==(const MediumGrid&) const = default;
};

//! What the grids give at one (x, y): bilinear in each.
struct MediumColumn {
    double floor = 0.0, bottom = 0.0, top = 0.0, coverage = 0.0;
};

class Medium {
public:
    Medium() = default;
    //! \throw InputError when the grid is empty or its arrays do not match nx ny.
    Medium(MediumGrid grid, const MediumOptions& options, const MediumDetail& detail);

    const MediumGrid& grid() const { return grid_; }
    const MediumOptions& options() const { return options_; }
    const MediumDetail& detail() const { return detail_; }

    MediumColumn column(double x, double y) const;
    //! Relative density d(p) in [0, 1] (see the file comment); 0 outside the shell.
    double density(const glm::dvec3& p) const;
    //! h of the file comment: (z - bottom) / (top - bottom) clamped to [0, 1]; 0 where the
    //! column holds no shell.
    double height_fraction(const glm::dvec3& p) const;
    //! sigma_t(p) = extinction * d(p), 1/m.
    double extinction(const glm::dvec3& p) const { return options_.extinction * density(p); }
    //! sigma_s = albedo sigma_t.
    double scattering(const glm::dvec3& p) const { return options_.albedo * extinction(p); }
    //! An upper bound of extinction() everywhere (for delta tracking and step control).
    double max_extinction() const { return options_.extinction * max_density_; }

    //! Box enclosing every point of non-zero density (min z = lowest floor, max z = highest top).
    const Bounds3& bounds() const { return bounds_; }
    //! Volume of the shell weighted by coverage: integral of coverage (top - floor)+ dx dy (m^3).
    double shell_volume() const;

    //! The noise factor alone, 1 - detail + detail smoothstep(0.25, 0.75, n), in [1 - detail, 1].
    double detail_factor(double x, double y, double h) const;
    //! The dissipation factor alone at relative height h, in (0, 1].
    double dissipation(double h) const;

    //! Same medium at another time (drift and dissipation move; the shell stays).
    void set_time(double seconds) { detail_.time = seconds; }

private:
    MediumGrid grid_;
    // The grid's samples interleaved (floor, bottom, top, coverage): a column's four corners in
    // two cache lines, where the grid's four arrays took eight (the reference's and the bake's
    // marches look a column up at each step).
    std::vector<glm::dvec4> corners_;
    MediumOptions options_;
    MediumDetail detail_;
    Bounds3 bounds_;
    double max_density_ = 0.0;
};

//! The deterministic, tileable 2D value noise (three octaves of 8, 16 and 32 cells, seed
//! 20081123) that both the medium and the layers' GPU texture sample: size x size values in
//! [0, 1], row-major, texel (i, j) at ((i + 0.5) / size, (j + 0.5) / size).
const std::vector<float>& fog_noise_tile(int size = 256);
//! The tile sampled as GL_LINEAR + GL_REPEAT samples it, at texture coordinates (s, t).
double sample_fog_noise(double s, double t, int size = 256);

}  // namespace kiri::geometry
