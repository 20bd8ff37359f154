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

}  // namespace kiri::render
