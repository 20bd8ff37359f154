#include "bench/fog_judge.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

#include "kiri/geometry/core/error.hpp"

namespace kiri::bench {

SceneJson::SceneJson(std::filesystem::path scene_file) : file(std::move(scene_file))
{
    std::ifstream in(file);
    if (!in)
        throw IoError(file.string(), "", "cannot read the scene");
    root = nlohmann::json::parse(in);
}

geometry::Scene SceneJson::parse(const nlohmann::json& varied) const
{
    return geometry::parse_scene(varied.dump(), file.string(), file.parent_path());
}

FogJudge::FogJudge(const geometry::Scene& given, const std::string& camera, int width, int height)
    : width_(width), height_(height)
{
    // Up to the light stage: the Medium, and its light volume where its model is `baked`.
    const geometry::PipelineProducts& fog = pipeline_.run(given, {geometry::Stage::light, geometry::ParticleSet::none});
    // The scene as kiri render sees it: the keys a DEM's scene leaves out (the sun, the Medium's
    // extinction, ...) derived from its terrain.
    const geometry::Scene& base = *fog.scene;
    const geometry::Terrain& terrain = *fog.terrain;
    const geometry::Bounds3 b = terrain.bounds();
    camera_ = render::to_camera(base.camera(camera, b.min, b.max));
    const geometry::FroxelOptions froxel = render::scene_froxel_options(base, terrain);
    // The view ends where the froxel volume does (0: nowhere).
    const geometry::ReferenceView view = render::reference_view(camera_, width, height, froxel.far);
    const auto start = std::chrono::steady_clock::now();
    geometry::ReferenceOptions options;
    options.surround = base.terrain.surround;
    const geometry::FogLighting lighting =
        render::scene_fog_lighting(base, &terrain, fog.medium.get(), froxel, fog.light_volume);
    reference_ = geometry::render_reference_fog({fog.medium.get(), froxel.height_fog}, &terrain.heightfield(), view,
                                                lighting, options);
    reference_fog_ = {fog.medium, froxel.height_fog, base.sun};
    context_ = render::create_headless_context();
    renderer_ = std::make_unique<render::Renderer>();
    renderer_->set_terrain(terrain, 1.0, base.terrain.surround);
    renderer_->set_sun(render::to_sun(base.sun));
    // Where a pixel's footprint holds two surfaces, the reference through each of the frame's
    // samples there (where the renderer puts them: a frame drawn to see).
    renderer_->draw(camera_, width, height);
    at_samples_.pixels = render::footprint_edges(reference_);
    at_samples_.reference = geometry::render_reference_rays(
        {fog.medium.get(), froxel.height_fog}, &terrain.heightfield(), view, lighting,
        render::sample_points(at_samples_.pixels, renderer_->read_radiance_samples()), options);
    reference_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

FogJudge::~FogJudge() = default;

void FogJudge::prepare(const geometry::Scene& scene, render::FogMode mode)
{
    const geometry::PipelineProducts& products = pipeline_.run(scene, render::pipeline_target(mode, scene));
    const geometry::Scene& derived = *products.scene;  // as the judge's reference and kiri render see it
    rendering_.emplace(derived, products, mode);
    renderer_->set_terrain(*products.terrain, 1.0, derived.terrain.surround);  // uploads when it changed
    rendering_->apply(*renderer_);
}

const geometry::Terrain& FogJudge::terrain() const { return *pipeline_.products().terrain; }

double FogJudge::frame_ms(int width, int height, int frames) { return frame_cost(width, height, frames).frame_ms; }

namespace {

double median(std::vector<double> v)
{
    if (v.empty())
        return 0.0;
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
    return v[v.size() / 2];
}

}  // namespace

FrameCost FogJudge::frame_cost(int width, int height, int frames)
{
    // Untimed frames first, for at least warm_up_ms: the first uploads the layers and builds the
    // buffer and the shadow map, and a GPU raises its clocks only under a sustained load (3
    // frames of a few ms each left an H200 at its idle clock). Then timed frames until `frames`
    // of them and at least timed_ms have passed: a median of many where frames are short.
    constexpr double warm_up_ms = 300.0, timed_ms = 500.0;
    constexpr int most_frames = 400;
    std::vector<double> ms;
    std::vector<std::vector<render::PassTime>> passes;
    const auto since = [](std::chrono::steady_clock::time_point t) {
        return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
    };
    int k = 0;
    const auto next_view = [&] {
        render::Camera c = camera_;
        c.position.z += 1e-3 * (1 + k++ % 64);  // a new view each frame: every pass reruns
        renderer_->draw(c, width, height);
    };
    const auto warm_up = std::chrono::steady_clock::now();
    do
        next_view();
    while (since(warm_up) < warm_up_ms);
    const auto timed = std::chrono::steady_clock::now();
    while (int(ms.size()) < frames || (since(timed) < timed_ms && int(ms.size()) < most_frames)) {
        next_view();
        ms.push_back(renderer_->last_stats().frame_ms);
        passes.push_back(renderer_->last_stats().passes);
    }
    FrameCost cost;
    cost.frame_ms = median(ms);
    cost.frames = int(ms.size());
    const render::FroxelStats& froxel = renderer_->last_stats().froxel;
    if (froxel.applied_pixels > 0) {
        cost.marched = double(froxel.marched_pixels) / froxel.applied_pixels;
        cost.upsampled = double(froxel.upsampled_pixels) / froxel.applied_pixels;
    }
    cost.drawn_particles = renderer_->last_stats().particles_drawn;
    cost.near_particles = renderer_->last_stats().near_particles;
    cost.particle_fragments = renderer_->last_stats().particle_fragments;
    for (const render::PassTime& pass : passes.back()) {
        std::vector<double> gpu, cpu;
        for (const auto& frame : passes)
            for (const render::PassTime& p : frame)
                if (p.pass == pass.pass) {
                    gpu.push_back(p.gpu_ms);
                    cpu.push_back(p.cpu_ms);
                }
        cost.passes.push_back({pass.pass, median(gpu), median(cpu)});
    }
    return cost;
}

void FogJudge::set_reduced_resolution(double scale)
{
    renderer_->set_froxel_resolution(scale);
    renderer_->set_terrain_resolution(scale);
    renderer_->set_particle_resolution(scale);
}

double FogJudge::still_ms(int width, int height)
{
    renderer_->clear_froxel_fog();  // the fog seen for the first time, as in a new process
    rendering_->apply(*renderer_);
    const auto start = std::chrono::steady_clock::now();
    still_image_ = renderer_->render(camera_, width, height);
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

namespace {

// Whether two Media are one fog: their grids, optics and detail (a pipeline that ran the medium
// stage again for another scene and back makes an equal one, not the same).
bool same_medium(const geometry::Medium* a, const geometry::Medium* b)
{
    if (a == b)
        return true;
    if (!a || !b)
        return false;
    return a->options() == b->options() && a->detail() == b->detail() && a->grid() == b->grid();
}

}  // namespace

std::string FogJudge::fog_difference() const
{
    const geometry::PipelineProducts& now = pipeline_.products();
    if (now.medium && !same_medium(now.medium.get(), reference_fog_.medium.get()))
        return "its Medium";
    if (render::scene_froxel_options(*now.scene, *now.terrain).height_fog != reference_fog_.height_fog)
        return "its height fog";
    if (now.scene->sun != reference_fog_.sun)
        return "its sun";
    return "";
}

render::FogError FogJudge::error(std::vector<float>* signed_error)
{
    if (const std::string differs = fog_difference(); !differs.empty())
        throw Error("the frame to judge draws another fog than the judge's reference (" + differs +
                    " differs): a configuration that changes the fog needs a judge of its own");
    // A still picture as kiri render draws it.
    last_image_ = renderer_->render(camera_, width_, height_);
    const render::RadianceImage with = renderer_->read_radiance();
    // The frame without fog sees the same terrain, in the same shadows (the sun's, as set).
    const Plain& plain = without_fog(rendering_->sun().terrain_shadows);
    const Plain& sky_lit = without_sun();
    at_samples_.without_fog = &plain.samples;
    at_samples_.without_sun = &sky_lit.samples;
    rendering_->apply(*renderer_);  // back to the fog for what follows
    return render::compare_frames(with, plain.image, reference_, signed_error, &sky_lit.image, &at_samples_);
}

void FogJudge::clear_fog()
{
    renderer_->clear_layers();
    renderer_->clear_particles();
    renderer_->set_fog_partition(std::nullopt);
    renderer_->clear_froxel_fog();
    renderer_->clear_sun_medium();  // the ground fully lit: the reference's shade is applied to it
}

const FogJudge::Plain& FogJudge::without_fog(bool shadows)
{
    std::optional<Plain>& plain = plain_[shadows ? 1 : 0];
    if (!plain) {
        clear_fog();
        renderer_->draw(camera_, width_, height_);
        renderer_->draw(camera_, width_, height_);
        plain = Plain{renderer_->read_radiance(), renderer_->read_radiance_samples()};
    }
    return *plain;
}

const FogJudge::Plain& FogJudge::without_sun()
{
    if (!sky_lit_) {
        clear_fog();
        render::SunLight dark = rendering_->sun();
        dark.intensity = 0.0;
        renderer_->set_sun(dark);
        renderer_->draw(camera_, width_, height_);
        sky_lit_ = Plain{renderer_->read_radiance(), renderer_->read_radiance_samples()};
        renderer_->set_sun(rendering_->sun());
    }
    return *sky_lit_;
}

}  // namespace kiri::bench
