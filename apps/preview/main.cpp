// kiri-preview SCENE.json (or DEM): the interactive preview (docs/preview.md). Exit codes: 0, or 2 with
// one line on stderr (bad arguments, bad scene, no display, no OpenGL 4.5).
#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>

#include "kiri/render/exr_image.hpp"
#include "preview_app.hpp"

int main(int argc, char** argv)
{
    using kiri::preview::Args;
    CLI::App app{"kiri-preview: interactive preview of a kiri scene (docs/preview.md)"};
    Args args;
    app.add_option("scene", args.scene, "scene file (JSON), or a DEM (a valley fog, every other key derived)")
        ->required();
    app.add_option("--width", args.width, "window width (screen units)")->check(CLI::Range(64, 16384));
    app.add_option("--height", args.height, "window height (screen units)")->check(CLI::Range(64, 16384));
    app.add_option("--camera", args.camera, "scene camera to start from (default: its first)");
    app.add_flag("--no-fog", args.no_fog, "start with the fog hidden");
    app.add_option("--mode", args.mode,
                   "how the fog is drawn at the start (M cycles): layers, particles, froxel, combined; auto "
                   "(default): combined, as kiri render")
        ->check(CLI::IsMember({"auto", "layers", "particles", "froxel", "combined"}));
    app.add_option("--view", args.views, "start with a view on (repeatable)")
        ->check(CLI::IsMember({"surface", "deviation", "clearance", "triangles", "patches", "control"}));
    app.add_option("--frames", args.frames, "scripted mode: frames to draw, then write --screenshot and exit")
        ->check(CLI::Range(1, 100000));
    app.add_option("--screenshot", args.screenshot, "scripted mode: the PNG written after the last frame");
    app.add_option("--save", args.save, "scripted mode: also save the scene (JSON) after the last frame");
    app.add_option("--camera-path", args.camera_path, "scripted mode: key views 'px py pz tx ty tz [fov]' per line");
    app.add_flag("--moving", args.moving,
                 "scripted mode: draw the camera path's frames as a moving view (dynamic resolution), the last "
                 "as the still");
    app.add_option("--moving-fps", args.moving_fps,
                   "the frame rate a moving view keeps by lowering its resolution (default 10)")
        ->check(CLI::Range(0.1, 1000.0));
    app.add_flag("--no-ui", args.no_ui, "hide the panel and the timings (H and T toggle them)");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0)
            return app.exit(e);
        std::fprintf(stderr, "kiri-preview: %s (see kiri-preview --help)\n", e.what());
        return 2;
    }
    if (args.scripted() != !args.screenshot.empty()) {
        std::fprintf(stderr, "kiri-preview: --frames and --screenshot go together\n");
        return 2;
    }
    if (!args.screenshot.empty() && !kiri::render::is_png_path(args.screenshot)) {
        std::fprintf(stderr, "kiri-preview: %s: --screenshot writes a PNG: name it .png\n", args.screenshot.c_str());
        return 2;
    }
    if (!args.scripted() && (!args.save.empty() || !args.camera_path.empty() || args.moving)) {
        std::fprintf(stderr, "kiri-preview: --save, --camera-path and --moving need --frames and --screenshot\n");
        return 2;
    }
    try {
        kiri::preview::PreviewApp preview(args);
        return preview.run();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "kiri-preview: %s\n", e.what());
        return 2;
    }
}
