#pragma once
//! \file scattered_points.hpp
//! Terrain from scattered elevation points (survey, LiDAR ground points) through a 2D
//! Delaunay triangulation (CGAL, Projection_traits_xy_3), resampled onto a heightfield.
#include <filesystem>
#include <vector>

#include <glm/vec3.hpp>

#include "kiri/geometry/heightfield.hpp"

namespace kiri::geometry {

//! Reads "x y z" rows (metres; '#' comments allowed).
//! \throw InputError naming the file and line.
std::vector<glm::dvec3> read_xyz_points(const std::filesystem::path& path);

//! Linear interpolation on the Delaunay triangulation of the points, sampled every
//! cell_size metres over their bounding box. Samples outside the convex hull are marked
//! invalid and filled from the nearest valid sample.
Heightfield heightfield_from_points(const std::vector<glm::dvec3>& points, double cell_size);

}  // namespace kiri::geometry
