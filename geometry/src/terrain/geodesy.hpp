#pragma once
// Internal: the local metric scale of the WGS84 ellipsoid, used to turn a geographic raster
// (degrees) into local metres once, at loading.
#include <cmath>

namespace kiri::geometry {

struct LocalScale {
    double east = 0.0;   // metres per degree of longitude
    double north = 0.0;  // metres per degree of latitude
};

// Metres per degree at geodetic latitude lat_deg on WGS84 (a = 6378137 m,
// 1/f = 298.257223563): north = M pi/180 with the meridional radius
// M = a (1 - e^2) / (1 - e^2 sin^2 lat)^(3/2), east = N cos(lat) pi/180 with the prime
// vertical radius N = a / sqrt(1 - e^2 sin^2 lat).
inline LocalScale wgs84_metres_per_degree(double lat_deg)
{
    constexpr double a = 6378137.0, f = 1.0 / 298.257223563, e2 = f * (2.0 - f);
    const double phi = lat_deg * M_PI / 180.0, s = std::sin(phi);
    const double w = 1.0 - e2 * s * s;
    const double m = a * (1.0 - e2) / (w * std::sqrt(w)), n = a / std::sqrt(w);
    return {n * std::cos(phi) * M_PI / 180.0, m * M_PI / 180.0};
}

}  // namespace kiri::geometry
