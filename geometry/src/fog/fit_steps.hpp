#pragma once
// Internal: the steps of BaseSurface::fit, in the order it runs them: validate the options,
// build the target, lay out the samples, assemble the per-face normal equations, solve, hold
// the clearance (active set), lift (local, then uniform) and measure. Each step reads the
// plain structs the previous ones made.
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec2.hpp>

#include "fog/fit_samples.hpp"
#include "kiri/geometry/fog/base_surface.hpp"
#include "surface/face_stencil.hpp"

namespace kiri::geometry {

class FitSolver;

//! \throw InputError for a non-finite option, a negative smoothness and, in blanket mode, a
//!        negative clearance, a thickness <= 0 or a clearance above the thickness.
void validate_fit_options(const FitOptions& options);

//! The height the fit aims at over (x, y): the smoothed terrain plus the offset (blanket), or
//! the lake's altitude (flat, or its grid's).
struct FitTarget {
    FitMode mode = FitMode::blanket;
    Heightfield smooth;  // blanket only
    double offset = 0.0, altitude = 0.0;
    std::shared_ptr<const Heightfield> altitude_grid;

    double at(double x, double y) const;
};
FitTarget make_fit_target(const Heightfield& terrain, const FitOptions& options);

//! What every step looks through: the stencils, the samples and the control vertices' xy,
//! which the fit never moves (kept relative to the control mesh's origin).
struct FitLayout {
    const FaceStencils& stencils;
    const FitSamples& samples;
    glm::dvec2 origin{0.0};
    std::vector<glm::dvec2> relative_xy;
    double patch_size = 0.0;

    int num_faces() const { return stencils.num_faces(); }
    int num_vertices() const { return int(relative_xy.size()); }
};
FitLayout make_fit_layout(const ControlMesh& control, const FaceStencils& stencils, const FitSamples& samples);

//! The terrain and the target under every sample, cached once: the constraint steps revisit
//! them many times.
struct SampleHeights {
    std::vector<double> terrain, target;
    std::vector<std::uint8_t> has_data;  // 0 over nodata cells: left out of data and constraint
    long long with_data = 0, without_data = 0;
};

//! Normal equations of one face, L h_S = r over the face's support S.
struct FaceSystem {
    std::vector<double> L, r;
};
//! Adds weight * (w . h_S - rhs)^2 to the face's energy (w: the support's n weights).
void add_row(FaceSystem& system, const double* w, std::size_t n, double weight, double rhs);
inline void add_row(FaceSystem& system, const std::vector<double>& w, double weight, double rhs)
{
    add_row(system, w.data(), w.size(), weight, rhs);
}

//! The fit's energy face by face (FitOptions::smoothness): the data term, each face's samples
//! sharing a data weight of 1 (data_weight per sample), then the thin-plate term.
struct FitAssembly {
    std::vector<FaceSystem> faces;
    std::vector<double> data_weight;  // per face
    SampleHeights samples;
    //! Every sample's stencil weights (order 0), a face's samples' in a row, support-sized each,
    //! evaluated once here: the clearance's iterations and the lifts revisit them (evaluated
    //! again at each visit they were a third of authoring the default scene).
    std::vector<double> weights;
    std::vector<std::size_t> face_weights;  // per face, where its first sample's weights start
    const double* weights_of(const FitLayout& layout, int face, std::size_t sample) const
    {
        return weights.data() + face_weights[face] +
            (sample - layout.samples.face_begin[face]) * layout.stencils.support(face).size();
    }
};
FitAssembly assemble_fit(const FitLayout& layout, const Terrain& terrain, const FitTarget& target,
                         const FitOptions& options);

//! \throw InputError when no sample has terrain data, or (lake) the terrain is above the
//!        lake's top everywhere.
void require_fog(const SampleHeights& samples, const FitOptions& options);

//! The target under each control vertex (the solver's regularisation pulls towards it).
std::vector<double> vertex_targets(const FitLayout& layout, const FitTarget& target);

//! The surface's height on face f where its stencil weights are w (support-sized), for the given
//! control heights.
double surface_z(const FitLayout& layout, int face, const double* w, const std::vector<double>& heights);

//! Blanket: z >= terrain + clearance at every sample, by augmented-Lagrangian iterations from
//! `heights` (the unconstrained solution); returns the best iterate and counts the samples
//! held in the last check.
std::vector<double> enforce_clearance(const FitLayout& layout, const FitAssembly& assembly, const FitOptions& options,
                                      FitSolver& solver, std::vector<double> heights, long long& held);

//! Blanket, local guarantee: raises the control vertices under samples still short of
//! terrain + clearance; returns the largest raise.
double lift_locally(const FitLayout& layout, const FitAssembly& assembly, double clearance,
                    std::vector<double>& heights);

//! The surface's height at every sample (with or without data).
std::vector<double> surface_at_samples(const FitLayout& layout, const FitAssembly& assembly,
                                       const std::vector<double>& heights);

//! The largest shortfall below terrain + clearance over the samples with data (>= 0).
double worst_shortfall(const SampleHeights& samples, double clearance, const std::vector<double>& surface);

//! Blanket, final guarantee: lifts every control height by a little more than the shortfall
//! (when > 0); returns the lift.
double lift_uniformly(double shortfall, std::vector<double>& heights);

//! Deviation from the target, clearance and fog fraction of the surface lifted by report.lift.
void measure_fit(const SampleHeights& samples, const std::vector<double>& surface, FitReport& report);

}  // namespace kiri::geometry
