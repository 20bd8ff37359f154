#pragma once
//! \file point_files.hpp
//! Scattered elevation points from the files users bring: "x y z" text (read_xyz_points), CSV
//! with a header row naming its columns, and PLY vertices (ASCII or binary little-endian).
#include <filesystem>
#include <vector>

#include <glm/vec3.hpp>

namespace kiri::geometry {

//! The points of `path` by its extension: `.ply` read_ply_points; `.csv` read_csv_points;
//! `.xyz`, `.txt` read_xyz_points.
//! \throw InputError naming the file, the line or vertex, and the reason.
std::vector<glm::dvec3> read_points(const std::filesystem::path& path);

//! CSV: a header row naming the columns (any order, any case, quoted or not; other columns are
//! ignored) with `x`, `y` and `z` among them, then one row of numbers each; a file whose first
//! row holds only numbers has no header and is read as "x y z" rows (read_xyz_points).
//! \throw InputError: a header without x, y or z ("needs columns x, y, z; found a, b, c"), a row
//!        too short or with a value that is not a finite number (its line and column).
std::vector<glm::dvec3> read_csv_points(const std::filesystem::path& path);

//! PLY (format ascii 1.0 or binary_little_endian 1.0): the `vertex` element's x, y and z
//! (scalar properties of any PLY number type; other properties are skipped). The vertex element
//! must come first.
//! \throw InputError: not PLY, big-endian, a vertex element missing or not first, x, y or z
//!        missing or a list, an unknown type, a count the file cannot hold (before allocating),
//!        a truncated body, a value that is not finite.
std::vector<glm::dvec3> read_ply_points(const std::filesystem::path& path);

}  // namespace kiri::geometry
