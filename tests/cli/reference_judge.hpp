#pragma once
// A `kiri render` picture judged against the CPU reference as `kiri bench` judges a renderer
// (render::compare_frames): the command's linear radiance (-o x.exr) with its fog and without
// (--mode terrain), the reference of the scene's Medium and height fog computed here for the
// same view (as `kiri render --mode reference` computes it).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>

#include "cli/kiri_runner.hpp"
#include "kiri/geometry/reference/reference_fog.hpp"
#include "kiri/geometry/scene/pipeline.hpp"
#include "kiri/geometry/scene/scene.hpp"
#include "kiri/render/exr_image.hpp"
#include "kiri/render/fog_error.hpp"
#include "kiri/render/scene_rendering.hpp"

namespace kiri::test {

//! `kiri render SCENE --mode MODE ARGS -o x.exr`, read back.
inline render::RadianceImage render_radiance(const std::string& scene, const std::string& mode, const std::string& args)
{
    const std::filesystem::path out = temp_path("judged_" + mode + ".exr");
    const RunResult r = run_kiri("render " + scene + " -o " + out.string() + " --mode " + mode + " " + args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    render::RadianceImage image = render::read_exr(out);
    std::filesystem::remove(out);
    return image;
}

//! The reference of the scene's fog seen from its camera `camera` ("" for the first): its Medium,
//! and its froxel height fog when `height_fog` (only the froxels draw it: false for the layers
//! and the particles alone).
inline geometry::ReferenceImage scene_reference(const std::string& scene_file, const std::string& camera, int width,
                                                int height, bool height_fog)
{
    const geometry::Scene given = geometry::load_scene(scene_file);
    const geometry::PipelineProducts products =
        geometry::author_scene(given, render::pipeline_target(render::FogMode::froxel, given));
    const geometry::Scene& scene = *products.scene;
    const geometry::Terrain& terrain = *products.terrain;
    const geometry::Bounds3 bounds = terrain.bounds();
    const render::Camera view_camera = render::to_camera(scene.camera(camera, bounds.min, bounds.max));
    const geometry::FroxelOptions options = render::scene_froxel_options(scene, terrain);
    const geometry::ReferenceView view = render::reference_view(view_camera, width, height, options.far);
    const geometry::FogLighting light =
        render::scene_fog_lighting(scene, &terrain, products.medium.get(), options, products.light_volume);
    return geometry::render_reference_fog(
        {products.medium.get(), height_fog ? options.height_fog : geometry::HeightFog{}}, &terrain.heightfield(), view,
        light);
}

inline double mean_luminance(const render::RadianceImage& image)
{
    double sum = 0.0;
    for (std::size_t k = 0; k < image.rgba.size(); k += 4)
        sum += geometry::luminance({image.rgba[k], image.rgba[k + 1], image.rgba[k + 2]});
    return sum / double(image.rgba.size() / 4);
}

//! What a grey overlay in place of the fog draws: the frame without fog under a uniform grey
//! veil of opacity `opacity`, as bright on average as the frame with fog. It makes the picture
//! brighter and greyer as fog does, but not where the fog is.
inline render::RadianceImage grey_veil(const render::RadianceImage& bare, const render::RadianceImage& fog,
                                       double opacity)
{
    const double grey = std::max(0.0, (mean_luminance(fog) - (1.0 - opacity) * mean_luminance(bare)) / opacity);
    render::RadianceImage veiled = bare;
    for (std::size_t k = 0; k < veiled.rgba.size(); k += 4)
        for (int c = 0; c < 3; ++c)
            veiled.rgba[k + c] = float((1.0 - opacity) * veiled.rgba[k + c] + opacity * grey);
    return veiled;
}

//! The fog of `fog` (over the frame without it, `bare`) against `reference`: more than
//! `min_fog_pixels` pixels of fog, a mean relative error below `bound`, and a grey veil of
//! opacity 0.2, 0.4 and 0.6 in place of the fog above it (a grey overlay does not pass). Prints
//! the figures, named `label`.
inline void expect_fog_agrees(const std::string& label, const render::RadianceImage& fog,
                              const render::RadianceImage& bare, const geometry::ReferenceImage& reference,
                              int min_fog_pixels, double bound)
{
    const render::FogError e = render::compare_frames(fog, bare, reference);
    std::printf("    %s against the reference: %d fog pixels, mean error %.4f, p99 %.3f (%.1f s)\n", label.c_str(),
                e.fog_pixels, e.mean_relative, e.p99_relative, reference.seconds);
    EXPECT_GT(e.fog_pixels, min_fog_pixels);
    EXPECT_LT(e.mean_relative, bound);
    for (double opacity : {0.2, 0.4, 0.6}) {
        const render::FogError grey = render::compare_frames(grey_veil(bare, fog, opacity), bare, reference);
        std::printf("    a grey veil of opacity %.1f: mean error %.4f\n", opacity, grey.mean_relative);
        EXPECT_GT(grey.mean_relative, bound) << "a grey veil of opacity " << opacity << " passes";
    }
}

}  // namespace kiri::test
