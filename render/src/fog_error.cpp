#include "kiri/render/fog_error.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "kiri/geometry/error.hpp"

namespace kiri::render {

FogError compare_fog(const FogBuffer& gpu, const geometry::ReferenceImage& ref, double min_depth, double max_depth)
{
    if (gpu.width != ref.width || gpu.height != ref.height ||
        gpu.rgba.size() != std::size_t(ref.width) * ref.height * 4 || gpu.depth.size() != ref.depth.size())
        throw Error("compare_fog: the fog buffer is " + std::to_string(gpu.width) + "x" + std::to_string(gpu.height) +
                    ", the reference " + std::to_string(ref.width) + "x" + std::to_string(ref.height));
    FogError e;
    std::vector<double> errors;
    double transmittance = 0.0, inscatter = 0.0;
    for (std::size_t k = 0; k < ref.depth.size(); ++k) {
        if (!(ref.depth[k] >= min_depth && ref.depth[k] <= max_depth))
            continue;
        const double y_bg = geometry::luminance(ref.background[k]);
        const double y_ref = geometry::luminance(ref.composed(k));
        if (!(std::abs(y_ref - y_bg) > 0.01 * y_ref))
            continue;  // the fog hardly shows here
        const bool sky_ref = std::isinf(ref.depth[k]), sky_gpu = gpu.depth[k] < 0.0f;
        if (sky_ref != sky_gpu || (!sky_ref && std::abs(gpu.depth[k] - ref.depth[k]) > 0.01 * ref.depth[k])) {
            ++e.silhouette_pixels;
            continue;
        }
        const float* f = &gpu.rgba[4 * k];
        const double y_gpu = y_bg * f[3] + geometry::luminance({f[0], f[1], f[2]});
        errors.push_back(std::abs(y_gpu - y_ref) / y_ref);
        transmittance += std::abs(f[3] - ref.transmittance[k]);
        const double in_ref = geometry::luminance(ref.inscatter[k]);
        inscatter += std::abs(geometry::luminance({f[0], f[1], f[2]}) - in_ref) / std::max(in_ref, 1e-12);
    }
    e.fog_pixels = int(errors.size());
    if (errors.empty())
        return e;
    double sum = 0.0;
    for (double x : errors)
        sum += x;
    e.mean_relative = sum / double(errors.size());
    e.mean_transmittance_error = transmittance / double(errors.size());
    e.mean_inscatter_relative = inscatter / double(errors.size());
    std::sort(errors.begin(), errors.end());
    e.p99_relative = errors[std::min(errors.size() - 1, std::size_t(std::floor(0.99 * double(errors.size()))))];
    e.worst_relative = errors.back();
    return e;
}

}  // namespace kiri::render
