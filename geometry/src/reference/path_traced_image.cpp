// The path tracer's estimates of rays and images (path_tracer.hpp): paths per pixel from streams
// of their own, their mean and standard error, and adaptive sampling by blocks.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>

#include "core/parallel_rows.hpp"
#include "kiri/geometry/reference/path_tracer.hpp"
#include "reference/path_tracer_core.hpp"

namespace kiri::geometry {
namespace {

using detail::PathTracer;
using detail::Random;

bool all_finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Welford's running mean and variance per channel; merged with an earlier estimate by Chan's
// formula, so a pixel's estimate after a later round is that of all its paths.
struct Accumulator {
    glm::dvec3 mean{0.0}, m2{0.0};
    int n = 0;
    void add(const glm::dvec3& v)
    {
        ++n;
        const glm::dvec3 d = v - mean;
        mean += d / double(n);
        m2 += d * (v - mean);
    }
    void merge(const PathEstimate& e)
    {
        if (e.samples <= 0)
            return;
        const double na = n, nb = e.samples, total = na + nb;
        const glm::dvec3 m2b = e.std_error * e.std_error * (nb * (nb - 1.0));
        const glm::dvec3 d = e.radiance - mean;
        mean += d * (nb / total);
        m2 += m2b + d * d * (na * nb / total);
        n += e.samples;
    }
    PathEstimate estimate() const
    {
        PathEstimate e;
        e.samples = n;
        e.radiance = mean;
        if (n > 1)
            e.std_error = glm::sqrt(glm::max(m2, glm::dvec3(0.0)) / (double(n - 1) * double(n)));
        return e;
    }
};

PathEstimate trace_pixel(const PathTracer& tracer, const glm::dvec3& origin, const glm::dvec3& dir, double t_max,
                         std::uint64_t seed, int samples, std::uint64_t stream, long long& vertices, long long& dropped)
{
    Random rng(seed, stream);
    Accumulator acc;
    for (int s = 0; s < samples; ++s) {
        const glm::dvec3 v = tracer.sample(origin, dir, t_max, rng, vertices);
        if (all_finite(v))
            acc.add(v);
        else
            ++dropped;
    }
    return acc.estimate();
}

// The pixels of the blocks whose mean luminance is still too noisy (PathTracerOptions::
// noise_target) and that may take more paths.
std::vector<int> noisy_pixels(const PathTracedImage& image, const PathTracerOptions& o, int max_samples)
{
    const int b = std::max(o.noise_block, 1);
    const int bw = (image.width + b - 1) / b, bh = (image.height + b - 1) / b;
    std::vector<double> sum(std::size_t(bw) * bh, 0.0), variance(sum.size(), 0.0);
    std::vector<int> count(sum.size(), 0), fewest(sum.size(), max_samples);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const std::size_t k = std::size_t(y) * image.width + x, block = std::size_t(y / b) * bw + x / b;
            sum[block] += luminance(image.radiance[k]);
            // The channels move together (one albedo and phase for all three), so the
            // luminance's error is that of the channels' weighted sum.
            const double se = luminance(image.std_error[k]);
            variance[block] += se * se;
            ++count[block];
            fewest[block] = std::min(fewest[block], image.pixel_samples[k]);
        }
    double top = 0.0;
    for (std::size_t k = 0; k < sum.size(); ++k)
        top = std::max(top, sum[k] / std::max(count[k], 1));
    std::vector<int> pixels;
    for (int by = 0; by < bh; ++by)
        for (int bx = 0; bx < bw; ++bx) {
            const std::size_t block = std::size_t(by) * bw + bx;
            const double mean = sum[block] / count[block], se = std::sqrt(variance[block]) / count[block];
            if (fewest[block] >= max_samples || !(mean > 1e-6 * top) || !(se > o.noise_target * mean))
                continue;
            for (int y = by * b; y < std::min((by + 1) * b, image.height); ++y)
                for (int x = bx * b; x < std::min((bx + 1) * b, image.width); ++x)
                    if (image.pixel_samples[std::size_t(y) * image.width + x] < max_samples)
                        pixels.push_back(y * image.width + x);
        }
    return pixels;
}

}  // namespace

