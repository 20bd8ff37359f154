#pragma once
//! \file dem.hpp
//! Loading elevation rasters (GeoTIFF, ESRI ASCII grid, SRTM .hgt, 8/16-bit PNG) through GDAL.
//!
//! Frame. Samples sit at pixel centres; the local origin (0, 0) is the centre of the data; rows
//! are reordered so that j = 0 is the south edge (north-up and south-up rasters alike) and
//! i = 0 the west edge. Rotated or sheared geotransforms are refused.
//!
//! Units. Projected rasters keep their coordinates, scaled by the CRS linear unit to metres.
//! Rasters without a CRS are taken to be in metres. Geographic rasters (degrees) are converted
//! once, with the local scale of the WGS84 ellipsoid at the centre latitude phi0:
//! metres per degree north = M(phi0) pi/180, east = N(phi0) cos(phi0) pi/180 (M, N the
//! meridional and prime-vertical radii). The grid stays regular, so the east-west scale is
//! exact only on the centre parallel: at a latitude phi0 + dphi it is off by a relative
//! ~tan(phi0) dphi (dphi in radians), i.e. 0.19 % (~28 m at the corners, 15 km east of the
//! centre) for the 0.29 degree tall Jacksboro DEM at 36.6 N, 1 % at the edges of a 1.1 degree
//! tile at 45 N. North-south distances are off by ~3 e^2 sin(2 phi0) dphi / 4 (< 0.01 % there).
//! Heights: z = vertical_offset + vertical_scale * (band offset + band scale * value), times
//! 0.3048 where the band's unit (or else the vertical CRS's) is feet, times the exaggeration.
//!
//! Nodata. Cells equal to the band's nodata value, NaN or Inf are marked valid = 0. So are the
//! fill values real exports leave undeclared (-3.4e38 and the other float limits, -32768,
//! -32767, -9999) and, in georeferenced rasters, heights outside -12 km..+9 km (no place on
//! Earth): these are counted in a one-line warning. Voids are filled by a smooth membrane over the valid cells (nodata_fill.hpp),
//! so heights stay finite with no spike or wall; a raster with no valid cell is refused, and one
//! whose heights are mostly outside that range is refused naming the vertical scale.
//!
//! Rasters without a CRS are metres, unless their geotransform is plainly degrees (cells under
//! 0.1 and the extent inside [-180, 180] x [-90, 90]): those are read as WGS 84 longitude and
//! latitude, with a warning.
//!
//! Errors. GDAL's own printing is silenced; its message goes into the exception.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "kiri/geometry/terrain/heightfield.hpp"

namespace kiri::geometry {

struct DemOptions {
    //! Cell size in metres for rasters without georeferencing (PNG heightmaps); 0 = required
    //! from the file (a PNG without it is refused).
    double cell_size = 0.0;
    //! Metres per raster unit and offset: z = offset + scale * value (PNG heightmaps; applied
    //! to every format, on top of the band's own scale/offset, so 1 and 0 leave others as is).
    double vertical_scale = 1.0;
    double vertical_offset = 0.0;
    //! Multiplies every height after the above (the scene's vertical exaggeration); the range of
    //! plausible elevations is checked before it.
    double exaggeration = 1.0;
    //! Refused above this many cells, before allocating (LimitError states the memory the
    //! load would need, ~17 bytes a cell while loading). The default, 2^26 cells, is 1.1 GiB
    //! while loading, and the terrain mesh + AABB tree of such a grid take several GiB more.
    std::size_t max_cells = std::size_t(1) << 26;  // 67,108,864 = 8192^2
};

//! Summary of a raster, as `kiri info` prints it.
struct DemInfo {
    std::string driver;                         //!< GDAL driver short name, e.g. "GTiff"
    int width = 0, height = 0;                  //!< cells along x (columns) and y (rows)
    double cell_dx_m = 0.0, cell_dy_m = 0.0;    //!< cell size in metres
    double extent_x_m = 0.0, extent_y_m = 0.0;  //!< width * cell_dx_m, height * cell_dy_m
    double z_min = 0.0, z_max = 0.0;            //!< elevation range of the valid cells (metres)
    std::size_t nodata_count = 0;               //!< cells that are nodata, NaN or Inf
    bool geographic = false;                    //!< source cells are degrees
    std::string crs_name;                       //!< empty when the raster has no CRS
    double centre_x = 0.0, centre_y = 0.0;      //!< data centre in the source CRS (lon/lat or E/N)
    std::vector<std::string> warnings;          //!< as Heightfield::warnings
};

//! Loads a raster into local metres. Nodata cells and NaN/Inf are masked (valid = 0) and
//! filled from their nearest valid neighbours so heights stay finite.
//! \throw InputError naming the file and the raster property (missing file, not a raster,
//!        zero size, all nodata); LimitError above options.max_cells.
Heightfield load_dem(const std::filesystem::path& path, const DemOptions& options = {});

//! Reads the header and statistics of a raster without building a terrain (same checks and
//! errors as load_dem, except that 1-cell-wide rasters are described rather than refused).
DemInfo dem_info(const std::filesystem::path& path, const DemOptions& options = {});

//! Resamples a heightfield to nx x ny samples over the same extent (bilinear). Used by
//! benchmarks that grow a real DEM. A sample is valid when its nearest source sample is.
//! \throw InputError below 2 x 2 samples; LimitError above DemOptions{}.max_cells.
Heightfield resample(const Heightfield& source, int nx, int ny);

}  // namespace kiri::geometry
