#pragma once
// A camera path for the scripted mode: a text file of key views, one per line,
//     px py pz  tx ty tz  [fov]
// (eye, target in local metres, vertical field of view in degrees, default 45); blank lines
// and lines starting with '#' are skipped. Frame i of N sees the path at i / (N - 1),
// interpolated linearly between key views spread evenly over [0, 1].
#include <filesystem>
#include <vector>

#include "kiri/render/camera.hpp"

namespace kiri::preview {

//! \throw kiri::InputError(file, "line N", reason) on a malformed line or an empty path.
std::vector<render::Camera> load_camera_path(const std::filesystem::path& file);
//! t in [0, 1] (clamped).
render::Camera camera_on_path(const std::vector<render::Camera>& keys, double t);

}  // namespace kiri::preview
