// `kiri author SCENE.json -o DIR`: the fog base surface of a scene as OBJ and PLY, its layers,
// its medium as OpenVDB (medium.vdb) and DIR/report.json with the fit figures, counts and
// timings. Every file is written under a temporary name and renamed into place, so DIR never
// holds a half-written result.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <string>

#include <CLI/CLI.hpp>
#include <OpenMesh/Core/System/omstream.hh>

#include "author_maps.hpp"
#include "author_outputs.hpp"
#include "commands.hpp"
#include "kiri/geometry/scene/author_estimate.hpp"
#include "kiri/geometry/terrain/dem.hpp"
#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/scene/fog_spec.hpp"
#include "kiri/geometry/layers/layer_export.hpp"
#include "kiri/geometry/particles/particles.hpp"
#include "kiri/geometry/volume/medium_vdb.hpp"
#include "kiri/geometry/scene/author_report.hpp"
#include "kiri/geometry/scene/dem_scene.hpp"
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

// The terrain the glTF carries for context, at most 1024 samples a side: the layers are the
// product, and a 3601 x 3601 DEM's own mesh would be most of the file and of the memory.
Terrain glb_terrain(const Heightfield& hf)
{
    constexpr int most = 1024;
    const int stride = std::max(1, (std::max(hf.nx, hf.ny) + most - 2) / (most - 1));
    Heightfield out;
    out.nx = (hf.nx - 1) / stride + 1;
    out.ny = (hf.ny - 1) / stride + 1;
    out.dx = hf.dx * stride;
    out.dy = hf.dy * stride;
    out.x0 = hf.x0;
    out.y0 = hf.y0;
    out.z.reserve(std::size_t(out.nx) * out.ny);
    for (int j = 0; j < out.ny; ++j)
        for (int i = 0; i < out.nx; ++i)
            out.z.push_back(hf.at(i * stride, j * stride));
    out.valid.assign(out.z.size(), 1);
    return Terrain(std::move(out));
}

struct AuthorArgs {
    std::string scene, out, camera, formats;
    double max_output_mib = default_output_limit_mib;
};

// A file to write: written under a temporary name, renamed into place with the others.
struct OutputFile {
    fs::path name;
    std::function<void(const fs::path& tmp)> write;
};

// Every file under a temporary name first, then each renamed into place: the folder never holds
// a half-written result, and a failure removes what it wrote.
void write_all(const std::vector<OutputFile>& files, const fs::path& out_dir)
{
    std::error_code ec;
    fs::create_directories(out_dir, ec);
    if (ec)
        throw IoError(out_dir.string(), "", "cannot create the output folder: " + ec.message());
    const auto tmp = [&](const OutputFile& f) { return out_dir / (".kiri-author.tmp." + f.name.string()); };
    try {
        for (const OutputFile& f : files)
            f.write(tmp(f));
        for (const OutputFile& f : files) {
            fs::rename(tmp(f), out_dir / f.name, ec);
            if (ec)
                throw IoError((out_dir / f.name).string(), "", "cannot move into place: " + ec.message());
        }
    } catch (...) {
        for (const OutputFile& f : files)
            fs::remove(tmp(f), ec);
        throw;
    }
}

