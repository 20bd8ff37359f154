#include "kiri/geometry/layers/layer_stack.hpp"

#include "kiri/geometry/layers/layer_lod.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/geometric.hpp>

#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/medium/medium.hpp"

namespace kiri::geometry {
namespace {

[[noreturn]] void refuse(const std::string& label, const std::string& field, const std::string& why)
{
    throw InputError(label, "/layers/" + field, why);
}

}  // namespace

void validate_layer_options(const LayerOptions& o, const std::string& label)
{
    check_fields(o, label, "/layers");
    if (!(o.thickness > 0.0) || !std::isfinite(o.thickness))
        refuse(label, "thickness", "must be a finite number > 0 (fog.thickness)");
    if (!std::isfinite(o.base_offset))
        refuse(label, "base_offset", "must be finite");
    validate_medium_options(o.optics, label);
}

bool layers_enlarge(const LayerOptions& o) { return o.enlargement && o.shading == LayerShading::source; }

LayerColumn layer_column(const LayerOptions& o, const glm::dvec3& eye, const glm::dvec3& point,
                         const glm::dvec3& normal)
{
    LayerColumn c;
    if (o.count == 0)
        return c;  // the base alone
    const double r0 = o.thickness / o.count;
    double r = r0;
    if (o.narrowing) {
        const double reference_distance = o.spacing_divisor * r0;
        const double distance = glm::length(eye - point);
        const double moved = std::isfinite(distance) ? reference_distance - distance : 0.0;
        r = narrowed_spacing(r0, moved, reference_distance);
    }
    r = std::max(r, o.thickness / o.max_count);
    c.spacing = r;
    c.count = o.thickness / r;
    c.sin_theta = layers_enlarge(o) ? std::sin(elevation_angle(eye, point, normal)) : 0.0;
    return c;
}

double layer_slab_share(double n, int i)
{
    if (!(n > 0.0) || i < 0)
        return 0.0;
    const double m = std::floor(n), part = n - m, k = double(i);
    return (k >= 1.0 && k <= m ? 0.5 : 0.0) + (k <= m - 1.0 ? 0.5 : 0.0) + (k == m ? 0.5 * part : 0.0) +
        (k == m + 1.0 ? 0.5 : 0.0);
}

double layer_slab_share_above(double n, int i)
{
    if (!(n > 0.0) || i < 0)
        return 0.0;
    const double m = std::floor(n), part = n - m, k = double(i);
    return (k <= m - 1.0 ? 0.5 : 0.0) + (k == m ? 0.5 * part : 0.0);
}

double layer_slab_over_ground(double share, int i, double spacing, double clearance)
{
    if (!(clearance >= 0.0) || !(spacing > 0.0))
        return 0.0;
    if (clearance >= spacing || i == 0)  // the base has no fog under it
        return share;
    const double lower = std::min(share, 0.5);  // the slab's half under the layer
    return clearance / spacing + (share - lower);
}

LayerVertex layer_vertex(const LayerOptions& o, const LayerColumn& c, int i, const glm::dvec3& point,
                         const glm::dvec2& centre)
{
    LayerVertex v;
    if (o.count == 0 || c.count <= 0.0) {
        v.position = point;
        v.alpha = i == 0 ? 1.0 : 0.0;
        return v;
    }
    const double n = c.count;
    const double fade_in = std::clamp(n + 1.0 - i, 0.0, 1.0);
    // (2.7), or the medium's profile 1 - (1 - top_density) h, equal to it at top_density 0.1.
    v.alpha = fade_in *
        (o.shading == LayerShading::medium ? 1.0 - (1.0 - o.optics.top_density) * std::min(double(i), n) / n
                                           : layer_alpha(std::min(double(i), n), n));
    v.exponent = c.spacing / (o.thickness / o.count);
    v.slab = layer_slab_share(n, i);
    v.slab_above = layer_slab_share_above(n, i);
    const double scale = layer_scale(i, c.sin_theta, o.enlargement_rate);
    const glm::dvec2 xy = centre + scale * (glm::dvec2(point) - centre);
    v.position = {xy.x, xy.y, point.z + i * c.spacing};
    return v;
}

double layer_dissipation(const LayerOptions& o, int i, double n)
{
    const MediumOptions& m = o.optics;
    if (!(m.dissipation_half_life > 0.0) || m.time <= 0.0)
        return 1.0;
    const double height = n > 0.0 ? std::min(i / n, 1.0) : 0.0;
    return std::exp2(-m.time / m.dissipation_half_life * (1.0 + height));
}

LayerBase make_layer_base(const BaseSurface& surface, const Tessellation& tessellation, const LayerOptions& options,
                          const std::string& label)
{
    validate_layer_options(options, label);
    const ControlMesh& control = surface.control();
    std::vector<BorderMask> masks(std::size_t(control.num_faces()));
    for (int f = 0; f < control.num_faces(); ++f)
        masks[std::size_t(f)] = patch_border_mask(control, f);
    LayerBase base;
    try {
        base.texture = make_layer_texture(masks, options.texture);
    } catch (const InputError& e) {
        throw InputError(label, "/" + e.field(), e.reason());
    }

    // Centre of enlargement: the patches' O (mean of the four corner points), area-weighted.
    glm::dvec2 weighted{0.0};
    double area = 0.0;
    for (int f = 0; f < control.num_faces(); ++f) {
        const glm::dvec3 c[4] = {surface.evaluate(f, 0, 0), surface.evaluate(f, 1, 0), surface.evaluate(f, 1, 1),
                                 surface.evaluate(f, 0, 1)};
        const glm::dvec2 o = 0.25 * glm::dvec2(c[0] + c[1] + c[2] + c[3]);
        const glm::dvec2 d1 = glm::dvec2(c[2] - c[0]), d2 = glm::dvec2(c[3] - c[1]);
        const double a = 0.5 * std::abs(d1.x * d2.y - d1.y * d2.x);
        weighted += a * o;
        area += a;
    }
    if (area > 0.0)
        base.centre = weighted / area;

    const TriMesh& mesh = tessellation.mesh;
    OpenMesh::VPropHandleT<int> patch_id;
    if (!mesh.get_property_handle(patch_id, patch_id_property))
        throw InputError(label, "/fog/tessellation", "the tessellation carries no patch ids");
    const std::size_t nv = mesh.n_vertices();
    base.position.resize(nv);
    base.normal.resize(nv);
    base.atlas_uv.resize(nv);
    base.min = glm::dvec3(INFINITY);
    base.max = glm::dvec3(-INFINITY);
    for (auto vh : mesh.vertices()) {
        const auto i = std::size_t(vh.idx());
        const auto& p = mesh.point(vh);
        const auto& n = mesh.normal(vh);
        const auto& t = mesh.texcoord2D(vh);
        base.position[i] = {p[0], p[1], p[2] + options.base_offset};
        base.normal[i] = {n[0], n[1], n[2]};
        base.atlas_uv[i] = base.texture.atlas_uv(masks[std::size_t(mesh.property(patch_id, vh))], t[0], t[1]);
        base.min = glm::min(base.min, base.position[i]);
        base.max = glm::max(base.max, base.position[i]);
    }
    base.triangles.reserve(mesh.n_faces() * 3);
    for (auto fh : mesh.faces())
        for (auto vh : mesh.fv_range(fh))
            base.triangles.push_back(std::uint32_t(vh.idx()));
    base.grid = make_layer_patch_grid(tessellation, base.position);
    return base;
}

namespace {
std::size_t nearest_vertex(const LayerBase& base, const glm::dvec3& eye)
{
    std::size_t nearest = 0;
    double best = INFINITY;
    for (std::size_t i = 0; i < base.position.size(); ++i) {
        const glm::dvec3 d = eye - base.position[i];
        const double d2 = glm::dot(d, d);
        if (d2 < best) {
            best = d2;
            nearest = i;
        }
    }
    return nearest;
}
}  // namespace

int layers_for_eye(const LayerBase& base, const LayerOptions& options, const glm::dvec3& eye)
{
    if (options.count == 0 || base.position.empty())
        return 0;
    // A column's count only grows as the eye comes closer: the nearest vertex decides.
    const std::size_t nearest = nearest_vertex(base, eye);
    const double most = layer_column(options, eye, base.position[nearest], base.normal[nearest]).count;
    return std::clamp(int(std::ceil(most - 1e-9)), options.count, options.max_count);
}

namespace {
// The base's triangle under (x, y) seen from above, and where in it: the GPU's layer i there is
// its vertices' base + i r interpolated (linear over the triangle). False where none lies under.
bool stack_under(const LayerBase& base, const LayerOptions& options, const glm::dvec3& eye, double& base_z,
                 double& spacing)
{
    for (std::size_t t = 0; t + 2 < base.triangles.size(); t += 3) {
        const std::uint32_t ia = base.triangles[t], ib = base.triangles[t + 1], ic = base.triangles[t + 2];
        const glm::dvec3 &a = base.position[ia], &b = base.position[ib], &c = base.position[ic];
        const double area = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
        if (!(std::abs(area) > 0.0))
            continue;
        const double wb = ((eye.x - a.x) * (c.y - a.y) - (c.x - a.x) * (eye.y - a.y)) / area;
        const double wc = ((b.x - a.x) * (eye.y - a.y) - (eye.x - a.x) * (b.y - a.y)) / area;
        const double wa = 1.0 - wb - wc;
        constexpr double eps = -1e-9;  // shared edges: either triangle may answer
        if (wa < eps || wb < eps || wc < eps)
            continue;
        const auto r = [&](std::uint32_t v) {
            return options.count > 0 ? layer_column(options, eye, base.position[v], base.normal[v]).spacing : 0.0;
        };
        base_z = wa * a.z + wb * b.z + wc * c.z;
        spacing = wa * r(ia) + wb * r(ib) + wc * r(ic);
        return true;
    }
    return false;
}
}  // namespace

LayerStackUnder layer_stack_under(const LayerBase& base, const LayerOptions& options, const glm::dvec3& eye)
{
    LayerStackUnder s;
    if (base.position.empty())
        return s;
    // Where no triangle lies under the eye (beyond the base's edge), the nearest vertex's column.
    if (!stack_under(base, options, eye, s.base_z, s.spacing)) {
        const std::size_t nearest = nearest_vertex(base, eye);
        s.base_z = base.position[nearest].z;
        s.spacing =
            options.count > 0 ? layer_column(options, eye, base.position[nearest], base.normal[nearest]).spacing : 0.0;
    }
    return s;
}

int layers_under_eye(const LayerBase& base, const LayerOptions& options, const glm::dvec3& eye, int top)
{
    if (base.position.empty() || !std::isfinite(eye.z))
        return 0;
    // The layers over the eye's own (x, y), where its rays start: the nearest vertex of a sloping
    // base may lie a spacing higher or lower than the base under the eye, and a count one off
    // draws the layer the eye's rays cross first behind the next one.
    return layers_under_eye(layer_stack_under(base, options, eye), options, eye, top);
}

int layers_under_eye(const LayerStackUnder& at_eye, const LayerOptions& options, const glm::dvec3& eye, int top)
{
    const double above = eye.z - at_eye.base_z, r = at_eye.spacing;
    if (!(above >= 0.0))
        return 0;
    if (options.count == 0)
        return top + 1;
    if (!(r > 0.0))
        return top + 1;
    return int(std::clamp(std::floor(above / r) + 1.0, 0.0, double(top + 1)));
}

std::vector<LayerMesh> build_layers(const LayerBase& base, const LayerOptions& options, const glm::dvec3& eye)
{
    const int top = layers_for_eye(base, options, eye);
    std::vector<LayerColumn> columns(base.position.size());
    for (std::size_t v = 0; v < columns.size(); ++v)
        columns[v] = layer_column(options, eye, base.position[v], base.normal[v]);
    std::vector<LayerMesh> layers(std::size_t(top) + 1);
    for (int i = 0; i <= top; ++i) {
        LayerMesh& layer = layers[std::size_t(i)];
        layer.index = i;
        layer.vertices.resize(columns.size());
        for (std::size_t v = 0; v < columns.size(); ++v) {
            layer.vertices[v] = layer_vertex(options, columns[v], i, base.position[v], base.centre);
            layer.vertices[v].alpha *= layer_dissipation(options, i, columns[v].count);
        }
    }
    return layers;
}

}  // namespace kiri::geometry
