#include "particles/shell_envelope.hpp"

#include <algorithm>
#include <cmath>

namespace kiri::geometry::detail {

ShellEnvelope::ShellEnvelope(const Medium& medium, double from, double share_max,
                             const std::function<double(double)>& by_thickness)
{
    const MediumGrid& g = medium.grid();
    if (!(share_max > 0.0) || g.nx < 2 || g.ny < 2)
        return;
    from = std::clamp(std::isfinite(from) ? from : 0.0, 0.0, 1.0);
    dx_ = g.dx;
    dy_ = g.dy;
    // The profile 1 - (1 - top_density) h at h >= from: largest at one end.
    const double top_density = medium.options().top_density;
    const double profile = std::max(1.0 - (1.0 - top_density) * from, top_density);
    double sum = 0.0;
    for (int j = 0; j + 1 < g.ny; ++j)
        for (int i = 0; i + 1 < g.nx; ++i) {
            const std::size_t corner[4] = {std::size_t(j) * g.nx + i, std::size_t(j) * g.nx + i + 1,
                                           std::size_t(j + 1) * g.nx + i, std::size_t(j + 1) * g.nx + i + 1};
            double coverage = 0.0, floor_low = HUGE_VAL, band_low = HUGE_VAL, top = -HUGE_VAL, thickest = -HUGE_VAL;
            for (std::size_t k : corner) {
                coverage = std::max(coverage, g.coverage[k]);
                thickest = std::max(thickest, g.top[k] - g.floor[k]);
                floor_low = std::min(floor_low, g.floor[k]);
                band_low = std::min(band_low, g.bottom[k] + from * (g.top[k] - g.bottom[k]));
                top = std::max(top, g.top[k]);
            }
            // No point of the cell lies below its lowest floor or its band's lowest bottom.
            const double z_low = std::max(floor_low, band_low);
            const double bound =
                std::min(coverage, 1.0) * profile * share_max * (by_thickness ? by_thickness(thickest) : 1.0);
            const double height = top - z_low;
            if (!(bound > 0.0) || !(height > 0.0) || !std::isfinite(height))
                continue;
            cells_.push_back({g.x0 + i * g.dx, g.y0 + j * g.dy, z_low, height, bound});
            sum += g.dx * g.dy * height * bound;
            cumulative_.push_back(sum);
        }
}

ShellEnvelope::Proposal ShellEnvelope::draw(std::mt19937_64& rng) const
{
    // A cell in proportion to its integral, then uniform in its box.
    const double u = uniform(rng) * cumulative_.back();
    const std::size_t c = std::min<std::size_t>(
        std::size_t(std::upper_bound(cumulative_.begin(), cumulative_.end(), u) - cumulative_.begin()),
        cells_.size() - 1);
    const Cell& cell = cells_[c];
    const double x = cell.x + dx_ * uniform(rng), y = cell.y + dy_ * uniform(rng);
    return {{x, y, cell.z_low + cell.height * uniform(rng)}, cell.bound};
}

}  // namespace kiri::geometry::detail
