#pragma once
// Files the preview writes: the edited scene (JSON that loads back) and screenshots (PNG),
// each under a temporary name renamed into place.
#include <filesystem>
#include <string>

#include "kiri/geometry/scene/scene.hpp"

namespace kiri::preview {

//! Writes `scene` to `out`; the terrain path is written relative to out's folder (absolute
//! when there is no relative path, another drive say). The text is parsed back before it
//! replaces anything. \throw kiri::IoError / InputError naming the file.
void save_scene(const geometry::Scene& scene, const std::filesystem::path& out);

//! `<folder>/<stem>-preview-<n>.png` with the first n not taken.
std::filesystem::path next_screenshot_path(const std::filesystem::path& folder, const std::string& stem);

}  // namespace kiri::preview
