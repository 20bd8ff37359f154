// `kiri info FILE`: what a raster holds, in the units kiri will use (metres).
#include <cstdio>
#include <memory>
#include <string>

#include "commands.hpp"
#include "kiri/geometry/terrain/dem.hpp"

namespace kiri::cli {

void add_info_command(CLI::App& app)
{
    auto* sub =
        app.add_subcommand("info", "Print grid size, cell size, extent, elevation range and nodata count of a DEM");
    auto file = std::make_shared<std::string>();
    auto cell = std::make_shared<double>(0.0);
    sub->add_option("file", *file, "elevation raster (GeoTIFF, ESRI ASCII, SRTM .hgt, PNG)")->required();
    sub->add_option("--cell-size", *cell, "metres per cell, for rasters without georeferencing (PNG)");
    sub->callback([file, cell] {
        geometry::DemOptions options;
        options.cell_size = *cell;
        const geometry::DemInfo i = geometry::dem_info(*file, options);
        std::printf("file:       %s (%s)\n", file->c_str(), i.driver.c_str());
        std::printf("grid:       %d x %d cells\n", i.width, i.height);
        std::printf("cell size:  %.3f m x %.3f m%s\n", i.cell_dx_m, i.cell_dy_m,
                    i.geographic ? " (geographic degrees converted at the data centre)" : "");
        std::printf("extent:     %.1f m x %.1f m\n", i.extent_x_m, i.extent_y_m);
        std::printf("elevation:  %.2f .. %.2f m\n", i.z_min, i.z_max);
        std::printf("nodata:     %zu cells\n", i.nodata_count);
        std::printf("crs:        %s\n", i.crs_name.empty() ? "(none)" : i.crs_name.c_str());
        std::printf("centre:     %.7f, %.7f (source CRS)\n", i.centre_x, i.centre_y);
        for (const std::string& w : i.warnings)
            std::fprintf(stderr, "kiri: warning: %s\n", w.c_str());
    });
}

}  // namespace kiri::cli
