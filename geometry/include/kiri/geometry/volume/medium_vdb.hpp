#pragma once
//! \file medium_vdb.hpp
//! The Medium as an OpenVDB file that DCC tools (Houdini, Blender, ...) open: one float grid
//! "density" of class fog volume holding the extinction sigma_t in 1/m, in world metres (x east,
//! y north, z up, the scene's local frame). OpenVDB's convention places voxel (i, j, k)'s value
//! at the grid's transform of (i, j, k), here (i v, j v, k v) for the voxel size v, and its
//! samplers interpolate trilinearly between those centres; each voxel holds the mean of
//! Medium::extinction over its cell (2 x 2 x 2 samples, 2 x 2 x 8 where the shell's floor or
//! top crosses it). Voxels centred below the Medium's floor (the ground) hold no fog: what their
//! cells held above the floor moves to the voxel above, so every column keeps its optical depth.
//! Metadata: the medium's extinction at density 1, albedo, anisotropy and the units. In a
//! renderer whose scene unit is the metre, the grid's values are the extinction coefficient as
//! they stand (Blender's Principled Volume "Density", Houdini's density with a scale of 1).
//! Blender 3.4's Cycles reads voxel (i, j, k) at the transform of (i + 1/2, j + 1/2, k + 1/2):
//! move the volume object by -v/2 on every axis there (docs/references.md, library facts).
#include <cstddef>
#include <filesystem>

#include "kiri/geometry/medium/medium.hpp"

namespace kiri::geometry {

struct VdbExportOptions {
    double voxel_size = 0.0;           //!< metres; 0: from the medium (at most about max_voxels)
    long long max_voxels = 8'000'000;  //!< refuse grids above this many active voxels (estimate)
};

struct VdbExportReport {
    double voxel_size = 0.0;
    std::size_t active_voxels = 0;
    double seconds = 0.0;
};

//! The voxel size the export picks: the medium's grid spacing, or finer (an eighth of the
//! mean thickness of the fog), or coarser where the shell would hold more than max_voxels.
double vdb_voxel_size(const Medium& medium, const VdbExportOptions& options = {});

//! Writes `path` (an OpenVDB .vdb file). \throw LimitError when the grid would exceed
//! max_voxels, IoError when the file cannot be written.
VdbExportReport write_medium_vdb(const Medium& medium, const std::filesystem::path& path,
                                 const VdbExportOptions& options = {});

}  // namespace kiri::geometry
