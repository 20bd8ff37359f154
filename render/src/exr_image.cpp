// The only file of kiri that includes OpenEXR: exr_image.hpp.
#include "kiri/render/exr_image.hpp"

#include <algorithm>
#include <cctype>
#include <string>
#include <system_error>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <unistd.h>

#include "kiri/geometry/core/error.hpp"

namespace kiri::render {
namespace {

constexpr const char* channels[4] = {"R", "G", "B", "A"};

}  // namespace

namespace {

std::string lower_extension(const std::filesystem::path& path)
{
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

}  // namespace

bool is_exr_path(const std::filesystem::path& path) { return lower_extension(path) == ".exr"; }

bool is_png_path(const std::filesystem::path& path) { return lower_extension(path) == ".png"; }

void write_exr_atomic(const std::filesystem::path& path, const RadianceImage& image)
{
    if (image.width <= 0 || image.height <= 0 || image.rgba.size() != std::size_t(image.width) * image.height * 4)
        throw IoError(path.string(), "image", "empty or inconsistent image");
    // Same folder as the target so that rename() is atomic (same file system).
    std::filesystem::path tmp = path;
    tmp += ".tmp." + std::to_string(::getpid());
    try {
        Imf::Header header(image.width, image.height);
        header.compression() = Imf::ZIP_COMPRESSION;
        Imf::FrameBuffer frame;
        const std::size_t x_stride = 4 * sizeof(float), y_stride = x_stride * std::size_t(image.width);
        for (int c = 0; c < 4; ++c) {
            header.channels().insert(channels[c], Imf::Channel(Imf::FLOAT));
            // OpenEXR takes a non-const base pointer; it only reads through it when writing.
            char* base = reinterpret_cast<char*>(const_cast<float*>(image.rgba.data() + c));
            frame.insert(channels[c], Imf::Slice(Imf::FLOAT, base, x_stride, y_stride));
        }
        Imf::OutputFile file(tmp.c_str(), header);
        file.setFrameBuffer(frame);
        file.writePixels(image.height);
    } catch (const std::exception& e) {
        std::error_code ignored;
        std::filesystem::remove(tmp, ignored);
        throw IoError(path.string(), "", std::string("cannot write the OpenEXR file: ") + e.what());
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::filesystem::remove(tmp, ec);
        throw IoError(path.string(), "", "cannot move the OpenEXR file into place: " + ec.message());
    }
}

RadianceImage read_exr(const std::filesystem::path& path)
{
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i window = file.header().dataWindow();
        RadianceImage image;
        image.width = window.max.x - window.min.x + 1;
        image.height = window.max.y - window.min.y + 1;
        if (image.width <= 0 || image.height <= 0)
            throw InputError(path.string(), "", "an empty OpenEXR image");
        image.rgba.assign(std::size_t(image.width) * std::size_t(image.height) * 4, 0.0f);
        const std::size_t x_stride = 4 * sizeof(float), y_stride = x_stride * std::size_t(image.width);
        // The slices' base points at pixel (0, 0) of the file's coordinates.
        const std::ptrdiff_t origin = -(std::ptrdiff_t(window.min.x) * std::ptrdiff_t(x_stride) +
                                        std::ptrdiff_t(window.min.y) * std::ptrdiff_t(y_stride));
        Imf::FrameBuffer frame;
        for (int c = 0; c < 4; ++c) {
            char* base = reinterpret_cast<char*>(image.rgba.data() + c) + origin;
            frame.insert(channels[c], Imf::Slice(Imf::FLOAT, base, x_stride, y_stride, 1, 1, c == 3 ? 1.0 : 0.0));
        }
        file.setFrameBuffer(frame);
        file.readPixels(window.min.y, window.max.y);
        return image;
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        throw InputError(path.string(), "", std::string("not a readable OpenEXR file: ") + e.what());
    }
}

}  // namespace kiri::render
