#pragma once
//! \file fog_maps.hpp
//! 2D products on the terrain's grid for GIS and engine pipelines: float GeoTIFFs
//! with the input DEM's georeferencing (GDAL), and 8-bit masks a user can look at and edit.
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "kiri/geometry/terrain/heightfield.hpp"

namespace kiri::geometry {

//! The value GeoTIFF maps carry where they have none (declared as the band's nodata).
inline constexpr double kMapNodata = -9999.0;

//! Writes one float32 band of grid.nx x grid.ny values (heightfield order, j = 0 south) as a
//! GeoTIFF (DEFLATE) in the source raster's CRS, row order and geotransform (Heightfield::georef;
//! a resampled grid gets the pixel size that spans the same extent; a grid without georeference
//! gets a local-metres transform and no CRS). value * scale is written where `defined` is
//! nonzero (empty = everywhere), kMapNodata elsewhere. `description` names the band. The same
//! input gives the same bytes. \throw IoError when GDAL cannot write the file.
//! `metadata` goes into the file's GDAL metadata (name, value), e.g. the fog's optics.
void write_geotiff_map(const std::filesystem::path& path, const Heightfield& grid, const std::vector<double>& values,
                       const std::vector<std::uint8_t>& defined, double scale, const std::string& description,
                       const std::vector<std::pair<std::string, std::string>>& metadata = {});

//! Writes a mask as an 8-bit grey PNG, north up (row 0 is the grid's northern row): 255 where
//! nonzero, 0 elsewhere. \throw IoError.
void write_mask_png(const std::filesystem::path& path, const Heightfield& grid, const std::vector<std::uint8_t>& mask);

//! Reads a mask raster (PNG, GeoTIFF, anything GDAL reads; band 1, nonzero = set) of exactly
//! the grid's size. Rasters without a geotransform are taken north up, like write_mask_png's;
//! georeferenced ones follow their transform's row and column order.
//! \throw InputError(file, field, reason) for a missing or unreadable file or a size mismatch.
std::vector<std::uint8_t> read_mask(const std::filesystem::path& path, const Heightfield& grid,
                                    const std::string& label, const std::string& field);

}  // namespace kiri::geometry
