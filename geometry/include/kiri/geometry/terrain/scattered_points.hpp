#pragma once
//! \file scattered_points.hpp
//! Terrain from scattered elevation points (survey, LiDAR ground points) through a 2D
//! Delaunay triangulation (CGAL, Projection_traits_xy_3), resampled onto a heightfield.
#include <filesystem>
#include <vector>

#include <glm/vec3.hpp>

#include "kiri/geometry/terrain/heightfield.hpp"

namespace kiri::geometry {

//! Reads "x y z" rows (metres; separated by blanks or commas; '#' starts a comment; blank
//! lines skipped). Exactly three finite numbers a row.
//! \throw InputError naming the file and line ("pts.xyz: line 7: ..."), or the file when it
//!        is missing or holds no point.
std::vector<glm::dvec3> read_xyz_points(const std::filesystem::path& path);

//! Linear interpolation on the Delaunay triangulation of the points, sampled every
//! cell_size metres over their bounding box. Samples outside the convex hull are marked
//! invalid and filled from the nearest valid sample.
//! Sample (i, j) is at input (xmin + i cell_size, ymin + j cell_size); as for DEMs the local
//! origin is the centre of the grid, whose input coordinates are georef.origin_x/y.
//! Points sharing x-y keep one of their heights.
//! \throw InputError for fewer than 3 points, non-finite values, collinear points or
//!        cell_size <= 0; LimitError above DemOptions{}.max_cells samples.
Heightfield heightfield_from_points(const std::vector<glm::dvec3>& points, double cell_size);

//! Whether path names a point file read by read_points (point_files.hpp: ".xyz", ".csv",
//! ".txt", ".ply", any case) rather than a raster.
bool is_point_file(const std::filesystem::path& path);

//! A grid spacing for the points: about one point a cell over their bounding box, to two
//! significant digits (the resolution the points carry). \pre at least 3 finite points.
double point_cell_size(const std::vector<glm::dvec3>& points);

}  // namespace kiri::geometry
