#pragma once
// Internal: the reference ray marcher's integrator (reference_fog.hpp says what it computes).
#include <memory>
#include <vector>

#include "kiri/geometry/reference/reference_fog.hpp"
#include "reference/heightfield_ray.hpp"
#include "reference/shell_intervals.hpp"

namespace kiri::geometry::detail {

//! One fine step of a view ray: midpoint, length, the two media's mean extinction, the optical
//! depth before it.
struct MarchStep {
    double t = 0.0, dt = 0.0, sigma_medium = 0.0, sigma_height = 0.0, tau_before = 0.0;
};

//! Sun term at a knot: optical depth to the sun (valid where visible) and terrain visibility.
struct SunKnot {
    double t = 0.0, tau = 0.0;
    bool visible = true;
};

//! Per-thread buffers, so tracing allocates nothing once warm.
struct MarchScratch {
    std::vector<Interval> view_intervals, sun_intervals;
    std::vector<MarchStep> steps, split;
    std::vector<SunKnot> knots;
};

class FogMarcher {
public:
    FogMarcher(const FogVolume& fog, const Heightfield* terrain, const FogLighting& light, const ReferenceOptions& o);
    RayFog trace(const glm::dvec3& origin, const glm::dvec3& dir, double t_max, MarchScratch& scratch) const;

    //! Optical depth from p towards the sun (both media), stopping early past the cutoff.
    double sun_optical_depth(const glm::dvec3& p, MarchScratch& scratch) const;
    //! Whether the terrain leaves the sun visible from p.
    bool sun_visible(const glm::dvec3& p) const;

private:
    FogVolume fog_;
    std::unique_ptr<HeightfieldRay> terrain_;
    const Heightfield* heightfield_ = nullptr;
    FogLighting light_;
    glm::dvec3 sun_{0.0, 0.0, 1.0};
    ReferenceOptions o_;
    // The lighting model's slowest fall of the sun's light with tau_sun (sun_scattering_decay),
    // and the optical depth towards the sun past which that light is below the options'
    // sun_cutoff's: sun_cutoff / decay.
    double sun_decay_ = 1.0, sun_cutoff_ = 12.0;

    double sigma_medium(const glm::dvec3& p) const { return fog_.medium ? fog_.medium->extinction(p) : 0.0; }
    //! Longest step along d at p that resolves the medium's features (grid cells, noise
    //! texels, height-fog scale) to `fraction` of their size.
    double feature_length(const glm::dvec3& p, const glm::dvec3& d, bool in_shell, double fraction) const;
    //! Steps of the view ray up to t_end (stops once T < min_transmittance).
    void march_view(const glm::dvec3& o, const glm::dvec3& w, double t_end, MarchScratch& s) const;
    //! Fills s.knots along the steps: the sun term at knots, shadow edges bracketed.
    void place_knots(const glm::dvec3& o, const glm::dvec3& w, MarchScratch& s) const;
    //! Cuts the steps at the terrain shadow edges between knots.
    void split_at_shadow_edges(MarchScratch& s) const;
    SunKnot sun_knot(const glm::dvec3& o, const glm::dvec3& w, double t, MarchScratch& s) const;
    glm::dvec3 surface_radiance(const glm::dvec3& p, MarchScratch& s, glm::dvec3* fog_shade = nullptr,
                                double* sun_through = nullptr) const;
    glm::dvec3 sky_radiance(const glm::dvec3& w) const;
};

}  // namespace kiri::geometry::detail
