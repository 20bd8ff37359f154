#pragma once
// Synthetic terrains for tests: an n x n ESRI ASCII grid, 20 m cells, its heights a function of
// (x, y) in metres from its south-west corner; a scene over one.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>

namespace kiri::test {

inline void write_dem(const std::filesystem::path& file, int n, const std::function<double(double, double)>& height)
{
    std::ofstream dem(file);
    dem << "ncols " << n << "\nnrows " << n << "\nxllcorner 0\nyllcorner 0\ncellsize 20\nNODATA_value -9999\n";
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c)
            dem << height(20.0 * c, 20.0 * (n - 1 - r)) << (c + 1 < n ? " " : "\n");
}

//! A fog lake of 10 m visibility (0.39 per metre) 150 m deep in a bowl 4 km wide, its camera "far"
//! 20 degrees down from 3.5 km, the sun 21 degrees up: `dir`/dense.json (and bowl.asc), returned.
inline std::filesystem::path write_dense_bowl_lake(const std::filesystem::path& dir)
{
    write_dem(dir / "bowl.asc", 201, [](double x, double y) {
        const double u = x / 2000.0 - 1.0, v = y / 2000.0 - 1.0;
        return 300.0 * (u * u + v * v) + 10.0 * std::sin(x / 310.0) * std::cos(y / 270.0);
    });
    std::ofstream scene(dir / "dense.json");
    scene << R"({"terrain": {"path": "bowl.asc"},
  "cameras": [{"name": "far", "position": [-2300, -2300, 1100], "target": [0, 0, 100], "fov": 40}],
  "sun": {"direction": [-0.75, 0.35, 0.32], "intensity": 3.2, "ambient": [0.22, 0.28, 0.38]},
  "fog": {"footprint": {"type": "terrain", "margin": 0}, "patch_size": 1000, "mode": "lake", "altitude": 150,
          "thickness": 150},
  "layers": {"count": 15},
  "medium": {"visibility": 10, "top_density": 0.5}})";
    return dir / "dense.json";
}

}  // namespace kiri::test
