#pragma once
//! \file layer_stack.hpp
//! The view-dependent stack of translucent layers over the fog's base surface ([Thesis] 2.2.3):
//! spacing (2.6), alpha (2.7), narrowing as the eye approaches (2.8) with layers added to keep
//! the thickness (2.9), and enlargement of upper layers (2.10).
//!
//! Over a network of patches the source's per-patch values (O, L, theta) would open cracks
//! between neighbouring patches' layers, so kiri evaluates them per vertex of the base
//! tessellation: L is the distance from the eye to the vertex, theta the angle between the
//! line vertex-eye and the base surface's tangent plane there (continuous over G1 patches),
//! and the enlargement is about one centre for the whole stack (the footprint's centroid).
//! For a single patch and the eye over O these are the source's values; shared edge vertices
//! carry equal inputs, so every layer is crack-free. See docs/layers.md.
#include <algorithm>
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "kiri/geometry/core/fields.hpp"
#include "kiri/geometry/layers/layer_patch_grid.hpp"
#include "kiri/geometry/layers/layer_texture.hpp"
#include "kiri/geometry/medium/medium_options.hpp"
#include "kiri/geometry/fog/tessellate.hpp"

namespace kiri::geometry {

// ---- [Thesis] (2.6)-(2.10), as printed or as docs/references.md reads them ------------------

//! (2.6) r = L / 200 (divisor configurable). L >= 0.
double layer_spacing(double eye_distance, double divisor = 200.0);
//! (2.7) a_i = 1 - 0.9 i / l for 0 <= i <= l; l = 0 gives the base alone, a_0 = 1.
double layer_alpha(double i, double l);
//! (2.8) the spacing narrowed by R = m / L0 when the eye moved m towards O from the reference
//! distance L0: r' = r0 (1 - R). R is clamped to [0, 1] (moving away does not widen the
//! spacing; reaching O gives 0), so r' is continuous in the eye position.
double narrowed_spacing(double r0, double moved, double reference_distance);
//! (2.10) P_k = 1 + (k / 1000) sin(theta); `rate` replaces 1/1000. Takes sin(theta), which the
//! column carries.
double layer_scale(double k, double sin_theta, double rate = 1e-3);
//! theta of (2.10): the angle in [0, pi/2] between the line from `point` to `eye` and the plane
//! through `point` with unit normal `normal`; 0 when the eye is at the point.
double elevation_angle(const glm::dvec3& eye, const glm::dvec3& point, const glm::dvec3& normal);

// ---- The stack ------------------------------------------------------------------------------

//! How a layer is lit and how opaque it is.
enum class LayerShading {
    //! The source's: a gray texture, alpha = opacity a_i per layer (corrected for the spacing),
    //! lit by an ad hoc sun and sky term.
    source,
    //! From the medium (medium.hpp, docs/medium.md): each layer is the slab of fog it stands for,
    //! of optical depth sigma_t r / |cos(view, normal)|, scattering albedo (sun HG(g) T_sun +
    //! ambient), T_sun through the fog above it. The layers then converge to the same fog the
    //! volume renderers draw as layers are added.
    medium,
};

inline constexpr Choice layer_shading_names[] = {{"medium", int(LayerShading::medium)},
                                                 {"source", int(LayerShading::source)}};

struct LayerOptions {
    int count = 15;                  //!< l0 (the source's 15)
    double thickness = 200.0;        //!< T0 = r0 l0 (world metres); the scene takes fog.thickness
    double spacing_divisor = 200.0;  //!< (2.6): the reference distance is L0 = 200 T0 / l0
    bool narrowing = true;
    bool enlargement = true;
    double enlargement_rate = 1e-3;  //!< (2.10)'s 1/1000
    //! Metres added to the base's height: a fog lake's fitted surface is its top, so its stack
    //! starts one thickness below (author_scene_fog sets -thickness in lake mode).
    double base_offset = 0.0;
    int max_count = 120;
    double opacity = 0.12;
    LayerTextureOptions texture;
    double ground_fade = 20.0;
    LayerShading shading = LayerShading::medium;
    //! The layers are smooth: half resolution costs a quarter and barely shows (`kiri bench
    //! --stage layers`).
    double resolution = 0.5;
    //! Level of detail (layer_lod.hpp): away from the eye the base's cells span about this many
    //! pixels of the layer pass; 0 draws the authored tessellation everywhere.
    double lod = 16.0;
    //! The fog's medium (world_layer_options copies the scene's): its optics shade the layers
    //! (LayerShading::medium) and its detail noise, wind, time and dissipation move them, so the
    //! layers and the volume renderers draw the same fog.
    MediumOptions optics;
    bool operator==(const LayerOptions&) const = default;
};

//! The "layers" section. max_count is raised to count when only count is given; the range of
//! enlargement_rate keeps every layer's scale (2.10) at most 2.
template <fields_of<LayerOptions> O, class V>
void visit_fields(O& o, V&& v)
{
    v(o.count,
      {.key = "count",
       .range = closed(1, 1000),
       .doc = "l0, layers above the base at the reference view (the formulas accept l = 0, the base "
              "alone; a scene asks for at least one layer)",
       .widget = closed(1, 100)});
    v(o.max_count,
      {.key = "max_count",
       .range = closed({double(std::max(o.count, 1)), "count"}, 1000),
       .doc = "most layers the narrowing may add",
       .widget = closed({double(o.count), "count"}, 400)});
    v(o.spacing_divisor,
      {.key = "spacing_divisor",
       .range = greater_than(0),
       .doc = "the 200 of (2.6)",
       .widget = closed(20, 2000),
       .log_widget = true});
    v(o.narrowing, {.key = "narrowing", .doc = "(2.8) + (2.9): the spacing narrows and layers are added near the eye"});
    v(o.enlargement,
      {.key = "enlargement",
       .doc = "(2.10): upper layers are enlarged, in the source shading (the medium shading draws the Medium's fog "
              "where it lies)"});
    v(o.enlargement_rate,
      {.key = "enlargement_rate",
       .range = closed(0, {1.0 / std::max(o.max_count, o.count), "1 / max_count"}),
       .doc = "the 1/1000 of (2.10)"});
    v(o.shading, {.key = "shading", .doc = "how a layer is filled and lit (above)", .choices = layer_shading_names});
    v(o.opacity,
      {.key = "opacity",
       .range = closed(0, 0.999),
       .doc = "`source` shading: a layer's alpha where a_i = 1 and the texture is opaque",
       .widget = closed(0, 0.9)});
    visit_fields(o.texture, v);
    v(o.ground_fade,
      {.key = "ground_fade",
       .unit = "m",
       .range = at_least(0),
       .doc = "`source` shading: of the DEM, over which a layer fades into the ground (`medium`: each "
              "layer holds the part of its slab above the ground)",
       .widget = closed(0, 200)});
    v(o.resolution,
      {.key = "resolution",
       .range = closed(0.125, 1),
       .doc = "of the target the layers are drawn into, relative to the frame (1: full resolution; "
              "below 1: reduced; a half-float target of its own, composited by depth, keeping 320 x 180 "
              "texels at least)"});
    v(o.lod,
      {.key = "lod",
       .unit = "px",
       .range = at_least(0),
       .doc = "level of detail: away from the eye the base's cells span about this many pixels of the layer "
              "pass, on a coarser grid of the same surface points; 0 draws the authored tessellation everywhere",
       .widget = closed(0, 32)});
}

//! What a layer vertex needs, evaluated per vertex for one eye (the GPU mirrors this in
//! render/shaders/layers.vert).
struct LayerVertex {
    glm::dvec3 position{0.0};  //!< after offset (z) and enlargement (x, y about the centre)
    double alpha = 0.0;        //!< w_i a_i: (2.7) with the recomputed count, faded in as layers are added
    double exponent = 1.0;     //!< r / r0: the opacity correction 1 - (1 - alpha opacity t)^exponent
    double slab = 1.0;         //!< medium shading: the share of r its slab of fog spans (layer_slab_share)
    double slab_above = 0.5;   //!< of that, the share of r above the layer (layer_slab_share_above)
};

//! Medium shading: the share of the spacing r that layer i's slab of fog spans in a stack of
//! n = T0 / r layers (real-valued), before its fade-in (LayerVertex::alpha). The stack is the
//! trapezoid rule over the thickness, with nodes at layers 0..m (m = floor(n)) and the top at n,
//! the partial layer m + 1 standing in for it: 1/2 for the base, 1 between, 1/2 + (n - m) / 2 for
//! layer m and 1/2 for layer m + 1 (faded in by n - m), so the slabs add up to n r = T0 and a
//! linear profile's optical depth is exact. One slab of r per layer held T0 + r.
double layer_slab_share(double n, int i);
//! Of layer_slab_share, the share of r that lies above layer i: each trapezoid's half next to the
//! layer, so the base's slab lies wholly over it and the top's (layer m + 1, or layer m where n is
//! whole) wholly under it. Where a dense fog's light falls steeply with depth, a slab centred on
//! the top layer put half its path in the clear air over the fog and lit the fog under the top at
//! half its depth (the layers 20 % too dark in the sun over a lake of 10 m visibility).
double layer_slab_share_above(double n, int i);
//! Medium shading where the ground cuts the stack: the share of the spacing r (m) that layer i's
//! slab (its layer_slab_share w) holds above the ground, the layer `clearance` metres over it.
//! The slab reaches down to the ground when the layer under it lies below the ground (hidden by
//! the terrain: clearance < r), so the layers over a column hold its fog from the ground up
//! (exactly, for an even density); 0 below the ground.
double layer_slab_over_ground(double share, int i, double spacing, double clearance);
//! Whether the stack is enlarged (2.10): in the source shading. The medium shading stands for the
//! Medium's fog, which the enlargement would carry off its extent and off the light taken at the
//! base's columns (docs/layers.md).
bool layers_enlarge(const LayerOptions& options);
//! Per-vertex quantities of the stack at base point p (normal n) for an eye.
struct LayerColumn {
    double spacing = 0.0;    //!< r: narrowed (2.8), never below T0 / max_count
    double count = 0.0;      //!< n = T0 / r: real-valued (2.9), so layers fade in without popping
    double sin_theta = 0.0;  //!< of (2.10)
};
LayerColumn layer_column(const LayerOptions& options, const glm::dvec3& eye, const glm::dvec3& point,
                         const glm::dvec3& normal);
//! Layer i (0 = base) of the column at `point` with enlargement about `centre` (x, y).
LayerVertex layer_vertex(const LayerOptions& options, const LayerColumn& column, int i, const glm::dvec3& point,
                         const glm::dvec2& centre);
//! Dissipation factor of layer i of n at the medium's time: 0.5^(t / half_life (1 + i / n)).
double layer_dissipation(const LayerOptions& options, int i, double n);

//! The base tessellation prepared for layers: positions, normals, atlas coordinates and
//! triangles, plus the centre of enlargement. Built once per fitted surface.
struct LayerBase {
    std::vector<glm::dvec3> position, normal;
    std::vector<glm::dvec2> atlas_uv;      //!< into `texture`
    std::vector<std::uint32_t> triangles;  //!< 3 indices each, counter-clockwise from above
    glm::dvec2 centre{0.0};                //!< footprint centroid (x, y)
    glm::dvec3 min{0.0}, max{0.0};         //!< bounds of the base
    LayerTexture texture;
    LayerPatchGrid grid;  //!< the vertices per patch, for a uniform tessellation (layer_lod.hpp)
};
//! \throw InputError (label names the scene) on bad options.
LayerBase make_layer_base(const BaseSurface& surface, const Tessellation& tessellation, const LayerOptions& options,
                          const std::string& label = {});

//! \throw InputError(label, "layers/...", reason) for options outside their documented ranges.
void validate_layer_options(const LayerOptions& options, const std::string& label = {});

//! How many layers above the base an eye needs: ceil of the largest column count over the
//! base's vertices (the top partial layer is faded in), at most options.max_count.
int layers_for_eye(const LayerBase& base, const LayerOptions& options, const glm::dvec3& eye);

//! The stack straight under (or over) the eye, as the drawn triangles interpolate it there: layer
//! i lies at base_z + i spacing (the nearest vertex's column beyond the base's edge).
struct LayerStackUnder {
    double base_z = 0.0;
    double spacing = 0.0;
};
LayerStackUnder layer_stack_under(const LayerBase& base, const LayerOptions& options, const glm::dvec3& eye);

//! How many of layers 0..top lie under the eye in the column nearest to it: 0 with the eye under
//! the base, top + 1 over the whole stack. A ray that climbs crosses the layers over the eye from
//! the lowest, one that descends those under it from the highest, so the pass draws the layers
//! over the eye top first and those under it bottom first: each far to near along its rays.
int layers_under_eye(const LayerBase& base, const LayerOptions& options, const glm::dvec3& eye, int top);
//! The same from the stack under the eye already found (one pass over the base's triangles).
int layers_under_eye(const LayerStackUnder& at_eye, const LayerOptions& options, const glm::dvec3& eye, int top);

//! One layer as a mesh: the base's triangles with LayerVertex data.
struct LayerMesh {
    int index = 0;  //!< 0 = base
    std::vector<LayerVertex> vertices;
};
//! Every layer for an eye, bottom to top (export, tests; the renderer does this on the GPU).
std::vector<LayerMesh> build_layers(const LayerBase& base, const LayerOptions& options, const glm::dvec3& eye);

}  // namespace kiri::geometry
