#include <algorithm>
#include <cmath>

#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/volume/froxel_options.hpp"

namespace kiri::geometry {
namespace {
// Exponential slicing needs a > 0: a millimetre is far closer than any froxel volume starts.
constexpr double min_near = 1e-3;
}  // namespace

double slice_depth(const FroxelOptions& o, double s, double a, double b)
{
    s = std::clamp(std::isfinite(s) ? s : 0.0, 0.0, 1.0);
    if (!(b > a))
        return a;
    switch (o.distribution) {
    case SliceDistribution::exponential: {
        const double lo = std::max(a, min_near);
        return b > lo ? lo * std::pow(b / lo, s) : a + (b - a) * s;
    }
    case SliceDistribution::log2: {
        const double c = o.log2_scale;
        return a + c * std::expm1(s * std::log1p((b - a) / c));
    }
    case SliceDistribution::power: return a + (b - a) * std::pow(s, o.power);
    }
    return a + (b - a) * s;
}

double slice_coordinate(const FroxelOptions& o, double d, double a, double b)
{
    if (!(b > a) || !(d > a))
        return 0.0;
    if (d >= b)
        return 1.0;
    switch (o.distribution) {
    case SliceDistribution::exponential: {
        const double lo = std::max(a, min_near);
        if (!(b > lo))
            return (d - a) / (b - a);
        return std::clamp(std::log(std::max(d, lo) / lo) / std::log(b / lo), 0.0, 1.0);
    }
    case SliceDistribution::log2: {
        const double c = o.log2_scale;
        return std::clamp(std::log1p((d - a) / c) / std::log1p((b - a) / c), 0.0, 1.0);
    }
    case SliceDistribution::power: return std::clamp(std::pow((d - a) / (b - a), 1.0 / o.power), 0.0, 1.0);
    }
    return (d - a) / (b - a);
}

const char* to_string(SliceDistribution d)
{
    switch (d) {
    case SliceDistribution::exponential: return "exponential";
    case SliceDistribution::log2: return "log2";
    case SliceDistribution::power: return "power";
    }
    return "exponential";
}

bool parse_slice_distribution(const std::string& name, SliceDistribution& out)
{
    for (SliceDistribution d : {SliceDistribution::exponential, SliceDistribution::log2, SliceDistribution::power})
        if (name == to_string(d)) {
            out = d;
            return true;
        }
    return false;
}

void validate_froxel_options(const FroxelOptions& o, const std::string& label)
{
    check_fields(o, label, "/froxel");
    if (o.far > 0.0 && o.far <= o.near)
        throw InputError(label, "/froxel/" + std::string(field_of(o, o.far).key),
                         "must be 0 (the scene's far side) or larger than near");
    validate_height_fog(o.height_fog, label);
}

}  // namespace kiri::geometry
