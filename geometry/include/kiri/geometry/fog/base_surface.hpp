#pragma once
//! \file base_surface.hpp
//! The fog's base surface: a smooth surface over the quad control mesh (Gregory patch network
//! or Catmull-Clark limit), fitted to a target over the terrain (docs/fog.md; [Thesis] 2.2.1).
#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "kiri/geometry/core/fields.hpp"
#include "kiri/geometry/fog/footprint.hpp"
#include "kiri/geometry/surface/surface.hpp"
#include "kiri/geometry/terrain/terrain.hpp"

namespace kiri::geometry {

class FaceStencils;
struct FitSamples;

enum class FitMode {
    blanket,  //!< smoothed terrain + offset, never below terrain + clearance
    lake,     //!< flat at `altitude`; passes under the ridges, fog only where terrain is below
};
inline constexpr Choice fit_mode_names[] = {{"blanket", int(FitMode::blanket)}, {"lake", int(FitMode::lake)}};

struct FitOptions {
    FitMode mode = FitMode::blanket;
    double offset = 60.0;
    double smoothing_length = 400.0;  //!< (fog_target.hpp)
    double altitude = 0.0;
    //! Lake: when set, the fog top at each point is this grid's bilinear height (m) instead of
    //! the flat altitude: fog placed by the terrain whose top is not flat (wind-blown, or
    //! regions with different tops; fog_placement.hpp). Must be finite everywhere.
    std::shared_ptr<const Heightfield> altitude_grid;
    double clearance = 10.0;
    double thickness = 200.0;
    //! Weight of the thin-plate energy against the data term: E = sum_faces [ mean_samples
    //! (z - target)^2 + smoothness h^4 mean_quadrature (z_xx^2 + 2 z_xy^2 + z_yy^2) ], h the
    //! patch size, so it is dimensionless and independent of the patch and sample counts.
    //! 0 = plain least squares. Planes are fitted exactly at any value.
    double smoothness = 0.05;
    //! Samples: every terrain grid vertex under the control mesh, plus this many cell-centred
    //! (u, v) samples per patch side (so each patch has data on coarse terrains); 0 = 4.
    int samples_per_patch = 0;
    int max_active_set_iterations = 50;
    bool operator==(const FitOptions&) const = default;
};

//! Keys of the scene's "fog" section (fog_spec.hpp). Lake mode needs an altitude; a blanket's
//! clearance is at most its thickness.
template <fields_of<FitOptions> O, class V>
void visit_fields(O& o, V&& v)
{
    v(o.mode,
      {.key = "mode",
       .doc = "`blanket`: the terrain smoothed at `smoothing` plus `offset`, never below terrain + "
              "`clearance`; `lake`: flat at `altitude`, passing under the ridges (fog only where the "
              "terrain is below it)",
       .choices = fit_mode_names});
    v(o.offset,
      {.key = "offset", .unit = "m", .doc = "blanket: above the smoothed terrain", .widget = closed(-200, 1000)});
    v(o.smoothing_length,
      {.key = "smoothing",
       .unit = "m",
       .range = at_least(0),
       .doc = "blanket: sigma of the Gaussian that smooths the terrain into the target (three "
              "box passes; 0 = none)",
       .widget = closed(0, 5000)});
    v(o.altitude,
      {.key = "altitude",
       .unit = "m",
       .doc = "lake: altitude of the fog top, metres of the DEM (the exaggeration stretches it with the "
              "terrain: `jacksboro_lake.json` fills to the 460 m contour)",
       .shown_default = "required in lake mode"});
    v(o.clearance,
      {.key = "clearance",
       .unit = "m",
       .range = at_least(0),
       .doc = "blanket: hard minimum height of the surface above the terrain, held at every terrain "
              "grid vertex under the mesh; at most `thickness`",
       .widget = closed(0, {o.thickness, "thickness"})});
    v(o.thickness,
      {.key = "thickness",
       .unit = "m",
       .range = greater_than(0),
       .doc = "fog thickness",
       .widget = closed({std::max(o.clearance, 1.0), "clearance"}, 2000),
       .log_widget = true});
    v(o.smoothness,
      {.key = "smoothness",
       .range = at_least(0),
       .doc = "weight of the thin-plate energy against the data term (dimensionless: it is scaled by "
              "the patch size); 0 = plain least squares, larger = gentler hills",
       .widget = closed(0, 10),
       .log_widget = true});
    v(o.samples_per_patch,
      {.key = "samples_per_patch",
       .range = closed(1, 1024),
       .doc = "(u, v) samples per patch side, in addition to every terrain grid vertex",
       .widget = closed(0, 64),
       .shown_default = "4",
       .omit_default = true});
}

//! Fit figures over the samples that have terrain data (the "fit" of report.json).
struct FitReport {
    double max_deviation = 0.0;  //!< max |surface - target| (m)
    double rms_deviation = 0.0;  //!< (m)
    //! min (surface - terrain) over the samples (m); >= clearance in blanket mode. The samples
    //! include every terrain grid vertex, where the piecewise-linear terrain peaks; between
    //! them the surface can only come closer where it is convex (a few % of the clearance on
    //! the tests' terrains).
    double min_clearance = 0.0;
    double local_lift = 0.0;    //!< largest control-vertex raise of the local guarantee step (m)
    double lift = 0.0;          //!< uniform lift of the final guarantee step (m)
    double fog_fraction = 0.0;  //!< share of samples with the terrain below the surface
    long long samples = 0;
    long long grid_vertex_samples = 0;  //!< of which terrain grid vertices
    long long nodata_samples = 0;       //!< samples over nodata cells (left out of data and constraint)
    long long active_constraints = 0;   //!< samples held at terrain + clearance (blanket)
    int iterations = 0;                 //!< active-set solves
    bool samples_reused = false;        //!< the sample layout of the previous fit (same terrain grid)
    int samples_per_patch = 0;
    double seconds_target = 0.0, seconds_assemble = 0.0, seconds_solve = 0.0;
};

//! Surface over a control mesh. The topology and the per-face stencils are built once in the
//! constructor; fit() and set_heights() change only the control heights.
class BaseSurface {
public:
    BaseSurface(ControlMesh control, SurfaceKind kind);
    ~BaseSurface();
    BaseSurface(BaseSurface&&) noexcept;
    BaseSurface& operator=(BaseSurface&&) noexcept;

