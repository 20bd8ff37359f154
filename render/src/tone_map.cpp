#include "kiri/render/tone_map.hpp"

#include <algorithm>
#include <cmath>

namespace kiri::render {

double tone_map(double radiance)
{
    return std::pow(1.0 - std::exp(-std::max(radiance, 0.0) * display_exposure), 1.0 / 2.2);
}

std::uint8_t tone_map_level(double radiance) { return std::uint8_t(std::lround(255.0 * tone_map(radiance))); }

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
