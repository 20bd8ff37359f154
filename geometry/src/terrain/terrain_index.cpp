// The terrain's triangle mesh (OpenMesh) and its CGAL AABB tree. CGAL stays in this file.
//
// The tree does not copy the triangles: a primitive is a face number, and the triangle is
// rebuilt from the heightfield on demand (property maps shared by the whole tree). That keeps
// a 4096^2 grid (33.5 M triangles) at ~4 bytes per primitive plus the tree nodes, instead of
// 72 more bytes per triangle for a cached copy.
#include "terrain/terrain_index.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>

#include <boost/iterator/counting_iterator.hpp>
#include <CGAL/AABB_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <glm/geometric.hpp>

#include "kiri/geometry/core/error.hpp"

namespace kiri::geometry {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point3 = K::Point_3;
using Triangle3 = K::Triangle_3;
using FaceId = std::uint32_t;

// What the index needs of the heightfield. The heights are read through the vector's buffer,
// which survives moving the Terrain (and its Heightfield) while this index lives on.
struct IndexGrid {
    int nx = 0, ny = 0;
    double dx = 1.0, dy = 1.0, x0 = 0.0, y0 = 0.0;
    const double* z = nullptr;
    std::size_t size() const { return std::size_t(nx) * std::size_t(ny); }
    double at(int i, int j) const { return z[std::size_t(j) * nx + i]; }
    double x_of(int i) const { return x0 + i * dx; }
    double y_of(int j) const { return y0 + j * dy; }
};

// Face f of the grid: cell c = f / 2 (row-major, (nx - 1) cells a row), k = f % 2.
// k = 0: (i,j) (i+1,j) (i+1,j+1), the triangle with s >= t; k = 1: (i,j) (i+1,j+1) (i,j+1).
// Both are counter-clockwise seen from above, so their normals point up.
struct FaceCorners {
    int i[3], j[3];
};

FaceCorners corners(const IndexGrid& hf, FaceId f)
{
    const int cell = int(f / 2), ci = cell % (hf.nx - 1), cj = cell / (hf.nx - 1);
    if (f % 2 == 0)
        return {{ci, ci + 1, ci + 1}, {cj, cj, cj + 1}};
    return {{ci, ci + 1, ci}, {cj, cj + 1, cj + 1}};
}

Point3 sample_point(const IndexGrid& hf, int i, int j) { return {hf.x_of(i), hf.y_of(j), hf.at(i, j)}; }

// Readable property maps (boost concept) from a face number to its triangle / a vertex.
struct TriangleMap {
    using key_type = FaceId;
    using value_type = Triangle3;
    using reference = Triangle3;
    using category = boost::readable_property_map_tag;
    const IndexGrid* hf = nullptr;
    friend Triangle3 get(const TriangleMap& m, FaceId f)
    {
        const FaceCorners c = corners(*m.hf, f);
        return {sample_point(*m.hf, c.i[0], c.j[0]), sample_point(*m.hf, c.i[1], c.j[1]),
                sample_point(*m.hf, c.i[2], c.j[2])};
    }
};

struct PointMap {
    using key_type = FaceId;
    using value_type = Point3;
    using reference = Point3;
    using category = boost::readable_property_map_tag;
    const IndexGrid* hf = nullptr;
    friend Point3 get(const PointMap& m, FaceId f)
    {
        const FaceCorners c = corners(*m.hf, f);
        return sample_point(*m.hf, c.i[0], c.j[0]);
    }
};

// Tag_true: the maps live once in the tree, not in every primitive; Tag_false: no datum cache.
using Primitive = CGAL::AABB_primitive<FaceId, TriangleMap, PointMap, CGAL::Tag_true, CGAL::Tag_false>;
using AabbTraits = CGAL::AABB_traits<K, Primitive>;
using Tree = CGAL::AABB_tree<AabbTraits>;

glm::dvec3 to_glm(const Point3& p) { return {p.x(), p.y(), p.z()}; }

bool finite_point(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

// Impl holds types of the anonymous namespace above, and is defined in this file alone. GCC
// warns of that only outside a translation unit's main file: in a unity batch.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wsubobject-linkage"
#endif
struct Terrain::Index::Impl {
    IndexGrid hf;
    std::size_t face_count = 0;

    std::once_flag mesh_once, tree_once;
    TriMesh mesh;
    Tree tree;

    explicit Impl(const Heightfield& h) : hf{h.nx, h.ny, h.dx, h.dy, h.x0, h.y0, h.z.data()}
    {
        if (hf.nx >= 2 && hf.ny >= 2)
            face_count = 2 * std::size_t(hf.nx - 1) * std::size_t(hf.ny - 1);
        if (face_count > std::numeric_limits<FaceId>::max())
            throw LimitError("", "terrain", "more than 2^32 triangles");
    }

    // Unit upward normal of face f, from the heightfield (same formula as Terrain::normal()).
    glm::dvec3 face_normal(FaceId f) const
    {
        const FaceCorners c = corners(hf, f);
        const glm::dvec3 a = to_glm(sample_point(hf, c.i[0], c.j[0]));
        const glm::dvec3 b = to_glm(sample_point(hf, c.i[1], c.j[1]));
        const glm::dvec3 d = to_glm(sample_point(hf, c.i[2], c.j[2]));
        glm::dvec3 n = glm::cross(b - a, d - a);
        if (n.z < 0.0)
            n = -n;
        return glm::normalize(n);
    }

    void build_mesh()
    {
        const int nx = hf.nx, ny = hf.ny;
        const std::size_t nv = hf.size();
        const std::size_t cells = nx >= 2 && ny >= 2 ? std::size_t(nx - 1) * (ny - 1) : 0;
        const std::size_t ne = nv == 0 ? 0 : std::size_t(nx - 1) * ny + std::size_t(nx) * (ny - 1) + cells;
        mesh.reserve(nv, ne, 2 * cells);
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i)
                mesh.add_vertex(TriMesh::Point(hf.x_of(i), hf.y_of(j), hf.at(i, j)));
        const auto vh = [nx](int i, int j) { return TriMesh::VertexHandle(j * nx + i); };
        // Same face order as FaceId, so face handle idx() == FaceId.
        for (int j = 0; j + 1 < ny; ++j)
            for (int i = 0; i + 1 < nx; ++i) {
                mesh.add_face(vh(i, j), vh(i + 1, j), vh(i + 1, j + 1));
                mesh.add_face(vh(i, j), vh(i + 1, j + 1), vh(i, j + 1));
            }
        mesh.request_face_normals();
        mesh.request_vertex_normals();
        mesh.update_normals();
    }

    void build_tree()
    {
        if (face_count == 0)
            return;
        tree.rebuild(boost::counting_iterator<FaceId>(0), boost::counting_iterator<FaceId>(FaceId(face_count)),
                     TriangleMap{&hf}, PointMap{&hf});
        // Closest-point queries start from the point of the surface straight below/above the
        // query (a good bound), so the KD-tree of reference points is not worth its memory.
        tree.do_not_accelerate_distance_queries();
    }

    const Tree& aabb()
    {
        std::call_once(tree_once, [this] { build_tree(); });
        return tree;
    }
};
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

Terrain::Index::Index(const Heightfield& hf) : impl(std::make_unique<Impl>(hf)) {}
Terrain::Index::~Index() = default;

const TriMesh& Terrain::Index::mesh() const
{
    std::call_once(impl->mesh_once, [this] { impl->build_mesh(); });
    return impl->mesh;
}

std::optional<RayHit> Terrain::Index::intersect_ray(const glm::dvec3& origin, const glm::dvec3& dir) const
{
    // A zero or non-finite direction has no hit rather than a NaN one.
    const double len = glm::length(dir);
    if (!finite_point(origin) || !std::isfinite(len) || len == 0.0)
        return std::nullopt;
    const glm::dvec3 d = dir / len;
    const Tree& tree = impl->aabb();
    if (tree.empty())
        return std::nullopt;
    const K::Ray_3 ray(Point3(origin.x, origin.y, origin.z), K::Vector_3(d.x, d.y, d.z));
    const auto hit = tree.first_intersection(ray);
    if (!hit)
        return std::nullopt;
    glm::dvec3 p;
    if (const Point3* point = boost::get<Point3>(&hit->first)) {
        p = to_glm(*point);
    } else {
        // The ray runs inside the triangle's plane: the first point is the nearer end.
        const K::Segment_3& s = boost::get<K::Segment_3>(hit->first);
        const glm::dvec3 a = to_glm(s.source()), b = to_glm(s.target());
        p = glm::dot(a - origin, d) <= glm::dot(b - origin, d) ? a : b;
    }
    RayHit result;
    result.t = std::max(0.0, glm::dot(p - origin, d));
    result.point = p;
    result.normal = impl->face_normal(hit->second);
    return result;
}

glm::dvec3 Terrain::Index::closest_point(const glm::dvec3& p) const
{
    if (!finite_point(p))
        throw InputError("", "closest_point", "query point is not finite");
    const IndexGrid& hf = impl->hf;
    if (hf.size() == 0)
        throw InputError("", "closest_point", "empty terrain");
    const Tree& tree = impl->aabb();
    if (tree.empty()) {
        // A single row or column of samples has no triangles: nearest sample.
        glm::dvec3 best = to_glm(sample_point(hf, 0, 0));
        for (int j = 0; j < hf.ny; ++j)
            for (int i = 0; i < hf.nx; ++i)
                if (const glm::dvec3 q = to_glm(sample_point(hf, i, j)); glm::distance(q, p) < glm::distance(best, p))
                    best = q;
        return best;
    }
    // Hint: the grid sample nearest to p in plan, a point of the mesh close to the answer.
    const int i = int(std::lround(std::clamp((p.x - hf.x0) / hf.dx, 0.0, double(hf.nx - 1))));
    const int j = int(std::lround(std::clamp((p.y - hf.y0) / hf.dy, 0.0, double(hf.ny - 1))));
    return to_glm(tree.closest_point(Point3(p.x, p.y, p.z), sample_point(hf, i, j)));
}

}  // namespace kiri::geometry
