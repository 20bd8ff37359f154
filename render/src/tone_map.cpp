#include "kiri/render/tone_map.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "kiri/geometry/core/error.hpp"

namespace kiri::render {

double tone_map(double radiance)
{
    return std::pow(1.0 - std::exp(-std::max(radiance, 0.0) * display_exposure), 1.0 / 2.2);
}

std::uint8_t tone_map_level(double radiance) { return std::uint8_t(std::lround(255.0 * tone_map(radiance))); }

double level_radiance(double level)
{
    const double display = std::clamp(level, 0.0, 254.5) / 255.0;
    return -std::log(1.0 - std::pow(display, 2.2)) / display_exposure;
}

RadianceImage radiance_at(const Image& picture, int width, int height)
{
    const int scale = width > 0 ? picture.width / width : 0;
    if (scale < 1 || picture.width != scale * width || picture.height != scale * height)
        throw Error("radiance_at: a " + std::to_string(picture.width) + "x" + std::to_string(picture.height) +
                    " picture is no whole multiple of " + std::to_string(width) + "x" + std::to_string(height));
    RadianceImage r{width, height, std::vector<float>(std::size_t(width) * height * 4, 1.0f)};
    // The centre of pixel x of the small image lies at scale (x + 1/2) in the picture: a pixel's
    // centre when the scale is odd, the corner of four pixels when it is even.
    const int lo = scale % 2 == 1 ? 0 : -1;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < 3; ++c) {
                double sum = 0.0;
                int n = 0;
                for (int dy = lo; dy <= 0; ++dy)
                    for (int dx = lo; dx <= 0; ++dx, ++n) {
                        const int px = x * scale + scale / 2 + dx, py = y * scale + scale / 2 + dy;
                        sum += level_radiance(picture.rgba[(std::size_t(py) * picture.width + px) * 4 + c]);
                    }
                r.rgba[(std::size_t(y) * width + x) * 4 + c] = float(sum / n);
            }
    return r;
}

Image tone_mapped(const geometry::ReferenceImage& r)
{
    Image image{r.width, r.height, std::vector<std::uint8_t>(std::size_t(r.width) * r.height * 4, 255)};
    for (std::size_t k = 0; k < r.inscatter.size(); ++k) {
        const glm::dvec3 c = r.composed(k);
        for (int ch = 0; ch < 3; ++ch)
            image.rgba[4 * k + std::size_t(ch)] = tone_map_level(c[ch]);
    }
    return image;
}

Image tone_mapped(const geometry::PathTracedImage& p)
{
    Image image{p.width, p.height, std::vector<std::uint8_t>(std::size_t(p.width) * p.height * 4, 255)};
    for (std::size_t k = 0; k < p.radiance.size(); ++k)
        for (int ch = 0; ch < 3; ++ch)
            image.rgba[4 * k + std::size_t(ch)] = tone_map_level(p.radiance[k][ch]);
    return image;
}

namespace {

RadianceImage linear_image(int width, int height, std::size_t n, auto&& radiance)
{
    RadianceImage image{width, height, std::vector<float>(n * 4, 1.0f)};
    for (std::size_t k = 0; k < n; ++k) {
        const glm::dvec3 c = radiance(k);
        for (int ch = 0; ch < 3; ++ch)
            image.rgba[4 * k + std::size_t(ch)] = float(c[ch]);
    }
    return image;
}

}  // namespace

RadianceImage linear_radiance(const geometry::ReferenceImage& r)
{
    return linear_image(r.width, r.height, r.inscatter.size(), [&](std::size_t k) { return r.composed(k); });
}

RadianceImage linear_radiance(const geometry::PathTracedImage& p)
{
    return linear_image(p.width, p.height, p.radiance.size(), [&](std::size_t k) { return p.radiance[k]; });
}

}  // namespace kiri::render
