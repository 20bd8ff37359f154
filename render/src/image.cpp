#include "kiri/render/image.hpp"

#include <stb_image.h>

#include <fstream>
#include <system_error>
#include <unistd.h>

#include "kiri/geometry/core/error.hpp"
#include "png_encode.hpp"

namespace kiri::render {

void write_png_atomic(const std::filesystem::path& path, const Image& image)
{
    if (image.width <= 0 || image.height <= 0 || image.rgba.size() != std::size_t(image.width) * image.height * 4)
        throw IoError(path.string(), "image", "empty or inconsistent image");
    // Same folder as the target so that rename() is atomic (same file system).
    std::filesystem::path tmp = path;
    tmp += ".tmp." + std::to_string(::getpid());
    const std::vector<std::uint8_t> png = detail::encode_png(image);
    bool written = false;
    if (!png.empty()) {
        std::ofstream file(tmp, std::ios::binary | std::ios::trunc);
        file.write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
        file.close();
        written = bool(file);
    }
    if (!written) {
        std::error_code ignored;
        std::filesystem::remove(tmp, ignored);
        throw IoError(path.string(), "", "cannot write the PNG (missing folder or no permission?)");
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::filesystem::remove(tmp, ec);
        throw IoError(path.string(), "", "cannot move the PNG into place: " + ec.message());
    }
}

Image read_png(const std::filesystem::path& path)
{
    int w = 0, h = 0, channels = 0;
    unsigned char* data = stbi_load(path.c_str(), &w, &h, &channels, 4);
    if (!data)
        throw InputError(path.string(), "", std::string("not a readable PNG: ") + stbi_failure_reason());
    Image image{w, h, std::vector<std::uint8_t>(data, data + std::size_t(w) * h * 4)};
    stbi_image_free(data);
    return image;
}

}  // namespace kiri::render
