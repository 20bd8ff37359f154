#include "kiri/geometry/surface/surface.hpp"

#include <cmath>
#include <string>

#include <glm/geometric.hpp>

#include "kiri/geometry/core/error.hpp"

namespace kiri::geometry {

std::unique_ptr<Surface> make_gregory_surface(const PolyMesh& mesh);
std::unique_ptr<Surface> make_limit_surface(const PolyMesh& mesh);

const char* to_string(SurfaceKind kind) { return kind == SurfaceKind::gregory ? "gregory" : "catmull-clark"; }

std::unique_ptr<Surface> make_surface(const PolyMesh& mesh, SurfaceKind kind)
{
    for (auto v : mesh.vertices()) {
        const auto p = mesh.point(v);
        if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
            throw InputError("", "control mesh/vertex " + std::to_string(v.idx()), "non-finite coordinate");
    }
    return kind == SurfaceKind::gregory ? make_gregory_surface(mesh) : make_limit_surface(mesh);
}

PatchSamples Surface::evaluate(int face, std::span<const double> u, std::span<const double> v, bool normals) const
{
    PatchSamples s;
    s.resize(u.size(), normals);
    evaluate_into(face, u, v, s.spans());
    return s;
}

void Surface::set_control_points(std::span<const glm::dvec3> points)
{
    if (points.size() != points_.size())
        throw InputError("", "control points",
                         "expected " + std::to_string(points_.size()) + ", got " + std::to_string(points.size()));
    for (const auto& p : points)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw InputError("", "control points", "non-finite coordinate");
    points_.assign(points.begin(), points.end());
    control_points_changed();
}

void Surface::check_face(int face) const
{
    if (face < 0 || face >= num_faces())
        throw InputError("", "face",
                         "face " + std::to_string(face) + " out of range [0, " + std::to_string(num_faces()) + ")");
}

}  // namespace kiri::geometry
