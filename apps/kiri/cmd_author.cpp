// `kiri author SCENE.json -o DIR`: the fog base surface of a scene as OBJ and PLY, its layers,
// its medium as OpenVDB (medium.vdb) and DIR/report.json with the fit figures, counts and
// timings. Every file is written under a temporary name and renamed into place, so DIR never
// holds a half-written result.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <CLI/CLI.hpp>
#include <OpenMesh/Core/System/omstream.hh>

#include "author_maps.hpp"
#include "commands.hpp"
#include "kiri/geometry/scene/author_estimate.hpp"
#include "kiri/geometry/terrain/dem.hpp"
#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/scene/fog_spec.hpp"
#include "kiri/geometry/layers/layer_export.hpp"
#include "kiri/geometry/particles/particles.hpp"
#include "kiri/geometry/volume/medium_vdb.hpp"
#include "kiri/geometry/scene/author_report.hpp"
#include "kiri/geometry/scene/pipeline.hpp"
#include "kiri/geometry/scene/scene.hpp"
#include "kiri/geometry/terrain/terrain.hpp"

namespace kiri::cli {
namespace {
namespace fs = std::filesystem;
using namespace kiri::geometry;

void write_mesh_file(TriMesh mesh, const fs::path& tmp, bool with_patch_ids)
{
    // PLY carries the patch id per vertex as a custom int property; OBJ has no place for it.
    OpenMesh::IO::Options opt = OpenMesh::IO::Options::VertexNormal | OpenMesh::IO::Options::VertexTexCoord;
    if (with_patch_ids)
        opt += OpenMesh::IO::Options::Custom;
    omlog().disable();  // OpenMesh's writers chat on stderr
    if (!OpenMesh::IO::write_mesh(mesh, tmp.string(), opt, 10))
        throw IoError(tmp.string(), "", "cannot write the mesh");
}

void write_text(const std::string& text, const fs::path& tmp)
{
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    out.close();
    if (!out)
        throw IoError(tmp.string(), "", "cannot write");
}

int author(const fs::path& scene_path, const fs::path& out_dir)
{
    check_output_folder(out_dir.string());
    const Scene scene = load_scene(scene_path);
    if (!scene.fog)
        throw InputError(scene_path.string(), "/fog", "the scene has no fog section to author");
    Pipeline pipeline;
    const std::shared_ptr<const Terrain> loaded = pipeline.run(scene, {Stage::terrain}).terrain;
    const Terrain& terrain = *loaded;
    // The estimate comes before any large allocation; above the limit the pipeline refuses.
    const AuthorEstimate estimate = estimate_author(world_fog_spec(scene), terrain.heightfield(), scene.layers.count);
    check_author_estimate(estimate, scene_path.string());
    std::printf("kiri author: %s\n", estimate.summary().c_str());
    std::fflush(stdout);
    // The layers are view dependent: exported as the scene's first camera sees them. The
    // particles are the whole fog (the scene's "particles" section, docs/particles.md).
    const Bounds3 bounds = terrain.bounds();
    PipelineTarget target{Stage::exports, ParticleSet::whole, scene.camera("", bounds.min, bounds.max).position};
    const PipelineProducts& fog = pipeline.run(scene, target);
    const Tessellation& tessellation = *fog.tessellation;
    const std::vector<LayerMesh>& layers = *fog.exports;
    const ParticleCloud& particles = *fog.particles;

    std::error_code ec;
    fs::create_directories(out_dir, ec);
    if (ec)
        throw IoError(out_dir.string(), "", "cannot create the output folder: " + ec.message());
    const std::string stem = ".kiri-author.tmp.";
    std::vector<std::pair<fs::path, fs::path>> files = {{out_dir / (stem + "obj"), out_dir / "base_surface.obj"},
                                                        {out_dir / (stem + "ply"), out_dir / "base_surface.ply"},
                                                        {out_dir / (stem + "json"), out_dir / "report.json"},
                                                        {out_dir / (stem + "glb"), out_dir / "layers.glb"},
                                                        {out_dir / (stem + "layers.obj"), out_dir / "layers.obj"},
                                                        {out_dir / (stem + "layers.ply"), out_dir / "layers.ply"},
                                                        {out_dir / (stem + "particles.ply"), out_dir / "particles.ply"},
                                                        {out_dir / (stem + "vdb"), out_dir / "medium.vdb"}};
    const std::vector<MapFile> maps = placement_maps(scene, terrain, fog.placed.get());
    for (const MapFile& m : maps)
        files.push_back({out_dir / (stem + m.name), out_dir / m.name});
    VdbExportReport vdb;
    try {
        write_mesh_file(tessellation.mesh, files[0].first, false);
        write_mesh_file(tessellation.mesh, files[1].first, true);
        write_text(author_report_json(scene, fog, pipeline.stages()), files[2].first);
        write_layers_glb(files[3].first, *fog.layer_base, layers, fog.layers, &terrain.mesh());
        write_layers_obj(files[4].first, *fog.layer_base, layers);
        write_layers_ply(files[5].first, *fog.layer_base, layers, fog.layers);
        write_particles_ply(files[6].first.string(), particles);
        vdb = write_medium_vdb(*fog.medium, files[7].first);
        for (std::size_t m = 0; m < maps.size(); ++m)
            maps[m].write(files[8 + m].first);
        for (const auto& [tmp, final_path] : files) {
            fs::rename(tmp, final_path, ec);
            if (ec)
                throw IoError(final_path.string(), "", "cannot move into place: " + ec.message());
        }
    } catch (...) {
        for (const auto& [tmp, final_path] : files)
            fs::remove(tmp, ec);
        throw;
    }
    const FitReport& fit = fog.surface->fit;
    if (fog.placed) {
        const ColumnFigures& c = fog.placed->figures;
        const double e = scene.terrain.exaggeration;
        std::printf(
            "fog placed by the terrain: %.2f km^2, %.3g m^3, thickness up to %.0f m (mean %.0f m), top %.0f..%.0f m, "
            "%d polygon(s), %zu map(s)\n",
            c.area_m2 * 1e-6, c.volume_m3 / e, c.max_thickness / e, c.mean_thickness / e, c.top_min / e, c.top_max / e,
            fog.placed->outline.components, maps.size());
    }
    std::printf(
        "%s: %d patches, %zu triangles, max deviation %.2f m, rms %.2f m, min clearance %.2f m, "
        "%zu layers, %zu particles, medium %zu voxels of %.3g m -> %s\n",
        scene_path.filename().string().c_str(), fog.surface->patches, tessellation.mesh.n_faces(), fit.max_deviation,
        fit.rms_deviation, fit.min_clearance, layers.size(), particles.particles.size(), vdb.active_voxels,
        vdb.voxel_size, out_dir.string().c_str());
    return 0;
}
}  // namespace

//! Registers `kiri author`.
void add_author_command(CLI::App& app)
{
    auto* sub = app.add_subcommand("author",
                                   "Fit the scene's fog; write its base surface, layers (OBJ, PLY, glTF), "
                                   "particles (PLY), the medium (OpenVDB) and report.json");
    auto scene = std::make_shared<std::string>();
    auto out = std::make_shared<std::string>();
    sub->add_option("scene", *scene, "scene file (JSON) with a fog section")->required();
    sub->add_option("-o,--out", *out, "output folder")->required();
    // Errors propagate to main, which prints one line and exits with code 2.
    sub->callback([scene, out] { author(*scene, *out); });
}

}  // namespace kiri::cli
