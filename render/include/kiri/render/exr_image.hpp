#pragma once
//! \file exr_image.hpp
//! Linear radiance as OpenEXR (32-bit float R, G, B, A; rows top to bottom as in RadianceImage):
//! what `kiri render -o frame.exr` writes for every mode, before the tone map, so other tools
//! (Blender, the Cycles cross-check) compare radiance, not display values.
#include <filesystem>

#include "kiri/render/image.hpp"

namespace kiri::render {

//! Writes to a temporary file beside path, then renames it: no partial file is ever left.
//! \throw kiri::IoError naming the path when it cannot be written.
void write_exr_atomic(const std::filesystem::path& path, const RadianceImage& image);
//! Reads R, G, B and A (1 where the file has no alpha) of an OpenEXR file's data window.
//! \throw kiri::InputError naming the path when it is not a readable OpenEXR file.
RadianceImage read_exr(const std::filesystem::path& path);
//! Whether `path` names an OpenEXR file (its extension is .exr, in any case).
bool is_exr_path(const std::filesystem::path& path);
//! Whether `path` names a PNG file (its extension is .png, in any case).
bool is_png_path(const std::filesystem::path& path);

}  // namespace kiri::render
