#pragma once
// Quad control meshes for the surface tests, generated (no files).
#include <cmath>
#include <random>
#include <vector>

#include "kiri/geometry/terrain/mesh.hpp"

namespace kiri::test {

using geometry::PolyMesh;

//! nx x ny quads of size h, z = f(x, y).
template <class F>
PolyMesh grid_mesh(int nx, int ny, double h, F f)
{
    PolyMesh m;
    std::vector<PolyMesh::VertexHandle> v;
    for (int j = 0; j <= ny; ++j)
        for (int i = 0; i <= nx; ++i)
            v.push_back(m.add_vertex(PolyMesh::Point(i * h, j * h, f(i * h, j * h))));
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const int a = j * (nx + 1) + i;
            m.add_face(std::vector<PolyMesh::VertexHandle>{v[a], v[a + 1], v[a + nx + 2], v[a + nx + 1]});
        }
    return m;
}

//! Each n-gon -> n quads (face centroid, edge midpoints): valences are kept, new vertices
//! get valence 4 (edge midpoints inside), 3 on the boundary... and n (face centroids).
inline PolyMesh quad_split(const PolyMesh& in)
{
    PolyMesh m;
    std::vector<PolyMesh::VertexHandle> vv(in.n_vertices()), ev(in.n_edges());
    for (auto v : in.vertices())
        vv[v.idx()] = m.add_vertex(in.point(v));
    for (auto e : in.edges()) {
        const auto h = in.halfedge_handle(e, 0);
        ev[e.idx()] = m.add_vertex((in.point(in.from_vertex_handle(h)) + in.point(in.to_vertex_handle(h))) * 0.5);
    }
    for (auto f : in.faces()) {
        PolyMesh::Point c(0, 0, 0);
        std::vector<PolyMesh::HalfedgeHandle> hs;
        for (auto h : in.fh_range(f)) {
            hs.push_back(h);
            c += in.point(in.from_vertex_handle(h));
        }
        const auto cv = m.add_vertex(c / double(hs.size()));
        const std::size_t n = hs.size();
        for (std::size_t k = 0; k < n; ++k) {
            const auto h = hs[k], hp = hs[(k + n - 1) % n];
            m.add_face(std::vector<PolyMesh::VertexHandle>{
                vv[in.from_vertex_handle(h).idx()], ev[in.edge_handle(h).idx()], cv, ev[in.edge_handle(hp).idx()]});
        }
    }
    return m;
}

//! A fan of n triangles around a centre, split twice into quads: an interior vertex of
//! valence n surrounded by a full ring of patches, valence-3 interior vertices (the triangle
//! centroids), boundary vertices of valence 2 (none), 3.
inline PolyMesh fan_mesh(int n, double radius = 10.0)
{
    PolyMesh m;
    const auto c = m.add_vertex(PolyMesh::Point(0, 0, 0));
    std::vector<PolyMesh::VertexHandle> ring;
    for (int k = 0; k < n; ++k) {
        const double a = 2 * M_PI * k / n;
        ring.push_back(m.add_vertex(PolyMesh::Point(radius * std::cos(a), radius * std::sin(a), 0)));
    }
    for (int k = 0; k < n; ++k)
        m.add_face(c, ring[k], ring[(k + 1) % n]);
    return quad_split(quad_split(m));
}

//! Random bumps of amplitude `amp` on z (fixed seed).
inline void bump(PolyMesh& m, double amp, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> d(-amp, amp);
    for (auto v : m.vertices()) {
        auto p = m.point(v);
        p[2] += d(rng);
        m.set_point(v, p);
    }
}

}  // namespace kiri::test
