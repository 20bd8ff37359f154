// libFuzzer target: the DEM loader (GDAL and kiri's own checks, nodata fill, geodesy) on
// arbitrary bytes. The first byte picks the file name, so that GDAL's format detection by
// name (SRTM .hgt) and by content (GeoTIFF, ASCII grid, PNG) are both exercised.
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

#include "kiri/geometry/terrain/dem.hpp"
#include "kiri/geometry/core/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    if (size < 1)
        return 0;
    static const char* const names[] = {"dem.tif", "dem.asc", "dem.png", "N36W085.hgt"};
    static const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("kiri_dem_fuzz_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::filesystem::path path = dir / names[data[0] % 4];
    if (std::FILE* f = std::fopen(path.c_str(), "wb")) {
        std::fwrite(data + 1, 1, size - 1, f);
        std::fclose(f);
    }
    kiri::geometry::DemOptions options;
    options.cell_size = 10.0;                  // PNG heightmaps need one
    options.max_cells = std::size_t(1) << 22;  // the fuzzer's memory limit is small
    try {
        const kiri::geometry::Heightfield hf = kiri::geometry::load_dem(path, options);
        for (double z : hf.z)
            if (!std::isfinite(z))
                __builtin_trap();  // the loader promises finite heights
    } catch (const kiri::InputError&) {}
    return 0;
}
