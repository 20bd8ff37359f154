#include "frame_budget.hpp"

#include <algorithm>
#include <cmath>

namespace kiri::preview {

float next_moving_scale(float scale, double measured_ms, const FrameBudget& budget)
{
    const float lo = std::isfinite(budget.min_scale) && budget.min_scale > 0.0f ? budget.min_scale : 0.125f;
    const float hi = std::isfinite(budget.max_scale) ? std::max(budget.max_scale, lo) : 1.0f;
    const float last = std::isfinite(scale) && scale > 0.0f ? std::clamp(scale, lo, hi) : hi;
    if (!(std::isfinite(measured_ms) && measured_ms > 0.0 && std::isfinite(budget.target_ms) && budget.target_ms > 0.0))
        return last;
    const double step = std::clamp(std::sqrt(budget.target_ms / measured_ms), 0.7, 1.25);
    return std::clamp(float(last * step), lo, hi);
}

double resolution_step(float ratio)
{
    if (!(std::isfinite(ratio) && ratio > 0.0f))
        return 0.125;
    double r = 1.0;
    while (r > 0.125 && r > double(ratio) * (1.0 + 1e-6))
        r *= 0.5;
    return r;
}

int off_power_of_two(int side)
{
    const auto power_of_two = [](int v) { return v >= 2 && (v & (v - 1)) == 0; };
    const auto clashes = [&](int v) {
        for (int k = 1; k <= 16; k *= 2)
            if (power_of_two((v + k - 1) / k))
                return true;
        return false;
    };
    if (side < 2 || side > (1 << 24))  // no texture is that large; no overflow below
        return side;
    while (clashes(side))
        ++side;
    return side;
}

}  // namespace kiri::preview
