#pragma once
//! \file dem.hpp
//! Loading elevation rasters (GeoTIFF, ESRI ASCII grid, SRTM .hgt, 8/16-bit PNG) through GDAL.
#include <cstddef>
#include <filesystem>
#include <string>

#include "kiri/geometry/heightfield.hpp"

namespace kiri::geometry {

struct DemOptions {
    //! Cell size in metres for rasters without georeferencing (PNG heightmaps); 0 = required
    //! from the file (a PNG without it is refused).
    double cell_size = 0.0;
    //! Metres per raster unit and offset: z = offset + scale * value (PNG heightmaps).
    double vertical_scale = 1.0;
    double vertical_offset = 0.0;
    //! Refused above this many cells, before allocating (documented limit).
    std::size_t max_cells = std::size_t(1) << 26;  // 67,108,864 = 8192^2
};

//! Summary of a raster, as `kiri info` prints it.
struct DemInfo {
    std::string driver;
    int width = 0, height = 0;
    double cell_dx_m = 0.0, cell_dy_m = 0.0;  //!< cell size in metres
    double extent_x_m = 0.0, extent_y_m = 0.0;
    double z_min = 0.0, z_max = 0.0;
    std::size_t nodata_count = 0;
    bool geographic = false;
    std::string crs_name;
};

//! Loads a raster into local metres. Nodata cells and NaN/Inf are masked (valid = 0) and
//! filled from their nearest valid neighbours so heights stay finite.
//! \throw InputError naming the file and the raster property (missing file, not a raster,
//!        zero size, all nodata); LimitError above options.max_cells.
Heightfield load_dem(const std::filesystem::path& path, const DemOptions& options = {});

//! Reads the header and statistics of a raster without building a terrain.
DemInfo dem_info(const std::filesystem::path& path, const DemOptions& options = {});

//! Resamples a heightfield to nx x ny samples over the same extent (bilinear). Used by
//! benchmarks that grow a real DEM.
Heightfield resample(const Heightfield& source, int nx, int ny);

}  // namespace kiri::geometry