    SurfaceKind kind() const { return kind_; }
    const ControlMesh& control() const { return control_; }
    int num_patches() const { return control_.num_faces(); }

    //! Fits the control heights to the target of options over the terrain.
    //! \throw InputError (bad options, clearance above thickness, a lake below all terrain,
    //!        no sample with data).
    FitReport fit(const Terrain& terrain, const FitOptions& options);

    std::vector<double> heights() const;
    void set_heights(const std::vector<double>& z);

    //! Point and first derivatives of patch `face` at (u, v) in [0,1]^2; corner k of the face's
    //! vertex list (OpenMesh fv order) sits at (0,0), (1,0), (1,1), (0,1).
    glm::dvec3 evaluate(int face, double u, double v, glm::dvec3* du = nullptr, glm::dvec3* dv = nullptr) const;
    //! The surface itself (surface.hpp), kept in step with the control heights.
    const Surface& surface() const { return *surface_; }

    //! The linear map behind evaluate() (internal type, see geometry/src/surface).
    const FaceStencils& stencils() const { return *stencils_; }

private:
    // The sample layout for the terrain's grid: the previous one when the grid is the same
    // (returns true), else a new one.
    bool place_samples(const Heightfield& terrain, int per_side);

    ControlMesh control_;
    SurfaceKind kind_;
    std::unique_ptr<FaceStencils> stencils_;  // the fit's linear map
    std::unique_ptr<Surface> surface_;        // evaluation (surface module)
    // The samples' (face, u, v) depend on the terrain's grid, not its heights: kept for refits.
    std::shared_ptr<const FitSamples> samples_;
    std::vector<double> samples_key_;
};

const char* to_string(FitMode mode);

}  // namespace kiri::geometry