PathEstimate path_traced_ray(const FogVolume& fog, const Heightfield* terrain, const glm::dvec3& origin,
                             const glm::dvec3& dir, double t_max, const FogLighting& light,
                             const PathTracerOptions& options, std::uint64_t stream)
{
    const PathTracer tracer(fog, terrain, light, options);
    long long vertices = 0, dropped = 0;
    const double len = glm::length(dir);
    const glm::dvec3 w = len > 0.0 && std::isfinite(len) ? dir / len : glm::dvec3(0.0, 0.0, -1.0);
    return trace_pixel(tracer, origin, w, t_max, options.seed, std::max(options.samples, 1), stream, vertices, dropped);
}

PathTracedImage render_path_traced(const FogVolume& fog, const Heightfield* terrain, const ReferenceView& view,
                                   const FogLighting& light, const PathTracerOptions& options)
{
    const auto start = std::chrono::steady_clock::now();
    PathTracedImage out;
    out.width = std::max(view.width, 0);
    out.height = std::max(view.height, 0);
    out.samples = std::max(options.samples, 1);
    const std::size_t n = std::size_t(out.width) * std::size_t(out.height);
    out.radiance.assign(n, glm::dvec3(0.0));
    out.std_error.assign(n, glm::dvec3(0.0));
    out.pixel_samples.assign(n, out.samples);
    const PathTracer tracer(fog, terrain, light, options);
    const glm::dvec3 forward = view.forward();
    std::atomic<long long> vertices{0}, dropped{0};
    const auto trace = [&](int k, std::uint64_t seed, int samples, long long& my_vertices, long long& my_dropped) {
        const int x = k % out.width, y = k / out.width;
        const glm::dvec3 w = view.ray(x, y);
        const double cos_axis = glm::dot(w, forward);
        const double t_max = view.max_depth > 0.0 && cos_axis > 0.0 ? view.max_depth / cos_axis : 1e6;
        return trace_pixel(tracer, view.eye, w, t_max, seed, samples, std::uint64_t(k), my_vertices, my_dropped);
    };
    detail::for_rows_in_parallel(options.threads, out.height, [&](auto next_row) {
        long long my_vertices = 0, my_dropped = 0;
        for (int y = next_row(); y < out.height; y = next_row())
            for (int x = 0; x < out.width; ++x) {
                const int k = y * out.width + x;
                const PathEstimate e = trace(k, options.seed, out.samples, my_vertices, my_dropped);
                out.radiance[k] = e.radiance;
                out.std_error[k] = e.std_error;
            }
        vertices += my_vertices;
        dropped += my_dropped;
    });
    const int max_samples = options.max_samples > 0 ? std::max(options.max_samples, out.samples) : 64 * out.samples;
    for (int round = 1; options.noise_target > 0.0 && n > 0; ++round) {
        const std::vector<int> pixels = noisy_pixels(out, options, max_samples);
        if (pixels.empty())
            break;
        // Each round its own streams: the pixel's stream under a seed no other round shares.
        const std::uint64_t seed = options.seed + std::uint64_t(round) * 0xD1B54A32D192ED03ull;
        detail::for_rows_in_parallel(options.threads, int(pixels.size()), [&](auto next_pixel) {
            long long my_vertices = 0, my_dropped = 0;
            for (int i = next_pixel(); i < int(pixels.size()); i = next_pixel()) {
                const int k = pixels[std::size_t(i)];
                const int had = out.pixel_samples[k], more = std::min(3 * had, max_samples - had);
                Accumulator acc;
                acc.merge({out.radiance[k], out.std_error[k], had});
                acc.merge(trace(k, seed, more, my_vertices, my_dropped));
                const PathEstimate e = acc.estimate();
                out.radiance[k] = e.radiance;
                out.std_error[k] = e.std_error;
                out.pixel_samples[k] = had + more;
            }
            vertices += my_vertices;
            dropped += my_dropped;
        });
        out.rounds = round + 1;
    }
    out.vertices = vertices;
    out.dropped = dropped;
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

}  // namespace kiri::geometry
