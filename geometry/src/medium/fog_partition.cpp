#include "kiri/geometry/medium/fog_partition.hpp"

#include <algorithm>
#include <cmath>

#include "kiri/geometry/core/error.hpp"

namespace kiri::geometry {

double smoother_step(double a, double b, double x)
{
    if (!(b > a))
        return x >= a ? 1.0 : 0.0;
    const double t = std::clamp((x - a) / (b - a), 0.0, 1.0);
    return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}

double far_share(const FogPartition& p, double distance)
{
    return smoother_step(p.near_start, p.near_end, std::isfinite(distance) ? distance : p.near_end);
}

ParticleDepthRange particle_depth_range(const FogPartition& p)
{
    const double full = p.particle_depth * p.particle_radius;
    if (!(full > 0.0) || !std::isfinite(full))
        return {};
    return {full / 3.0, full};
}

double particle_depth_share(const FogPartition& p, double thickness)
{
    const ParticleDepthRange range = particle_depth_range(p);
    if (!(range.full > 0.0))
        return 1.0;
    return smoother_step(range.start, range.full, std::isnan(thickness) ? 0.0 : thickness);
}

double particle_share(const FogPartition& p, double h, double thickness)
{
    if (!(p.particle_share > 0.0))
        return 0.0;
    const double band_start = 1.0 - p.particle_band;
    return p.particle_share * smoother_step(band_start, 1.0, std::isfinite(h) ? h : 0.0) *
        particle_depth_share(p, thickness);
}

FogShares fog_shares(const FogPartition& p, double distance, double h, double thickness)
{
    FogShares s;
    s.particles = particle_share(p, h, thickness);
    const double far = far_share(p, distance);
    s.layers = (1.0 - s.particles) * far;
    s.froxels = (1.0 - s.particles) * (1.0 - far);
    return s;
}

void validate_fog_partition(const FogPartition& p, const std::string& label) { check_fields(p, label, "/combined"); }

}  // namespace kiri::geometry
