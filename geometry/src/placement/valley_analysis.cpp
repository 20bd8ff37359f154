#include "kiri/geometry/placement/valley_analysis.hpp"

#include <algorithm>
#include <cmath>

#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/fog/fog_target.hpp"

namespace kiri::geometry {

ValleyMap analyse_valleys(const Heightfield& hf, const ValleyOptions& o, const std::string& label)
{
    if (!std::isfinite(o.threshold))
        throw InputError(label, "valleys/threshold", "must be a finite number");
    ValleyMap out;
    out.nx = hf.nx;
    out.ny = hf.ny;
    out.radii = o.radii;
    if (out.radii.empty()) {
        const double cell = std::max(hf.dx, hf.dy);
        const double cap = 0.25 * std::min(hf.x_max() - hf.x0, hf.y_max() - hf.y0);
        for (double cells : {4.0, 16.0, 64.0})
            out.radii.push_back(std::max(cell, std::min(cells * cell, cap)));
    }
    for (std::size_t k = 0; k < out.radii.size(); ++k)
        if (!(out.radii[k] > 0.0) || !std::isfinite(out.radii[k]))
            throw InputError(label, "valleys/radii/" + std::to_string(k), "must be a finite number of metres > 0");

    const std::size_t n = hf.size();
    const bool masked = hf.valid.size() == n;
    out.index.assign(n, 0.0);
    for (double r : out.radii) {
        const Heightfield mean = smooth_heightfield(hf, r);
        std::vector<double> tpi(n);
        double sum2 = 0.0;
        std::size_t count = 0;
        for (std::size_t k = 0; k < n; ++k) {
            tpi[k] = hf.z[k] - mean.z[k];
            if (!masked || hf.valid[k]) {
                sum2 += tpi[k] * tpi[k];
                ++count;
            }
        }
        // The TPI's mean over the terrain is ~0 by construction: its RMS is its deviation.
        const double sd = count ? std::sqrt(sum2 / double(count)) : 0.0;
        if (sd > 0.0)
            for (std::size_t k = 0; k < n; ++k)
                out.index[k] -= tpi[k] / sd / double(out.radii.size());
    }
    out.mask.assign(n, 0);
    for (std::size_t k = 0; k < n; ++k) {
        if (masked && !hf.valid[k]) {
            out.index[k] = 0.0;
            continue;
        }
        out.mask[k] = out.index[k] > o.threshold;
        out.cells += out.mask[k];
    }
    return out;
}

}  // namespace kiri::geometry
