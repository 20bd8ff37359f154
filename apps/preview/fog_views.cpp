#include "fog_views.hpp"

#include <algorithm>
#include <cmath>

#include "kiri/geometry/fog/fog_target.hpp"
#include "kiri/geometry/terrain/terrain.hpp"

namespace kiri::preview {
namespace {

glm::vec4 mix(const glm::vec4& a, const glm::vec4& b, double t) { return a + float(t) * (b - a); }

// A colour from stops spread evenly over [0, 1].
template <std::size_t N>
glm::vec4 ramp(const glm::vec4 (&stops)[N], double t)
{
    t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0) * double(N - 1);
    const std::size_t i = std::min(std::size_t(t), N - 2);
    return mix(stops[i], stops[i + 1], t - double(i));
}

render::OverlayMesh surface_mesh(const geometry::TriMesh& mesh)
{
    render::OverlayMesh m;
    m.positions.reserve(mesh.n_vertices());
    m.normals.reserve(mesh.n_vertices());
    for (auto v : mesh.vertices()) {
        const auto p = mesh.point(v);
        const auto n = mesh.has_vertex_normals() ? mesh.normal(v) : geometry::TriMesh::Normal(0.0, 0.0, 1.0);
        m.positions.emplace_back(p[0], p[1], p[2]);
        m.normals.emplace_back(n[0], n[1], n[2]);
    }
    m.indices.reserve(mesh.n_faces() * 3);
    for (auto f : mesh.faces())
        for (auto v : mesh.fv_range(f))
            m.indices.push_back(std::uint32_t(v.idx()));
    return m;
}

// Each patch side as a polyline of `segments` pieces evaluated on the exact surface; the
// sides shared by two patches are drawn twice (they coincide: the network is G1).
render::OverlayMesh patch_border_lines(const geometry::BaseSurface& surface, int segments)
{
    render::OverlayMesh m;
    m.primitive = render::OverlayMesh::Primitive::lines;
    const double corners[5][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}};
    for (int f = 0; f < surface.num_patches(); ++f)
        for (int side = 0; side < 4; ++side) {
            const std::uint32_t first = std::uint32_t(m.positions.size());
            for (int k = 0; k <= segments; ++k) {
                const double t = double(k) / segments;
                const double u = corners[side][0] + t * (corners[side + 1][0] - corners[side][0]);
                const double v = corners[side][1] + t * (corners[side + 1][1] - corners[side][1]);
                m.positions.emplace_back(surface.evaluate(f, u, v));
                if (k > 0)
                    m.indices.insert(m.indices.end(), {first + std::uint32_t(k) - 1, first + std::uint32_t(k)});
            }
        }
    return m;
}

render::OverlayMesh control_mesh_lines(const geometry::ControlMesh& control)
{
    render::OverlayMesh m;
    m.primitive = render::OverlayMesh::Primitive::lines;
    for (auto v : control.mesh.vertices()) {
        const auto p = control.mesh.point(v);
        m.positions.emplace_back(p[0], p[1], p[2]);
    }
    for (auto e : control.mesh.edges()) {
        const auto h = control.mesh.halfedge_handle(e, 0);
        m.indices.push_back(std::uint32_t(control.mesh.from_vertex_handle(h).idx()));
        m.indices.push_back(std::uint32_t(control.mesh.to_vertex_handle(h).idx()));
    }
    return m;
}

}  // namespace

glm::vec4 diverging_color(double t)
{
    static const glm::vec4 stops[] = {
        {0.13f, 0.30f, 0.85f, 1.0f}, {0.97f, 0.97f, 0.97f, 1.0f}, {0.85f, 0.15f, 0.12f, 1.0f}};
    return ramp(stops, 0.5 * (t + 1.0));
}

glm::vec4 sequential_color(double t)
{
    // Close to viridis at five stops.
    static const glm::vec4 stops[] = {{0.27f, 0.00f, 0.33f, 1.0f},
                                      {0.23f, 0.32f, 0.55f, 1.0f},
                                      {0.13f, 0.57f, 0.55f, 1.0f},
                                      {0.37f, 0.79f, 0.38f, 1.0f},
                                      {0.99f, 0.91f, 0.14f, 1.0f}};
    return ramp(stops, t);
}

std::shared_ptr<const FogViews> make_fog_views(const geometry::BaseSurface& surface,
                                               const geometry::Tessellation& tessellation,
                                               const geometry::Terrain& terrain, const geometry::FitOptions& fit)
{
    auto views = std::make_shared<FogViews>();
    views->surface = surface_mesh(tessellation.mesh);
    views->patch_borders = patch_border_lines(surface, 16);
    views->control_mesh = control_mesh_lines(surface.control());

    // The fit's target, as BaseSurface::fit computes it.
    const geometry::Heightfield& hf = terrain.heightfield();
    const bool blanket = fit.mode == geometry::FitMode::blanket;
    const geometry::Heightfield smooth =
        blanket ? geometry::smooth_heightfield(hf, fit.smoothing_length) : geometry::Heightfield{};
    const std::size_t n = views->surface.positions.size();
    std::vector<double> deviation(n, 0.0), clearance(n, 0.0);
    std::vector<char> data(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec3 p(views->surface.positions[i]);
        data[i] = geometry::has_data(hf, p.x, p.y);
        const double target = blanket ? geometry::sample_bilinear(smooth, p.x, p.y) + fit.offset : fit.altitude;
        deviation[i] = p.z - target;
        clearance[i] = p.z - terrain.height(p.x, p.y);
        if (data[i])
            views->clearance_range = std::max(views->clearance_range, clearance[i]);
    }
    // The deviation's colour range: the 98th percentile of |deviation|, so that a few large
    // values (where the clearance holds the surface up over a sharp ridge) do not wash out the
    // rest; beyond it the colour saturates.
    std::vector<double> magnitude;
    magnitude.reserve(n);
    for (std::size_t i = 0; i < n; ++i)
        if (data[i])
            magnitude.push_back(std::abs(deviation[i]));
    if (!magnitude.empty()) {
        const auto k = magnitude.begin() + std::ptrdiff_t(0.98 * double(magnitude.size() - 1));
        std::nth_element(magnitude.begin(), k, magnitude.end());
        views->deviation_range = *k;
    }
    const glm::vec4 nodata(0.5f, 0.5f, 0.5f, 1.0f);
    views->deviation_colors.resize(n);
    views->clearance_colors.resize(n);
    // Below a centimetre a deviation is rounding: such a surface maps to white, not to noise.
    const double dr = std::max(views->deviation_range, 0.01), cr = std::max(views->clearance_range, 0.01);
    for (std::size_t i = 0; i < n; ++i) {
        views->deviation_colors[i] = data[i] ? diverging_color(deviation[i] / dr) : nodata;
        // Below the terrain (a lake under a ridge) is the bottom of the map.
        views->clearance_colors[i] = data[i] ? sequential_color(clearance[i] / cr) : nodata;
    }
    return views;
}

}  // namespace kiri::preview
