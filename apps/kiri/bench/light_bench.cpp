// Light: the lighting model every renderer shares (fog_lighting.hpp), drawn exactly by the CPU
// reference marcher, against the path tracer (every order of scattering), view by view: uniform
// slabs seen from above, from the side and from inside at sun elevations of 10, 30 and 60
// degrees, a thin layer, and the shipped scenes' cameras (jacksboro_lake is the thick valley
// lake). The fog's own light only: no sky, a black ground (as scripts/crosscheck-cycles.sh).
// Per view: the brightness ratio (mean luminance over the path tracer's) and the mean relative
// error of 4x4-pixel blocks, for the baked model (its light-transport volume baked per view,
// light_volume_bake.hpp; the bake's time reported), the fitted model and the octaves it replaced,
// their pictures side by side (path tracer | baked | fitted | octaves), and the medians and the
// views meeting the goal (10 % brightness, 15 % block error). Then the cost of the lighting in
// each GL renderer, fitted against octaves and baked, measured side by side (KIRI_LIGHT_NO_COST=1
// skips it, KIRI_LIGHT_COST_ONLY=1 measures it alone).
// Then each GL renderer's picture under the baked model against the path tracer, the same way
// (KIRI_LIGHT_NO_RENDERERS=1 skips it): what every renderer inherits from the model.
// KIRI_LIGHT_VIEWS=TEXT[,TEXT...] keeps the views whose name holds one of the texts;
// KIRI_LIGHT_BAKE="photons per column,levels,bands,max side[,column normalised 0/1[,min photons[,seed]]]"
// sets the bake's options;
// KIRI_LIGHT_BAKED_ONLY=1 draws the baked model alone (reported in the other models' columns too:
// a quicker loop while tuning the bake).
//
// The judge: the path tracer at 1,024 paths a pixel (256 with --quick), then adaptively
// (PathTracerOptions::noise_target) more in each 4x4 block whose mean is noisier than 3 %, up to
// 16,384 (4,096); KIRI_LIGHT_JUDGE="samples,noise,max samples" sets them (noise 0: no adaptive
// rounds). Dark blocks, at 1e-5 of the frame's brightest, are otherwise off by a factor of 3 at
// 1,024 paths (docs/medium.md). Each view reports the judge's own noise: the mean over the
// blocks counted of their relative standard error, the error a perfect model would still show.
// The judge's images are cached in OUT/light/ (NAME.JUDGE.path.exr, its standard error and
// paths a pixel in NAME.JUDGE.path_error.exr): a rerun only renders the models. How the constants were found: KIRI_LIGHT_FIT=1 fits MultipleScatteringFit's
// constants to the slab and thin-layer views (Nelder-Mead on the sum over the views of the
// squared block and brightness errors plus the worst view's, with the model at half the size),
// KIRI_LIGHT_FIT_ITERATIONS steps (40) from KIRI_LIGHT_CONSTANTS ("b,c,d,K,k,e"; the defaults
// without), and prints them; KIRI_LIGHT_CONSTANTS also replaces the fitted model's constants in
// the report, and KIRI_LIGHT_FITTED_ONLY=1 reports the views fitted on alone.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "bench/bench.hpp"
#include "bench/fog_judge.hpp"
#include "bench/light_renderers.hpp"
#include "bench/light_views.hpp"
#include "kiri/geometry/reference/light_volume_bake.hpp"
#include "kiri/geometry/reference/path_tracer.hpp"
#include "kiri/geometry/reference/reference_fog.hpp"
#include "kiri/render/exr_image.hpp"
#include "kiri/render/tone_map.hpp"

