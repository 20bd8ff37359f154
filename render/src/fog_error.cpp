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

std::vector<std::size_t> footprint_edges(const geometry::ReferenceImage& ref, double bend, double fog_bend)
{
    std::vector<std::size_t> edges;
    const auto depth = [&](int x, int y) { return ref.depth[std::size_t(y) * ref.width + x]; };
    const auto through = [&](int x, int y) { return ref.transmittance[std::size_t(y) * ref.width + x]; };
    const auto inscattered = [&](int x, int y) {
        return geometry::luminance(ref.inscatter[std::size_t(y) * ref.width + x]);
    };
    const std::size_t n = std::size_t(ref.width) * std::size_t(ref.height);
    const bool fog =
        fog_bend > 0.0 && ref.transmittance.size() == n && ref.inscatter.size() == n && ref.background.size() == n;
    const int axes[4][2] = {{1, 0}, {0, 1}, {1, 1}, {1, -1}};
    for (int y = 0; y < ref.height; ++y)
        for (int x = 0; x < ref.width; ++x) {
            const double d = depth(x, y);
            // The fog's bend: its transmittance, or its light against the pixel's own.
            const double t = fog ? through(x, y) : 0.0, s = fog ? inscattered(x, y) : 0.0;
            const double light_bend =
                fog ? fog_bend * geometry::luminance(ref.composed(std::size_t(y) * ref.width + x)) : 0.0;
            bool edge = false;
            for (const auto& a : axes) {
                const int x0 = x - a[0], y0 = y - a[1], x1 = x + a[0], y1 = y + a[1];
                const bool has0 = x0 >= 0 && y0 >= 0 && x0 < ref.width && y0 < ref.height;
                const bool has1 = x1 >= 0 && y1 >= 0 && x1 < ref.width && y1 < ref.height;
                // The sky beside the terrain, either way (a neighbour outside the image: none).
                const double before = has0 ? depth(x0, y0) : d, after = has1 ? depth(x1, y1) : d;
                edge = edge || std::isinf(d) != std::isinf(before) || std::isinf(d) != std::isinf(after);
                // The bend, along the axes whose both neighbours lie in the image.
                if (has0 && has1 && !std::isinf(d) && !std::isinf(before) && !std::isinf(after))
                    edge = edge || std::abs(before - 2.0 * d + after) > bend * d;
                if (has0 && has1 && fog)
                    edge = edge || std::abs(through(x0, y0) - 2.0 * t + through(x1, y1)) > fog_bend ||
                        std::abs(inscattered(x0, y0) - 2.0 * s + inscattered(x1, y1)) > light_bend;
            }
            if (edge)
                edges.push_back(std::size_t(y) * ref.width + x);
        }
    return edges;
}

std::vector<glm::dvec2> sample_points(const std::vector<std::size_t>& pixels, const RadianceSamples& samples)
{
    std::vector<glm::dvec2> points;
    points.reserve(pixels.size() * std::size_t(samples.samples));
    const std::size_t width = std::size_t(std::max(samples.width, 1));
    for (std::size_t k : pixels)
        for (int s = 0; s < samples.samples; ++s)
            points.emplace_back(double(k % width) + 0.5 + samples.offsets[std::size_t(2 * s)],
                                double(k / width) + 0.5 + samples.offsets[std::size_t(2 * s + 1)]);
    return points;
}

FogError compare_frames(const RadianceImage& with_fog, const RadianceImage& without_fog,
                        const geometry::ReferenceImage& ref, std::vector<float>* signed_error,
                        const RadianceImage* without_sun, const SampleReference* at_samples)
{
    const std::size_t n = std::size_t(ref.width) * std::size_t(ref.height);
    // Every frame as large as the reference, `per_pixel` RGBA values a pixel.
    const auto check = [&](int width, int height, std::size_t values, int per_pixel) {
        if (width != ref.width || height != ref.height || values != 4 * n * std::size_t(per_pixel))
            throw Error("compare_frames: a frame is " + std::to_string(width) + "x" + std::to_string(height) +
                        ", the reference " + std::to_string(ref.width) + "x" + std::to_string(ref.height));
    };
    for (const RadianceImage* image : {&with_fog, &without_fog, without_sun})
        if (image)
            check(image->width, image->height, image->rgba.size(), 1);
    if (at_samples) {
        for (const RadianceSamples* frame : {at_samples->without_fog, at_samples->without_sun})
            if (frame)
                check(frame->width, frame->height, frame->rgba.size(), frame->samples);
        if (!at_samples->without_fog ||
            at_samples->reference.transmittance.size() !=
                at_samples->pixels.size() * std::size_t(at_samples->without_fog->samples))
            throw Error("compare_frames: the reference at the samples has " +
                        std::to_string(at_samples->reference.transmittance.size()) + " rays for " +
                        std::to_string(at_samples->pixels.size()) + " pixels, or no frame without fog");
    }
    FogError e;
    std::vector<double> errors;
    if (signed_error)
        signed_error->assign(n, std::numeric_limits<float>::quiet_NaN());
    const auto luminance_at = [](const RadianceImage& image, std::size_t k) {
        const float* p = &image.rgba[4 * k];
        return geometry::luminance({p[0], p[1], p[2]});
    };
    // The reference's luminance per pixel: its centre's ray, or the mean over its samples.
    std::vector<double> y_refs(n, -1.0);
    if (at_samples) {
        const int m = at_samples->without_fog->samples;
        const auto sample_luminance = [&](const RadianceSamples& frame, std::size_t k, int s) {
            const float* p = &frame.rgba[4 * (k * std::size_t(m) + std::size_t(s))];
            return geometry::luminance({p[0], p[1], p[2]});
        };
        for (std::size_t i = 0; i < at_samples->pixels.size(); ++i) {
            const std::size_t k = at_samples->pixels[i];
            if (k >= n)
                throw Error("compare_frames: pixel " + std::to_string(k) + " of the samples outside the frame");
            double sum = 0.0;
            for (int s = 0; s < m; ++s)
                sum += reference_luminance(
                    at_samples->reference, i * std::size_t(m) + std::size_t(s),
                    sample_luminance(*at_samples->without_fog, k, s),
                    at_samples->without_sun ? sample_luminance(*at_samples->without_sun, k, s) : -1.0);
            y_refs[k] = sum / double(m);
        }
    }
    for (std::size_t k = 0; k < n; ++k) {
        const double y_bg = luminance_at(without_fog, k);
        const double y_ref = y_refs[k] >= 0.0
            ? y_refs[k]
            : reference_luminance(ref, k, y_bg, without_sun ? luminance_at(*without_sun, k) : -1.0);
        if (!(std::abs(y_ref - y_bg) > 0.01 * y_ref))
            continue;  // the fog hardly shows here
        if (!(y_ref > 0.0))
            continue;  // black in the reference (its fog's shade over more than this frame's ground): no relative error
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
