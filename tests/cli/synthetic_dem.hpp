#pragma once
// A synthetic terrain for a test: an n x n ESRI ASCII grid, 20 m cells, its heights a function of
// (x, y) in metres from its south-west corner.
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

}  // namespace kiri::test