namespace kiri::bench {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// One view, authored, with the path tracer's luminance.
struct Prepared {
    LightView view;
    fs::path scene_file;
    geometry::PipelineProducts products;
    geometry::FroxelOptions froxel;
    geometry::ReferenceView reference_view;
    geometry::FogLighting light;
    render::RadianceImage path;
    std::vector<double> truth;        //!< the path tracer's luminance
    std::vector<double> truth_error;  //!< its standard error (luminance)
    double judge_paths = 0.0;         //!< the judge's mean paths a pixel
    //! For the fit: the view at half the size and the truth's 2x2 means (4x4 blocks are 2x2).
    geometry::ReferenceView coarse_view;
    std::vector<double> coarse_truth;
    double path_seconds = 0.0;
    //! The baked model's light-transport volume of this view's fog and sun.
    std::shared_ptr<const geometry::LightVolume> volume;
};

//! The bake's options: the defaults, or
//! KIRI_LIGHT_BAKE="photons_per_column,levels,bands,max_side[,column_normalised[,min_photons[,seed]]]"
//! (another seed: the bake's noise, view by view).
geometry::LightVolumeOptions bake_options()
{
    geometry::LightVolumeOptions o;
    int normalised = 1;
    unsigned long long seed = o.seed;
    if (const char* k = std::getenv("KIRI_LIGHT_BAKE"))
        std::sscanf(k, "%d,%d,%d,%d,%d,%lld,%llu", &o.photons_per_column, &o.levels, &o.bands, &o.max_side, &normalised,
                    &o.min_photons, &seed);
    o.column_normalised = normalised != 0;
    o.seed = seed;
    return o;
}

//! The judge's paths a pixel and its adaptive sampling: the defaults, or
//! KIRI_LIGHT_JUDGE="samples,noise,max samples".
struct Judge {
    int samples = 1024;
    double noise = 0.03;
    int max_samples = 16384;
    //! The cache's name for it: the paths alone when not adaptive (as the caches before it).
    std::string tag() const
    {
        if (noise <= 0.0)
            return std::to_string(samples);
        char t[64];
        std::snprintf(t, sizeof t, "%d-%g-%d", samples, noise, max_samples);
        return t;
    }
};

Judge judge_options(bool quick)
{
    Judge j;
    if (quick) {
        j.samples = 256;
        j.max_samples = 4096;
    }
    if (const char* k = std::getenv("KIRI_LIGHT_JUDGE"))
        std::sscanf(k, "%d,%lf,%d", &j.samples, &j.noise, &j.max_samples);
    j.samples = std::max(j.samples, 1);
    j.max_samples = std::max(j.max_samples, j.samples);
    return j;
}

std::vector<double> luminances(const render::RadianceImage& image)
{
    std::vector<double> l(std::size_t(image.width) * image.height);
    for (std::size_t k = 0; k < l.size(); ++k)
        l[k] = geometry::luminance({image.rgba[4 * k], image.rgba[4 * k + 1], image.rgba[4 * k + 2]});
    return l;
}

std::vector<double> luminances(const geometry::ReferenceImage& image)
{
    std::vector<double> l(image.inscatter.size());
    for (std::size_t k = 0; k < l.size(); ++k)
        l[k] = geometry::luminance(image.composed(k));
    return l;
}

//! As scripts/cycles_medium.py's compare: the brightness ratio, the mean relative error of the
//! 4x4 blocks the reference lights (above 1e-6 of its brightest) and its signed mean.
struct LightError {
    double ratio = 0.0, block = 0.0, signed_block = 0.0;
    double judge_noise = 0.0;  //!< the mean relative standard error of b's blocks counted
    //! The mean relative error of the blocks above 1 % of b's brightest: the picture's visible
    //! fog, without the blocks a thousandth as bright where a little light leaked counts as much.
    double visible_block = 0.0;
};

//! b_error: b's standard error per pixel, if known (then LightError::judge_noise).
LightError light_error(const std::vector<double>& a, const std::vector<double>& b, int width, int height, int n = 4,
                       const std::vector<double>* b_error = nullptr)
{
    LightError e;
    double sa = 0.0, sb = 0.0;
    for (std::size_t k = 0; k < a.size(); ++k) {
        sa += a[k];
        sb += b[k];
    }
    e.ratio = sb > 0.0 ? sa / sb : 0.0;
    const int bw = width / n, bh = height / n;
    std::vector<double> ba(std::size_t(bw) * bh, 0.0), bb(ba.size(), 0.0), bv(ba.size(), 0.0);
    for (int y = 0; y < bh * n; ++y)
        for (int x = 0; x < bw * n; ++x) {
            const std::size_t k = std::size_t(y) * width + x, block = std::size_t(y / n) * bw + x / n;
            ba[block] += a[k];
            bb[block] += b[k];
            if (b_error)
                bv[block] += (*b_error)[k] * (*b_error)[k];
        }
    const double top = *std::max_element(bb.begin(), bb.end());
    int lit = 0, visible = 0;
    for (std::size_t k = 0; k < bb.size(); ++k)
        if (bb[k] > 1e-6 * std::max(top, 1e-30)) {
            e.block += std::abs(ba[k] - bb[k]) / bb[k];
            e.signed_block += (ba[k] - bb[k]) / bb[k];
            e.judge_noise += std::sqrt(bv[k]) / bb[k];
            ++lit;
            if (bb[k] > 1e-2 * top) {
                e.visible_block += std::abs(ba[k] - bb[k]) / bb[k];
                ++visible;
            }
        }
    if (lit > 0) {
        e.block /= lit;
        e.signed_block /= lit;
        e.judge_noise /= lit;
    }
    if (visible > 0)
        e.visible_block /= visible;
    return e;
}

//! KIRI_LIGHT_SPLIT=1: the baked model's light scattered more than once (it less the model
//! `none`, single scattering, which the reference draws exactly) over the path tracer's (it less
//! the same), printed for the view and written per 4x4 block to OUT/light/VIEW.blocks.txt
//! (column, row, path tracer, single scattering, baked): where the baked volume's light misses.
void split_single_scattering(const Context& c, const Prepared& p, const std::vector<double>& baked, int width,
                             int height);

Prepared prepare_view(const Context& c, const LightView& v, int width, int height, const Judge& judge)
{
    const fs::path dir = c.out_dir() / "light";
    fs::create_directories(dir);
    const fs::path file = v.scene.rfind("slab", 0) == 0 || v.scene.rfind("thin", 0) == 0
        ? write_slab_scene(dir, v.scene)
        : c.data_dir() / "scenes" / (v.scene + ".json");
    Prepared p;
    p.view = v;
    p.scene_file = file;
    const geometry::Scene scene = geometry::load_scene(file.string());
    p.products = geometry::author_scene(scene, render::pipeline_target(render::FogMode::froxel, scene));
    const geometry::Bounds3 bounds = p.products.terrain->bounds();
    const render::Camera camera = render::to_camera(scene.camera(v.camera, bounds.min, bounds.max));
    p.froxel = render::scene_froxel_options(scene, *p.products.terrain);
    p.reference_view = render::reference_view(camera, width, height, p.froxel.far);
    p.light = render::scene_fog_lighting(scene, p.products.terrain.get(), p.products.medium.get(), p.froxel);
    p.light.sky = false;
    const fs::path cached = dir / (v.name + "." + judge.tag() + ".path.exr");
    const fs::path cached_error = dir / (v.name + "." + judge.tag() + ".path_error.exr");
    render::RadianceImage error;  // rgb: the standard error; a: the paths
    if (fs::exists(cached) && fs::exists(cached_error)) {
        p.path = render::read_exr(cached);
        error = render::read_exr(cached_error);
    } else {
        geometry::PathTracerOptions po;
        po.samples = judge.samples;
        po.noise_target = judge.noise;
        po.max_samples = judge.max_samples;
        po.ground = geometry::PathGround::black;
        const geometry::PathTracedImage traced =
            geometry::render_path_traced({p.products.medium.get(), p.froxel.height_fog},
                                         &p.products.terrain->heightfield(), p.reference_view, p.light, po);
        p.path_seconds = traced.seconds;
        p.path = render::linear_radiance(traced);
        error.width = traced.width;
        error.height = traced.height;
        error.rgba.resize(4 * traced.std_error.size());
        for (std::size_t k = 0; k < traced.std_error.size(); ++k) {
            for (int ch = 0; ch < 3; ++ch)
                error.rgba[4 * k + ch] = float(traced.std_error[k][ch]);
            error.rgba[4 * k + 3] = float(traced.pixel_samples[k]);
        }
        render::write_exr_atomic(cached_error, error);
        render::write_exr_atomic(cached, p.path);
    }
    p.truth = luminances(p.path);
    p.truth_error = luminances(error);
    for (std::size_t k = 0; k < p.truth.size(); ++k)
        p.judge_paths += error.rgba[4 * k + 3] / double(p.truth.size());
    p.volume = std::make_shared<const geometry::LightVolume>(
        geometry::bake_light_volume({p.products.medium.get(), p.froxel.height_fog}, &p.products.terrain->heightfield(),
                                    p.light.sun_direction, bake_options()));
    p.light.light_volume = p.volume;
    p.coarse_view = p.reference_view;
    p.coarse_view.width = width / 2;
    p.coarse_view.height = height / 2;
    p.coarse_truth.assign(std::size_t(p.coarse_view.width) * p.coarse_view.height, 0.0);
    for (int y = 0; y < 2 * p.coarse_view.height; ++y)
        for (int x = 0; x < 2 * p.coarse_view.width; ++x)
            p.coarse_truth[std::size_t(y / 2) * p.coarse_view.width + x / 2] +=
                0.25 * p.truth[std::size_t(y) * width + x];
    return p;
}

geometry::ReferenceImage model_image(const Prepared& p, geometry::MultipleScattering kind,
                                     const geometry::MultipleScatteringFit& fit = {}, bool coarse = false)
{
    geometry::FogLighting light = p.light;
    light.multiple_scattering = kind;
    light.fit = fit;
    geometry::ReferenceOptions ro;
    ro.shade_terrain = false;
    if (coarse)
        ro.optical_step = 0.05;
    return geometry::render_reference_fog({p.products.medium.get(), p.froxel.height_fog},
                                          &p.products.terrain->heightfield(), coarse ? p.coarse_view : p.reference_view,
                                          light, ro);
}

void split_single_scattering(const Context& c, const Prepared& p, const std::vector<double>& baked, int width,
                             int height)
{
    const std::vector<double> single = luminances(model_image(p, geometry::MultipleScattering::none));
    constexpr int n = 4;
    const int bw = width / n, bh = height / n;
    std::vector<double> bp(std::size_t(bw) * bh, 0.0), bs(bp.size(), 0.0), bb(bp.size(), 0.0);
    for (int y = 0; y < bh * n; ++y)
        for (int x = 0; x < bw * n; ++x) {
            const std::size_t b = std::size_t(y / n) * bw + x / n, k = std::size_t(y) * width + x;
            bp[b] += p.truth[k];
            bs[b] += single[k];
            bb[b] += baked[k];
        }
    double path = 0.0, once = 0.0, model = 0.0;
    std::ofstream f(c.out_dir() / "light" / (p.view.name + ".blocks.txt"));
    for (std::size_t b = 0; b < bp.size(); ++b) {
        path += bp[b];
        once += bs[b];
        model += bb[b];
        f << b % bw << ' ' << b / bw << ' ' << bp[b] << ' ' << bs[b] << ' ' << bb[b] << '\n';
    }
    std::printf("  %-34s single scattering %.3f of the path tracer's light; more than once: baked / path %.3f\n",
                p.view.name.c_str(), path > 0.0 ? once / path : 0.0,
                path > once ? (model - once) / (path - once) : 0.0);
}

// Nelder-Mead over MultipleScatteringFit's constants on the views fitted on: the sum over the
// views of the squared block error and the squared brightness error, plus the worst view's.
void fit_constants(const std::vector<Prepared>& views)
{
    constexpr int D = 6;
    using Point = std::array<double, D>;
    const auto to_fit = [](const Point& x) {
        geometry::MultipleScatteringFit f;
        f.persistence = std::clamp(x[0], 0.0, 1.0);
        f.eccentricity = std::clamp(x[1], 0.0, 1.0);
        f.diffuse_eccentricity = std::clamp(x[2], -1.0, 1.0);
        f.amplitude = std::max(x[3], 0.0);
        f.sun_power = x[4];
        f.low_sun_eccentricity = x[5];
        return f;
    };
    const auto cost = [&](const Point& x) {
        const geometry::MultipleScatteringFit f = to_fit(x);
        double sum = 0.0, worst = 0.0;
        for (const Prepared& p : views) {
            const geometry::ReferenceImage r = model_image(p, geometry::MultipleScattering::fitted, f, true);
            const LightError e = light_error(luminances(r), p.coarse_truth, r.width, r.height, 2);
            const double v = e.block * e.block + (e.ratio - 1) * (e.ratio - 1);
            sum += v;
            worst = std::max(worst, v);
        }
        std::printf("    %.4f,%.4f,%.4f,%.4f,%.4f,%.4f: sum %.5f worst %.5f\n", f.persistence, f.eccentricity,
                    f.diffuse_eccentricity, f.amplitude, f.sun_power, f.low_sun_eccentricity, sum, worst);
        std::fflush(stdout);
        return sum + worst;
    };
    const geometry::MultipleScatteringFit start;
    std::array<Point, D + 1> simplex;
    simplex.fill({start.persistence, start.eccentricity, start.diffuse_eccentricity, start.amplitude, start.sun_power,
                  start.low_sun_eccentricity});
    if (const char* k = std::getenv("KIRI_LIGHT_CONSTANTS"))
        std::sscanf(k, "%lf,%lf,%lf,%lf,%lf,%lf", &simplex[0][0], &simplex[0][1], &simplex[0][2], &simplex[0][3],
                    &simplex[0][4], &simplex[0][5]);
    for (int i = 1; i <= D; ++i)
        simplex[i] = simplex[0];
    const double step[D] = {-0.05, -0.15, 0.3, 0.7, -0.4, 0.3};
    for (int i = 0; i < D; ++i)
        simplex[i + 1][i] += step[i];
    std::array<double, D + 1> f;
    for (int i = 0; i <= D; ++i)
        f[i] = cost(simplex[i]);
    const char* n = std::getenv("KIRI_LIGHT_FIT_ITERATIONS");
    for (int it = 0, iterations = n ? std::atoi(n) : 40; it < iterations; ++it) {
        std::array<int, D + 1> order;
        for (int i = 0; i <= D; ++i)
            order[i] = i;
        std::sort(order.begin(), order.end(), [&](int a, int b) { return f[a] < f[b]; });
        const int worst = order[D], second = order[D - 1], best = order[0];
        Point centre{};
        for (int i : order)
            if (i != worst)
                for (int d = 0; d < D; ++d)
                    centre[d] += simplex[i][d] / D;
        const auto along = [&](double t) {
            Point x;
            for (int d = 0; d < D; ++d)
                x[d] = centre[d] + t * (simplex[worst][d] - centre[d]);
            return x;
        };
        const Point reflected = along(-1.0);
        const double fr = cost(reflected);
        if (fr < f[best]) {
            const Point expanded = along(-2.0);
            const double fe = cost(expanded);
            simplex[worst] = fe < fr ? expanded : reflected;
            f[worst] = std::min(fe, fr);
        } else if (fr < f[second]) {
            simplex[worst] = reflected;
            f[worst] = fr;
        } else {
            const Point contracted = along(0.5);
            const double fc = cost(contracted);
            if (fc < f[worst]) {
                simplex[worst] = contracted;
                f[worst] = fc;
            } else {
                for (int i : order)
                    if (i != best) {
                        for (int d = 0; d < D; ++d)
                            simplex[i][d] = simplex[best][d] + 0.5 * (simplex[i][d] - simplex[best][d]);
                        f[i] = cost(simplex[i]);
                    }
            }
        }
    }
    const int best = int(std::min_element(f.begin(), f.end()) - f.begin());
    const geometry::MultipleScatteringFit b = to_fit(simplex[best]);
    std::printf(
        "  best: persistence %.4f eccentricity %.4f diffuse_eccentricity %.4f amplitude %.4f sun_power %.4f "
        "low_sun_eccentricity %.4f (cost %.5f)\n",
        b.persistence, b.eccentricity, b.diffuse_eccentricity, b.amplitude, b.sun_power, b.low_sun_eccentricity,
        f[best]);
}

// Path tracer | fitted | octaves, tone-mapped, side by side.
render::Image side_by_side(const std::vector<render::Image>& images)
{
    render::Image out;
    const int gap = 2;
    out.height = images.front().height;
    for (const render::Image& i : images)
        out.width += i.width + gap;
    out.width -= gap;
    out.rgba.assign(std::size_t(out.width) * out.height * 4, 255);
    int x0 = 0;
    for (const render::Image& i : images) {
        for (int y = 0; y < i.height; ++y)
            std::copy_n(&i.rgba[std::size_t(y) * i.width * 4], i.width * 4,
                        &out.rgba[(std::size_t(y) * out.width + x0) * 4]);
        x0 += i.width + gap;
    }
    return out;
}

render::Image tone_mapped_path(const render::RadianceImage& r)
{
    geometry::ReferenceImage as_reference;
    as_reference.width = r.width;
    as_reference.height = r.height;
    const std::size_t n = std::size_t(r.width) * r.height;
    as_reference.inscatter.resize(n);
    as_reference.transmittance.assign(n, 0.0);
    as_reference.background.assign(n, glm::dvec3(0.0));
    as_reference.depth.assign(n, 0.0);
    for (std::size_t k = 0; k < n; ++k)
        as_reference.inscatter[k] = {r.rgba[4 * k], r.rgba[4 * k + 1], r.rgba[4 * k + 2]};
    return render::tone_mapped(as_reference);
}

// The cost of the lighting in each GL renderer: frames of the default scene's Medium with the
// fitted model, with octaves and baked (its volume read per froxel, per layer fragment, per
// billboard corner), alternated, the median of each.
void light_cost(Context& c, std::ofstream& md)
{
    SceneJson source(c.data_dir() / "scenes/jacksboro.json");
    json base = source.root;
    base["froxel"].erase("height_fog");
    const int w = 320, h = 180, frames = c.quick() ? 3 : 7;
    FogJudge judge(source.parse(base), "ridge", 80, 45);
    const char* models[] = {"fitted", "octaves", "baked"};
    md << "\n| renderer | frame, fitted (ms) | frame, octaves (ms) | frame, baked (ms) | fitted / octaves | baked / "
          "fitted |\n|---|---|---|---|---|---|\n";
    for (const render::FogMode mode :
         {render::FogMode::layers, render::FogMode::particles, render::FogMode::froxel, render::FogMode::combined}) {
        double ms[3] = {0.0, 0.0, 0.0};
        std::vector<double> runs[3];
        for (int round = 0; round < 3; ++round)
            for (int m = 0; m < 3; ++m) {
                json varied = base;
                varied["medium"]["multiple_scattering"] = models[m];
                judge.prepare(source.parse(varied), mode);
                runs[m].push_back(judge.frame_ms(w, h, frames));
            }
        for (int m = 0; m < 3; ++m) {
            std::sort(runs[m].begin(), runs[m].end());
            ms[m] = runs[m][1];
        }
        const std::string series = render::to_string(mode);
        std::printf("  %-9s frame %dx%d: fitted %.1f ms, octaves %.1f ms (%.2fx), baked %.1f ms (%.2fx fitted)\n",
                    series.c_str(), w, h, ms[0], ms[1], ms[0] / ms[1], ms[2], ms[2] / ms[0]);
        std::fflush(stdout);
        md << "| " << series << " | " << ms[0] << " | " << ms[1] << " | " << ms[2] << " | " << ms[0] / ms[1] << " | "
           << ms[2] / ms[0] << " |\n";
    }
}

// Every GL renderer under the baked model against the path tracer, view by view: the same
// brightness and block errors as the model's, of each renderer's picture over a black world
// drawn at 4 times the size, each judge pixel read at its centre (bench/light_renderers.hpp).
void renderers_against_path(const std::vector<Prepared>& views, const std::vector<LightError>& model, std::ofstream& md,
                            int width, int height)
{
    LightFrames frames;
    const render::FogMode modes[] = {render::FogMode::layers, render::FogMode::particles, render::FogMode::froxel,
                                     render::FogMode::combined};
    md << "\nEach GL renderer under `baked`, its picture over a black world at " << 4 * width << "x" << 4 * height
       << " read at the centres of " << width << "x" << height << " pixels"
       << ", against the path tracer: brightness, block error, and in brackets the block error over the blocks above 1 "
          "% of the brightest (layers and particles draw no height fog: -). First the model itself (the CPU "
          "reference).\n\n"
       << "| view | model | layers | particles | froxels | combined |\n|---|---|---|---|---|---|\n";
    std::vector<double> blocks[4], visible[4];
    int met[4] = {0, 0, 0, 0}, drawn[4] = {0, 0, 0, 0};
    for (const Prepared& p : views) {
        const LightError& em = model[std::size_t(&p - views.data())];
        char cell[96];
        std::snprintf(cell, sizeof cell, " | %.3f, %.1f %% (%.1f %%)", em.ratio, 100 * em.block,
                      100 * em.visible_block);
        md << "| " << p.view.name << cell;
        std::printf("  %-34s model %.3f %5.1f %% (%4.1f %%)", p.view.name.c_str(), em.ratio, 100 * em.block,
                    100 * em.visible_block);
        for (int m = 0; m < 4; ++m) {
            const std::vector<double> l = frames.luminance(p.scene_file, p.view.camera, modes[m], width, height, 4);
            if (l.empty()) {
                md << " | -";
                std::printf(" %-9s -              ", render::to_string(modes[m]));
                continue;
            }
            const LightError e = light_error(l, p.truth, width, height);
            const bool ok = std::abs(e.ratio - 1.0) <= 0.10 && e.block <= 0.15;
            blocks[m].push_back(e.block);
            visible[m].push_back(e.visible_block);
            met[m] += ok;
            ++drawn[m];
            std::snprintf(cell, sizeof cell, " | %.3f, %.1f %% (%.1f %%)%s", e.ratio, 100 * e.block,
                          100 * e.visible_block, ok ? " met" : "");
            md << cell;
            std::printf(" %-9s %.3f %5.1f %% (%4.1f %%)%s", render::to_string(modes[m]), e.ratio, 100 * e.block,
                        100 * e.visible_block, ok ? " met" : "    ");
        }
        md << " |\n";
        std::printf("\n");
        std::fflush(stdout);
    }
    md << "\nMedian block error (over the visible blocks) and views meeting the goal:";
    std::printf("  GL renderers under baked, median block error (visible blocks) and the goal met:");
    const auto median = [](std::vector<double> v) {
        std::sort(v.begin(), v.end());
        return v.empty() ? 0.0 : v[v.size() / 2];
    };
    for (int m = 0; m < 4; ++m) {
        md << " " << render::to_string(modes[m]) << " " << 100 * median(blocks[m]) << " % (" << 100 * median(visible[m])
           << " %), " << met[m] << " of " << drawn[m] << (m < 3 ? ";" : ".\n");
        std::printf(" %s %.1f %% (%.1f %%), %d of %d%s", render::to_string(modes[m]), 100 * median(blocks[m]),
                    100 * median(visible[m]), met[m], drawn[m], m < 3 ? ";" : "\n");
    }
}

// Whether `name` holds one of the comma-separated texts of `list`.
bool names_any(const std::string& name, const std::string& list)
{
    for (std::size_t a = 0; a <= list.size();) {
        const std::size_t b = std::min(list.find(',', a), list.size());
        if (b > a && name.find(list.substr(a, b - a)) != std::string::npos)
            return true;
        a = b + 1;
    }
    return false;
}

void light(Context& c)
{
    if (std::getenv("KIRI_LIGHT_COST_ONLY")) {  // the GL renderers' cost per model alone
        std::ofstream md(c.out_dir() / "light_cost.md");
        light_cost(c, md);
        return;
    }
    const int width = 80, height = 45;
    const Judge judge = judge_options(c.quick());
    const char* fit = std::getenv("KIRI_LIGHT_FIT");
    const bool fitting = fit && std::string(fit) == "1";
    std::vector<Prepared> views;
    for (const LightView& v : light_views(c.quick())) {
        if ((fitting || std::getenv("KIRI_LIGHT_FITTED_ONLY")) && !v.fitted_on)
            continue;
        if (const char* only = std::getenv("KIRI_LIGHT_VIEWS"); only && !names_any(v.name, only))
            continue;
        views.push_back(prepare_view(c, v, width, height, judge));
        if (views.back().path_seconds > 0.0)
            std::printf("  %-34s path traced (%.0f paths a pixel on average) in %.1f s\n", v.name.c_str(),
                        views.back().judge_paths, views.back().path_seconds);
        std::fflush(stdout);
    }
    if (fitting) {
        fit_constants(views);
        return;
    }
    std::ofstream md(c.out_dir() / "light.md");
    md << "The fog's own light (no sky, black ground), " << width << "x" << height << ", the path tracer at "
       << judge.samples << " paths a pixel";
    if (judge.noise > 0.0)
        md << ", and up to " << judge.max_samples << " in the 4x4 blocks noisier than " << 100 * judge.noise << " %";
    md << ". Brightness: mean luminance over the path tracer's; block: mean relative "
       << "error of 4x4-pixel blocks (signed in brackets). Goal: brightness within 10 %, block error under 15 %. "
       << "Judge noise: the path tracer's own mean relative standard error over those blocks.\n\n"
       << "| view | baked brightness | baked block | bake (s) | fitted brightness | fitted block | octaves "
          "brightness | octaves block | judge noise (paths a pixel) | fitted on |\n"
       << "|---|---|---|---|---|---|---|---|---|---|\n";
    double time_fitted = 0.0, time_octaves = 0.0, time_baked = 0.0, time_bake = 0.0;
    std::vector<double> block_baked, block_fitted, bright_baked, bright_fitted, judge_noise;
    std::vector<LightError> model_errors;  // the baked model's, view by view
    int met_baked = 0, met_fitted = 0;
    const auto met = [](const LightError& e) { return std::abs(e.ratio - 1.0) <= 0.10 && e.block <= 0.15; };
    for (const Prepared& p : views) {
        geometry::MultipleScatteringFit constants;
        if (const char* k = std::getenv("KIRI_LIGHT_CONSTANTS"))
            std::sscanf(k, "%lf,%lf,%lf,%lf,%lf,%lf", &constants.persistence, &constants.eccentricity,
                        &constants.diffuse_eccentricity, &constants.amplitude, &constants.sun_power,
                        &constants.low_sun_eccentricity);
        const geometry::ReferenceImage baked = model_image(p, geometry::MultipleScattering::baked);
        const bool baked_only = std::getenv("KIRI_LIGHT_BAKED_ONLY") != nullptr;
        const geometry::ReferenceImage fitted =
            baked_only ? baked : model_image(p, geometry::MultipleScattering::fitted, constants);
        const geometry::ReferenceImage octaves =
            baked_only ? fitted : model_image(p, geometry::MultipleScattering::octaves);
        time_baked += baked.seconds;
        time_fitted += fitted.seconds;
        time_octaves += octaves.seconds;
        time_bake += p.volume->seconds;
        const LightError eb = light_error(luminances(baked), p.truth, width, height, 4, &p.truth_error);
        const LightError ef = light_error(luminances(fitted), p.truth, width, height);
        const LightError eo = light_error(luminances(octaves), p.truth, width, height);
        block_baked.push_back(eb.block);
        block_fitted.push_back(ef.block);
        bright_baked.push_back(std::abs(eb.ratio - 1.0));
        bright_fitted.push_back(std::abs(ef.ratio - 1.0));
        judge_noise.push_back(eb.judge_noise);
        model_errors.push_back(eb);
        met_baked += met(eb);
        met_fitted += met(ef);
        c.add({"baked", p.view.name, eb.ratio, baked.seconds + p.volume->seconds, "mean 4x4-block error", eb.block, 0.0,
               0.0});
        c.add({"fitted", p.view.name, ef.ratio, fitted.seconds, "mean 4x4-block error", ef.block, 0.0, 0.0});
        c.add({"octaves", p.view.name, eo.ratio, octaves.seconds, "mean 4x4-block error", eo.block, 0.0, 0.0});
        std::printf(
            "  %-34s baked: %.3f %5.1f %% (%+5.1f %%) %s bake %.2f s   fitted: %.3f %5.1f %%%s  octaves: %.3f "
            "%5.1f %%  judge noise %.1f %%\n",
            p.view.name.c_str(), eb.ratio, 100 * eb.block, 100 * eb.signed_block, met(eb) ? "met" : "   ",
            p.volume->seconds, ef.ratio, 100 * ef.block, met(ef) ? " met" : "", eo.ratio, 100 * eo.block,
            100 * eb.judge_noise);
        std::fflush(stdout);
        char line[320];
        std::snprintf(line, sizeof line,
                      "| %s | %.3f | %.1f %% (%+.1f %%) | %.2f | %.3f | %.1f %% (%+.1f %%) | %.3f | %.1f %% | %.1f %% "
                      "(%.0f) | %s |\n",
                      p.view.name.c_str(), eb.ratio, 100 * eb.block, 100 * eb.signed_block, p.volume->seconds, ef.ratio,
                      100 * ef.block, 100 * ef.signed_block, eo.ratio, 100 * eo.block, 100 * eb.judge_noise,
                      p.judge_paths, p.view.fitted_on ? "yes" : "");
        md << line;
        if (std::getenv("KIRI_LIGHT_SPLIT"))
            split_single_scattering(c, p, luminances(baked), width, height);
        render::write_png_atomic(c.out_dir() / "light" / (p.view.name + ".png"),
                                 side_by_side({tone_mapped_path(p.path), render::tone_mapped(baked),
                                               render::tone_mapped(fitted), render::tone_mapped(octaves)}));
    }
    const auto median = [](std::vector<double> v) {
        if (v.empty())
            return 0.0;
        std::sort(v.begin(), v.end());
        return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
    };
    std::printf(
        "  medians: baked block %.1f %%, brightness %.1f %%, goal met on %d of %zu; fitted block %.1f %%, "
        "brightness %.1f %%, goal met on %d; the judge's noise %.1f %%\n",
        100 * median(block_baked), 100 * median(bright_baked), met_baked, views.size(), 100 * median(block_fitted),
        100 * median(bright_fitted), met_fitted, 100 * median(judge_noise));
    std::printf("  CPU reference, all views: baked %.2f s (+ bakes %.2f s), fitted %.2f s, octaves %.2f s\n",
                time_baked, time_bake, time_fitted, time_octaves);
    md << "\nMedians over " << views.size() << " views: baked block " << 100 * median(block_baked) << " %, brightness "
       << 100 * median(bright_baked) << " %, goal met on " << met_baked << "; fitted block "
       << 100 * median(block_fitted) << " %, brightness " << 100 * median(bright_fitted) << " %, goal met on "
       << met_fitted << "; the judge's noise " << 100 * median(judge_noise) << " %.\n";
    md << "\nCPU reference over all views: baked " << time_baked << " s (bakes " << time_bake << " s), fitted "
       << time_fitted << " s, octaves " << time_octaves << " s.\n";
    if (!std::getenv("KIRI_LIGHT_NO_RENDERERS"))
        renderers_against_path(views, model_errors, md, width, height);
    if (std::getenv("KIRI_LIGHT_NO_COST"))
        return;
    if (!std::getenv("KIRI_LIGHT_FITTED_ONLY"))
        light_cost(c, md);
}

}  // namespace

KIRI_BENCH_STAGE({"light",
                  "The lighting model against the path tracer, view by view: brightness ratio vs block error",
                  {"brightness ratio (model / path tracer)", "error_value", "mean 4x4-block error", false, true, true},
                  light});

}  // namespace kiri::bench
