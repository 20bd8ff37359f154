#include "author_maps.hpp"

#include "kiri/geometry/placement/fog_maps.hpp"
#include "kiri/geometry/scene/author_report.hpp"

namespace kiri::cli {

using namespace kiri::geometry;

std::vector<MapFile> placement_maps(const Scene& scene, const Terrain& terrain, const PlacedFog* placed)
{
    std::vector<MapFile> maps;
    if (!placed)
        return maps;
    // Captured by reference: the scene, terrain and fog outlive the writes.
    const PlacedFog& p = *placed;
    const Heightfield& hf = terrain.heightfield();
    const double to_dem = 1.0 / scene.terrain.exaggeration;
    const auto meta = optics_metadata(scene.medium);
    maps.push_back({"fog_top.tif", [&p, &hf, to_dem, meta](const std::filesystem::path& f) {
                        write_geotiff_map(f, hf, p.columns.top, p.columns.mask, to_dem, "fog top altitude (m)", meta);
                    }});
    maps.push_back({"fog_bottom.tif", [&p, &hf, to_dem, meta](const std::filesystem::path& f) {
                        write_geotiff_map(f, hf, p.columns.bottom, p.columns.mask, to_dem, "fog bottom altitude (m)",
                                          meta);
                    }});
    maps.push_back({"fog_thickness.tif", [&p, &hf, to_dem, meta](const std::filesystem::path& f) {
                        std::vector<double> t(hf.size());
                        for (std::size_t k = 0; k < t.size(); ++k)
                            t[k] = p.columns.thickness(k);
                        write_geotiff_map(f, hf, t, hf.valid, to_dem, "fog thickness (m)", meta);
                    }});
    maps.push_back(
        {"fog_mask.png", [&p, &hf](const std::filesystem::path& f) { write_mask_png(f, hf, p.columns.mask); }});
    if (p.flood)
        maps.push_back({"flood_level.tif", [&p, &hf, to_dem](const std::filesystem::path& f) {
                            write_geotiff_map(f, hf, p.flood->level, p.flood->reached, to_dem,
                                              "lowest fog top reaching the cell from the seeds (m)");
                        }});
    if (p.valleys) {
        maps.push_back(
            {"valleys.png", [&p, &hf](const std::filesystem::path& f) { write_mask_png(f, hf, p.valleys->mask); }});
        maps.push_back({"valley_index.tif", [&p, &hf](const std::filesystem::path& f) {
                            write_geotiff_map(f, hf, p.valleys->index, hf.valid, 1.0, "cold-air-pool index (sd)");
                        }});
    }
    return maps;
}

}  // namespace kiri::cli
