#include "kiri/geometry/scene/quality.hpp"

namespace kiri::geometry {

const char* to_string(Quality q)
{
    switch (q) {
    case Quality::low: return "low";
    case Quality::medium: return "medium";
    case Quality::high: return "high";
    default: return "ultra";
    }
}

bool parse_quality(std::string_view name, Quality& out)
{
    for (Quality q : {Quality::low, Quality::medium, Quality::high, Quality::ultra})
        if (name == to_string(q)) {
            out = q;
            return true;
        }
    return false;
}

QualityPreset quality_preset(Quality q)
{
    // Each step up roughly doubles the cost where it pays most (docs/combined.md's table):
    // froxels near the eye, then layers, then the particles' detail.
    static constexpr QualityPreset presets[] = {
        {8, 0.25, 4000, 64, 80, 45, 32, 12, 0.0},      // low: no particles
        {12, 0.5, 10000, 96, 120, 68, 48, 16, 0.4},    // medium
        {15, 0.5, 20000, 128, 160, 90, 64, 24, 0.5},   // high: the sections' defaults
        {30, 1.0, 60000, 192, 240, 135, 96, 32, 0.5},  // ultra
    };
    return presets[int(q)];
}

}  // namespace kiri::geometry
