#pragma once
//! \file heightfield.hpp
//! A regular grid of elevations in local metres: the terrain as loaded.
#include <cstdint>
#include <string>
#include <vector>

namespace kiri::geometry {

//! Where the local frame sits on Earth, kept so that 2D products (fog maps) can be written
//! back with the input's georeferencing.
struct GeoReference {
    std::string crs_wkt;                           //!< source CRS as WKT; empty when the raster had none
    bool geographic = false;                       //!< source cells were degrees (converted to metres at load)
    double origin_x = 0.0;                         //!< source-CRS coordinate of local (0,0): lon or easting
    double origin_y = 0.0;                         //!< source-CRS coordinate of local (0,0): lat or northing
    double geotransform[6] = {0, 1, 0, 0, 0, -1};  //!< GDAL geotransform of the source raster
    int source_width = 0;                          //!< source raster size (pixels), before any flip
    int source_height = 0;
};

//! Elevation grid. Sample (i, j), 0 <= i < nx (east), 0 <= j < ny (north), lies at local
//! (x0 + i dx, y0 + j dy) and has height z[j * nx + i]; row j = 0 is the southernmost,
//! whatever the source's row order. World frame: local metres, x east, y north, z up,
//! origin near the centre of the data (DESIGN "world frame").
struct Heightfield {
    int nx = 0, ny = 0;               //!< samples along x (columns) and y (rows)
    double dx = 1.0, dy = 1.0;        //!< sample spacing in metres, both > 0
    double x0 = 0.0, y0 = 0.0;        //!< local position of sample (0, 0) (south-west)
    std::vector<double> z;            //!< nx * ny heights in metres; finite everywhere
    std::vector<std::uint8_t> valid;  //!< 1 where the source had data, 0 where nodata was filled
    GeoReference georef;
    //! What the loader guessed or repaired (undeclared fill values, degrees without a CRS), one
    //! line each ("FILE: field: what"), for the apps to print as warnings.
    std::vector<std::string> warnings;

    double at(int i, int j) const { return z[static_cast<std::size_t>(j) * nx + i]; }
    double x_of(int i) const { return x0 + i * dx; }
    double y_of(int j) const { return y0 + j * dy; }
    double x_max() const { return x0 + (nx - 1) * dx; }
    double y_max() const { return y0 + (ny - 1) * dy; }
    std::size_t size() const { return z.size(); }
};

}  // namespace kiri::geometry
