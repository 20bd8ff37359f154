// The only file of kiri that includes OpenVDB (a heavy header set): medium_vdb.hpp.
#include "kiri/geometry/volume/medium_vdb.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>
#include <vector>

#include <openvdb/openvdb.h>

#include "kiri/geometry/core/error.hpp"

namespace kiri::geometry {
namespace {

void initialise_openvdb()
{
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
}

// Mean thickness of the fog, weighted by coverage.
double mean_thickness(const Medium& m)
{
    const MediumGrid& g = m.grid();
    double sum = 0.0, weight = 0.0;
    for (std::size_t k = 0; k < g.coverage.size(); ++k)
        if (g.coverage[k] > 0.0 && g.top[k] > g.floor[k]) {
            sum += g.coverage[k] * (g.top[k] - g.floor[k]);
            weight += g.coverage[k];
        }
    return weight > 0.0 ? sum / weight : 0.0;
}

}  // namespace

double vdb_voxel_size(const Medium& m, const VdbExportOptions& o)
{
    if (o.voxel_size > 0.0)
        return o.voxel_size;
    const MediumGrid& g = m.grid();
    double voxel = std::min(g.dx, g.dy);
    const double thick = mean_thickness(m);
    if (thick > 0.0)
        voxel = std::min(voxel, thick / 8.0);
    // Coarser where the shell would hold too many voxels.
    const double volume = m.shell_volume();
    if (volume > 0.0)
        voxel = std::max(voxel, std::cbrt(volume / double(std::max(o.max_voxels, 1LL)) * 1.5));
    return std::max(voxel, 1e-3);
}

VdbExportReport write_medium_vdb(const Medium& m, const std::filesystem::path& path, const VdbExportOptions& o)
{
    const auto start = std::chrono::steady_clock::now();
    initialise_openvdb();
    VdbExportReport report;
    const double v = vdb_voxel_size(m, o);
    report.voxel_size = v;
    const double estimate = m.shell_volume() / (v * v * v);
    if (estimate > double(o.max_voxels))
        throw LimitError(path.string(), "voxel_size",
                         "the grid would hold about " + std::to_string(std::llround(estimate)) + " voxels (limit " +
                             std::to_string(o.max_voxels) + ")");
    openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(v));
    grid->setName("density");
    grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    auto accessor = grid->getAccessor();
    const Bounds3& b = m.bounds();
    const int i0 = int(std::floor(b.min.x / v)), i1 = int(std::ceil(b.max.x / v));
    const int j0 = int(std::floor(b.min.y / v)), j1 = int(std::ceil(b.max.y / v));
    // OpenVDB's convention: voxel (i, j, k)'s value sits at the transform of (i, j, k), here
    // (i v, j v, k v), and a trilinear sampler reads the value at a world point from the eight
    // voxels around it. Each voxel holds the mean of the Medium over its cell [index +- 1/2]:
    // 2 x 2 samples across and 2 along z (the profile is linear in z), 8 along z in the voxels a
    // face of the shell crosses.
    const double q = 0.25 * v;
    std::vector<double> column;
    for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) {
            // Only the heights where the columns around this one hold fog.
            double lo = 1e300, hi = -1e300;
            for (int c = 0; c < 4; ++c) {
                const MediumColumn col = m.column(i * v + ((c & 1) ? q : -q), j * v + ((c & 2) ? q : -q));
                if (col.coverage > 0.0 && col.top > col.floor) {
                    lo = std::min(lo, col.floor);
                    hi = std::max(hi, col.top);
                }
            }
            if (hi < lo)
                continue;
            const MediumColumn centre = m.column(i * v, j * v);
            const int k0 = int(std::floor(lo / v)), k1 = int(std::ceil(hi / v));
            column.assign(std::size_t(k1 - k0 + 1), 0.0);
            for (int k = k0; k <= k1; ++k) {
                const double z = k * v;
                const bool face = std::abs(z - centre.floor) < v || std::abs(z - centre.top) < v;
                const int nz = face ? 8 : 2;
                double sum = 0.0;
                for (int s = 0; s < 4 * nz; ++s)
                    sum += m.extinction(
                        {i * v + ((s & 1) ? q : -q), j * v + ((s & 2) ? q : -q), z + ((s / 4 + 0.5) / nz - 0.5) * v});
                column[std::size_t(k - k0)] = sum / (4 * nz);
            }
            // The fog ends at the floor (the ground): voxels centred below it hold none, and
            // what their cells held above the floor moves to the lowest voxel centred at or
            // above it, so the column keeps its optical depth. (A trilinear read still spreads
            // that voxel down to the one under it: at most about half a voxel's worth of fog
            // lies below the floor, where the terrain hides it.)
            const int kf = std::clamp(int(std::ceil(centre.floor / v)), k0, k1);
            for (int k = k0; k < kf; ++k) {
                column[std::size_t(kf - k0)] += column[std::size_t(k - k0)];
                column[std::size_t(k - k0)] = 0.0;
            }
            for (int k = k0; k <= k1; ++k)
                if (const double value = column[std::size_t(k - k0)]; value > 0.0)
                    accessor.setValue(openvdb::Coord(i, j, k), float(value));
        }
    grid->insertMeta("extinction_at_density_1", openvdb::DoubleMetadata(m.options().extinction));
    grid->insertMeta("albedo", openvdb::DoubleMetadata(m.options().albedo));
    grid->insertMeta("anisotropy", openvdb::DoubleMetadata(m.options().anisotropy));
    grid->insertMeta("units", openvdb::StringMetadata("world: metres (x east, y north, z up); density: 1/m"));
    grid->insertMeta("creator", openvdb::StringMetadata("kiri"));
    report.active_voxels = std::size_t(grid->activeVoxelCount());
    try {
        openvdb::io::File file(path.string());
        file.write({grid});
        file.close();
    } catch (const openvdb::Exception& e) {
        throw IoError(path.string(), "", std::string("cannot write the OpenVDB file: ") + e.what());
    }
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return report;
}

}  // namespace kiri::geometry
