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

}  // namespace kiri::preview
