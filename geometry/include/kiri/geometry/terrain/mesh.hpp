#pragma once
//! \file mesh.hpp
//! OpenMesh types used across kiri, in double precision (traits with Vec3d points and normals).
//! OpenMesh wants MeshIO.hh included before the mesh kernel headers for read_mesh/write_mesh.
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

namespace kiri::geometry {

struct DoubleTraits : public OpenMesh::DefaultTraits {
    using Point = OpenMesh::Vec3d;
    using Normal = OpenMesh::Vec3d;
    using TexCoord2D = OpenMesh::Vec2d;
};

using TriMesh = OpenMesh::TriMesh_ArrayKernelT<DoubleTraits>;
using PolyMesh = OpenMesh::PolyMesh_ArrayKernelT<DoubleTraits>;

}  // namespace kiri::geometry
