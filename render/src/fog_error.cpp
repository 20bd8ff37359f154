#include "kiri/render/fog_error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "kiri/geometry/core/error.hpp"

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

double reference_luminance(const geometry::ReferenceImage& ref, std::size_t k, double y_without_fog,
                           double y_without_sun)
{
    // The ground under the fog lies in its shade: of the sun's part of the frame without fog
    // (it less the frame without the sun either) the reference's fog lets ground_sun through;
    // without that frame, the sunlight the reference's shade takes is taken from it.
    double y_shaded = y_without_fog;
    if (y_without_sun >= 0.0 && k < ref.ground_sun.size())
        y_shaded = y_without_sun + ref.ground_sun[k] * std::max(y_without_fog - y_without_sun, 0.0);
    else if (k < ref.fog_shade.size())
        y_shaded = std::max(y_without_fog - geometry::luminance(ref.fog_shade[k]), 0.0);
    return y_shaded * ref.transmittance[k] + geometry::luminance(ref.inscatter[k]);
}

FogError compare_frames(const RadianceImage& with_fog, const RadianceImage& without_fog,
                        const geometry::ReferenceImage& ref, std::vector<float>* signed_error,
                        const RadianceImage* without_sun)
{
    const std::size_t n = std::size_t(ref.width) * std::size_t(ref.height);
    for (const RadianceImage* image : {&with_fog, &without_fog, without_sun})
        if (image && (image->width != ref.width || image->height != ref.height || image->rgba.size() != 4 * n))
            throw Error("compare_frames: a frame is " + std::to_string(image->width) + "x" +
                        std::to_string(image->height) + ", the reference " + std::to_string(ref.width) + "x" +
                        std::to_string(ref.height));
    FogError e;
    std::vector<double> errors;
    if (signed_error)
        signed_error->assign(n, std::numeric_limits<float>::quiet_NaN());
    const auto luminance_at = [](const RadianceImage& image, std::size_t k) {
        const float* p = &image.rgba[4 * k];
        return geometry::luminance({p[0], p[1], p[2]});
    };
    for (std::size_t k = 0; k < n; ++k) {
        const double y_bg = luminance_at(without_fog, k);
        const double y_ref = reference_luminance(ref, k, y_bg, without_sun ? luminance_at(*without_sun, k) : -1.0);
        if (!(std::abs(y_ref - y_bg) > 0.01 * y_ref))
            continue;  // the fog hardly shows here
        const double y_gpu = luminance_at(with_fog, k);
        errors.push_back(std::abs(y_gpu - y_ref) / y_ref);
        if (signed_error)
            (*signed_error)[k] = float((y_gpu - y_ref) / y_ref);
    }
    e.fog_pixels = int(errors.size());
    if (errors.empty())
        return e;
    double sum = 0.0;
    for (double x : errors)
        sum += x;
    e.mean_relative = sum / double(errors.size());
    std::sort(errors.begin(), errors.end());
    e.p99_relative = errors[std::min(errors.size() - 1, std::size_t(std::floor(0.99 * double(errors.size()))))];
    e.worst_relative = errors.back();
    return e;
}

Image error_map(const std::vector<float>& signed_error, int width, int height, double full_scale)
{
    if (signed_error.size() != std::size_t(width) * std::size_t(height))
        throw Error("error_map: " + std::to_string(signed_error.size()) + " values for " + std::to_string(width) + "x" +
                    std::to_string(height));
    Image map;
    map.width = width;
    map.height = height;
    map.rgba.resize(4 * signed_error.size());
    for (std::size_t k = 0; k < signed_error.size(); ++k) {
        std::uint8_t* px = &map.rgba[4 * k];
        const float d = signed_error[k];
        if (std::isnan(d)) {
            px[0] = px[1] = px[2] = 128;
        } else {
            const double t = std::clamp(double(d) / full_scale, -1.0, 1.0);
            const auto fade = std::uint8_t(std::lround(255.0 * (1.0 - std::abs(t))));
            px[0] = t > 0 ? 255 : fade;
            px[1] = fade;
            px[2] = t < 0 ? 255 : fade;
        }
        px[3] = 255;
    }
    return map;
}

}  // namespace kiri::render
