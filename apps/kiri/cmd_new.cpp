// `kiri new DEM -o scene.json`: the scene kiri derives for a DEM, every key spelled out, as a
// starter to edit. Only the terrain is loaded: the derived keys need nothing of the fog's stages.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <system_error>

#include "commands.hpp"
#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/scene/dem_scene.hpp"
#include "kiri/geometry/scene/pipeline.hpp"

namespace kiri::cli {
namespace {

namespace fs = std::filesystem;

struct NewArgs {
    std::string dem, out;
    bool force = false;
};

void run(const NewArgs& a)
{
    check_output_file(a.out);
    if (!a.force && fs::exists(a.out))
        throw IoError(a.out, "", "exists already (--force replaces it)");
    if (geometry::is_scene_path(a.dem))
        throw InputError(a.dem, "", "is a scene: kiri new starts from a DEM (GeoTIFF, .asc, .hgt, ENVI, PNG, ...)");
    geometry::Pipeline pipeline;
    const geometry::PipelineProducts& products = pipeline.run(geometry::dem_scene(a.dem), {geometry::Stage::terrain});
    const std::string text = geometry::starter_scene_json(*products.scene, a.out);
    // Written beside, then renamed: no half-written scene.
    const fs::path tmp = fs::path(a.out).concat(".kiri-new.tmp");
    std::error_code ec;
    {
        std::ofstream out(tmp, std::ios::binary);
        out << text;
        out.close();
        if (!out) {
            fs::remove(tmp, ec);
            throw IoError(a.out, "", "cannot write");
        }
    }
    fs::rename(tmp, a.out, ec);
    if (ec) {
        fs::remove(tmp, ec);
        throw IoError(a.out, "", "cannot move into place");
    }
    std::printf("%s\n", a.out.c_str());
    print_derived(*products.derived, products.terrain->heightfield());
}

}  // namespace

void add_new_command(CLI::App& app)
{
    auto* sub = app.add_subcommand(
        "new", "Write the scene kiri derives for a DEM (a valley fog; every key spelled out) as a starter to edit");
    auto a = std::make_shared<NewArgs>();
    sub->add_option("dem", a->dem, "elevation raster (GeoTIFF, ESRI ASCII, SRTM .hgt, ENVI, PNG, ...)")->required();
    sub->add_option("-o,--out", a->out, "scene file to write (JSON)")->required();
    sub->add_flag("--force", a->force, "replace an existing file");
    sub->callback([a] { run(*a); });
}

}  // namespace kiri::cli
