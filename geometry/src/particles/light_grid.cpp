#include "kiri/geometry/particles/light_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <glm/geometric.hpp>

namespace kiri::geometry {
namespace {

// Shears steeper than this would make voxels needles; the unsheared frame is kept instead.
constexpr double max_shear = 8.0;

struct Extent {
    double lo = std::numeric_limits<double>::infinity(), hi = -std::numeric_limits<double>::infinity();
    void add(double a, double b)
    {
        lo = std::min(lo, a);
        hi = std::max(hi, b);
    }
    double size() const { return hi - lo; }
};

// Depth range w' of the cloud for a shear: each particle's sphere (a billboard fragment can be
// r away in any direction) and its shadow start over its footprint (w - a u - b v varies by
// r sqrt(a^2 + b^2) across the disc).
Extent depth_extent(const std::vector<glm::dvec3>& uvw, const ParticleCloud& cloud, double a, double b)
{
    Extent e;
    const double tilt = 1.0 + std::sqrt(a * a + b * b);
    for (std::size_t k = 0; k < uvw.size(); ++k) {
        const double w = uvw[k].z - a * uvw[k].x - b * uvw[k].y;
        const double r = cloud.particles[k].radius * tilt;
        e.add(w - r, w + r);
    }
    return e;
}

// Least-squares plane w = a u + b v + c through the centres.
void fit_plane(const std::vector<glm::dvec3>& uvw, double& a, double& b)
{
    glm::dvec3 mean(0.0);
    for (const glm::dvec3& q : uvw)
        mean += q;
    mean /= double(uvw.size());
    double suu = 0, suv = 0, svv = 0, suw = 0, svw = 0;
    for (const glm::dvec3& q : uvw) {
        const glm::dvec3 d = q - mean;
        suu += d.x * d.x;
        suv += d.x * d.y;
        svv += d.y * d.y;
        suw += d.x * d.z;
        svw += d.y * d.z;
    }
    const double det = suu * svv - suv * suv;
    a = b = 0.0;
    if (std::abs(det) > 1e-12 * std::max(suu * svv, 1e-300)) {
        a = (suw * svv - svw * suv) / det;
        b = (svw * suu - suw * suv) / det;
    }
}

}  // namespace

glm::dvec3 LightGrid::light_coordinates(const glm::dvec3& p) const
{
    return {glm::dot(u_axis, p), glm::dot(v_axis, p), -glm::dot(light, p)};
}

glm::dvec3 LightGrid::to_grid(const glm::dvec3& p) const
{
    const glm::dvec3 q = light_coordinates(p);
    return {(q.x - origin.x) / voxel.x, (q.y - origin.y) / voxel.y,
            (q.z - shear_u * q.x - shear_v * q.y - origin.z) / voxel.z};
}

glm::dmat4 LightGrid::world_to_texture() const
{
    // Rows: g_x = (U.p - u0) / du, g_y = (V.p - v0) / dv, g_z = ((-L - a U - b V).p - w0) / dw; then / size.
    const glm::dvec3 depth_axis = -light - shear_u * u_axis - shear_v * v_axis;
    const glm::dvec3 rows[3] = {u_axis / (voxel.x * size[0]), v_axis / (voxel.y * size[1]),
                                depth_axis / (voxel.z * size[2])};
    const double offsets[3] = {-origin.x / (voxel.x * size[0]), -origin.y / (voxel.y * size[1]),
                               -origin.z / (voxel.z * size[2])};
    glm::dmat4 m(0.0);
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c)
            m[c][r] = rows[r][c];
        m[3][r] = offsets[r];
    }
    m[3][3] = 1.0;
    return m;
}

int LightGrid::shadow_start(double w, int i, int j) const
{
    const double g = (w - shear_u * column_u(i) - shear_v * column_v(j) - origin.z) / voxel.z;
    const double k = std::ceil(g - 0.5);
    return int(std::clamp(k, -1.0, double(size[2])));
}

LightGrid make_light_grid(const ParticleCloud& cloud, const glm::dvec3& light, const LightGridOptions& options)
{
    const double len = glm::length(light);
    if (!(len > 0.0) || !std::isfinite(len))
        throw std::invalid_argument("make_light_grid: the light direction must be finite and not zero");
    if (cloud.particles.empty())
        throw std::invalid_argument("make_light_grid: no particles");
    const int nw = options.depth_resolution > 0 ? options.depth_resolution : options.resolution;
    if (options.resolution < 4 || options.resolution > 1024 || nw < 4 || nw > 1024)
        throw std::invalid_argument("make_light_grid: resolution outside [4, 1024]");
    LightGrid g;
    g.light = light / len;
    // U horizontal where it can be (perpendicular to the light and to z), V completes the frame.
    const glm::dvec3 up(0.0, 0.0, 1.0);
    const glm::dvec3 side = glm::cross(up, g.light);
    g.u_axis = glm::length(side) > 1e-9 ? glm::normalize(side) : glm::dvec3(1.0, 0.0, 0.0);
    g.v_axis = glm::normalize(glm::cross(g.light, g.u_axis));

    std::vector<glm::dvec3> uvw(cloud.particles.size());
    for (std::size_t k = 0; k < uvw.size(); ++k)
        uvw[k] = g.light_coordinates(cloud.particles[k].position);
    double a = 0.0, b = 0.0;
    if (options.frame != LightFrame::light && uvw.size() >= 3)
        fit_plane(uvw, a, b);
    const bool shear_ok = std::isfinite(a) && std::isfinite(b) && std::sqrt(a * a + b * b) <= max_shear;
    bool sheared = options.frame == LightFrame::sheared && shear_ok;
    if (options.frame == LightFrame::automatic && shear_ok)
        sheared = depth_extent(uvw, cloud, a, b).size() < depth_extent(uvw, cloud, 0.0, 0.0).size();
    g.frame = sheared ? LightFrame::sheared : LightFrame::light;
    g.shear_u = sheared ? a : 0.0;
    g.shear_v = sheared ? b : 0.0;

    Extent eu, ev;
    for (std::size_t k = 0; k < uvw.size(); ++k) {
        const double r = cloud.particles[k].radius;
        eu.add(uvw[k].x - r, uvw[k].x + r);
        ev.add(uvw[k].y - r, uvw[k].y + r);
    }
    const Extent ew = depth_extent(uvw, cloud, g.shear_u, g.shear_v);
    const int n = options.resolution;
    g.size = {n, n, nw};
    // One empty voxel on each side of u and v and before the first slice (a lookup clamped to
    // the edge then reads nothing), at least a millimetre per voxel.
    const double du = std::max(eu.size() / (n - 2), 1e-3), dv = std::max(ev.size() / (n - 2), 1e-3);
    const double dw = std::max(ew.size() / (nw - 1), 1e-3);
    g.voxel = {du, dv, dw};
    g.origin = {eu.lo - du, ev.lo - dv, ew.lo - dw};
    return g;
}

}  // namespace kiri::geometry