int author(const AuthorArgs& args)
{
    const fs::path scene_path(args.scene), out_dir(args.out);
    const std::set<AuthorFormat> formats =
        args.formats.empty() ? default_author_formats() : parse_author_formats(args.formats);
    check_output_folder(out_dir.string());
    const Scene given = load_scene_or_dem(scene_path);
    if (!given.fog)
        throw InputError(scene_path.string(), "/fog", "the scene has no fog section to author");
    Pipeline pipeline;
    const PipelineProducts& first = pipeline.run(given, {Stage::terrain});
    const std::shared_ptr<const Terrain> loaded = first.terrain;
    // The scene as the pipeline completed it: the keys the file left out derived from the terrain.
    const std::shared_ptr<const Scene> completed = first.scene;
    const Scene& scene = *completed;
    const Terrain& terrain = *loaded;
    // The estimates come before any large allocation; above the limits the pipeline (memory)
    // or this command (files) refuses.
    const AuthorEstimate estimate = estimate_author(world_fog_spec(scene), terrain.heightfield(), scene.layers.count);
    check_author_estimate(estimate, scene_path.string());
    const OutputEstimate files_estimate =
        estimate_outputs(estimate, double(terrain.heightfield().size()), double(scene.particles.count), formats);
    check_output_estimate(files_estimate, args.max_output_mib, scene_path.string());
    std::printf("kiri author: memory %s; files %s\n", estimate.summary().c_str(), files_estimate.summary().c_str());
    std::fflush(stdout);
    // The layers are view dependent: exported as the camera sees them (the scene's first).
    const Bounds3 bounds = terrain.bounds();
    const bool layers_wanted =
        formats.count(AuthorFormat::glb) || formats.count(AuthorFormat::obj) || formats.count(AuthorFormat::ply);
    const bool particles_wanted = formats.count(AuthorFormat::particles) > 0;
    PipelineTarget target;
    target.up_to = layers_wanted ? Stage::exports : particles_wanted ? Stage::particles : Stage::medium;
    target.light = false;  // no export holds the baked light
    target.particles = particles_wanted ? ParticleSet::whole : ParticleSet::none;
    target.export_eye = scene.camera(args.camera, bounds.min, bounds.max).position;
    const PipelineProducts& fog = pipeline.run(given, target);
    const Tessellation& tessellation = *fog.tessellation;

    std::vector<OutputFile> files = {
        {"report.json", [&](const fs::path& f) { write_text(author_report_json(scene, fog, pipeline.stages()), f); }}};
    VdbExportReport vdb;
    if (formats.count(AuthorFormat::surface)) {
        files.push_back({"base_surface.obj", [&](const fs::path& f) { write_mesh_file(tessellation.mesh, f, false); }});
        files.push_back({"base_surface.ply", [&](const fs::path& f) { write_mesh_file(tessellation.mesh, f, true); }});
    }
    if (formats.count(AuthorFormat::glb))
        files.push_back({"layers.glb", [&](const fs::path& f) {
                             const Terrain context = glb_terrain(terrain.heightfield());
                             write_layers_glb(f, *fog.layer_base, *fog.exports, fog.layers, &context.mesh());
                         }});
    if (formats.count(AuthorFormat::obj))
        files.push_back({"layers.obj", [&](const fs::path& f) { write_layers_obj(f, *fog.layer_base, *fog.exports); }});
    if (formats.count(AuthorFormat::ply))
        files.push_back(
            {"layers.ply", [&](const fs::path& f) { write_layers_ply(f, *fog.layer_base, *fog.exports, fog.layers); }});
    if (particles_wanted)
        files.push_back({"particles.ply", [&](const fs::path& f) { write_particles_ply(f.string(), *fog.particles); }});
    if (formats.count(AuthorFormat::vdb))
        files.push_back({"medium.vdb", [&](const fs::path& f) { vdb = write_medium_vdb(*fog.medium, f); }});
    std::vector<MapFile> maps;
    if (formats.count(AuthorFormat::maps))
        maps = placement_maps(scene, terrain, fog.placed.get());
    for (const MapFile& m : maps)
        files.push_back({m.name, m.write});
    write_all(files, out_dir);

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
    std::printf("%s: %d patches, %zu triangles, max deviation %.2f m, rms %.2f m, min clearance %.2f m",
                scene_path.filename().string().c_str(), fog.surface->patches, tessellation.mesh.n_faces(),
                fit.max_deviation, fit.rms_deviation, fit.min_clearance);
    if (fog.exports)
        std::printf(", %zu layers", fog.exports->size());
    if (fog.particles)
        std::printf(", %zu particles", fog.particles->particles.size());
    if (vdb.active_voxels > 0)
        std::printf(", medium %zu voxels of %.3g m", vdb.active_voxels, vdb.voxel_size);
    std::printf(" -> %s\n", out_dir.string().c_str());
    print_derived(*fog.derived, terrain.heightfield());
    return 0;
}
}  // namespace

void run_author(const std::string& input, const std::string& out_dir)
{
    AuthorArgs args;
    args.scene = input;
    args.out = out_dir;
    author(args);
}

//! Registers `kiri author`.
void add_author_command(CLI::App& app)
{
    auto* sub =
        app.add_subcommand("author",
                           "Fit the scene's fog; write its layers (glTF), the medium (OpenVDB), particles (PLY), "
                           "maps of fog placed by the terrain and report.json (--formats for more)");
    auto args = std::make_shared<AuthorArgs>();
    sub->add_option("scene", args->scene,
                    "scene file (JSON) with a fog section, or a DEM (a valley fog, every other key derived)")
        ->required();
    sub->add_option("-o,--out", args->out, "output folder")->required();
    sub->add_option("--formats", args->formats,
                    "comma-separated: glb (layers.glb), vdb (medium.vdb), particles (particles.ply), maps (fog placed "
                    "by the terrain), surface (base_surface.obj/.ply), obj (layers.obj), ply (layers.ply), all; "
                    "default glb,vdb,particles,maps");
    sub->add_option("--camera", args->camera,
                    "the scene camera the view-dependent layers are exported for (default: its first)");
    sub->add_option("--max-output", args->max_output_mib, "refuse when the files would weigh more (MiB, default 2048)")
        ->check(CLI::PositiveNumber);
    // Errors propagate to main, which prints one line and exits with code 2.
    sub->callback([args] { author(*args); });
}

}  // namespace kiri::cli
