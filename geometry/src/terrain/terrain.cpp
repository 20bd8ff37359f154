#include "kiri/geometry/terrain/terrain.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "kiri/geometry/terrain/ground.hpp"
#include "terrain/terrain_index.hpp"

namespace kiri::geometry {

Terrain::Terrain(Heightfield heightfield) : hf_(std::move(heightfield)) {}
Terrain::~Terrain() = default;
Terrain::Terrain(Terrain&&) noexcept = default;
Terrain& Terrain::operator=(Terrain&&) noexcept = default;

Bounds3 Terrain::bounds() const
{
    const auto [lo, hi] = std::minmax_element(hf_.z.begin(), hf_.z.end());
    const double zmin = hf_.z.empty() ? 0.0 : *lo, zmax = hf_.z.empty() ? 0.0 : *hi;
    return {{hf_.x0, hf_.y0, zmin}, {hf_.x_max(), hf_.y_max(), zmax}};
}

namespace {
// Cell (i, j) and the local coordinates (s, t) in [0, 1]^2 of (x, y), clamped to the grid.
struct CellCoords {
    int i, j;
    double s, t;
};

CellCoords locate(const Heightfield& hf, double x, double y)
{
    const double fx = std::clamp((x - hf.x0) / hf.dx, 0.0, double(hf.nx - 1));
    const double fy = std::clamp((y - hf.y0) / hf.dy, 0.0, double(hf.ny - 1));
    const int i = std::min(int(fx), std::max(hf.nx - 2, 0));
    const int j = std::min(int(fy), std::max(hf.ny - 2, 0));
    return {i, j, fx - i, fy - j};
}
}  // namespace

// Each cell is split along the diagonal (i, j)-(i+1, j+1): the lower-right triangle holds
// s >= t, the upper-left one s < t. Interpolation is linear on the triangle.
double Terrain::height(double x, double y) const { return grid_height(hf_, x, y); }

glm::dvec3 Terrain::normal(double x, double y) const
{
    if (hf_.nx < 2 || hf_.ny < 2)
        return {0.0, 0.0, 1.0};
    const auto [i, j, s, t] = locate(hf_, x, y);
    const double z00 = hf_.at(i, j), z11 = hf_.at(i + 1, j + 1);
    double gx, gy;  // dz/dx, dz/dy on the triangle
    if (s >= t) {
        gx = (hf_.at(i + 1, j) - z00) / hf_.dx;
        gy = (z11 - hf_.at(i + 1, j)) / hf_.dy;
    } else {
        gy = (hf_.at(i, j + 1) - z00) / hf_.dy;
        gx = (z11 - hf_.at(i, j + 1)) / hf_.dx;
    }
    return glm::normalize(glm::dvec3(-gx, -gy, 1.0));
}

const Terrain::Index& Terrain::index() const
{
    // Built on first use: rendering alone never pays for the mesh and the AABB tree.
    if (!index_)
        index_ = std::make_unique<Index>(hf_);
    return *index_;
}

const TriMesh& Terrain::mesh() const { return index().mesh(); }

std::optional<RayHit> Terrain::intersect_ray(const glm::dvec3& origin, const glm::dvec3& dir) const
{
    return index().intersect_ray(origin, dir);
}

glm::dvec3 Terrain::closest_point(const glm::dvec3& p) const { return index().closest_point(p); }

}  // namespace kiri::geometry
