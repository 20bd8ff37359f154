// The Medium as OpenVDB (medium_vdb.hpp), read back with the OpenVDB library: the grid, its
// units and metadata, values against Medium::extinction, nothing outside the shell.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>

#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/medium/medium.hpp"
#include "kiri/geometry/volume/medium_vdb.hpp"
#include "temp_path.hpp"

using namespace kiri::geometry;

namespace {

// A shell 20 m thick from z = 100 over [-200, 200]^2 with the layers' profile, fading out
// towards x = 200 (coverage).
Medium sample_medium()
{
    MediumGrid g;
    g.nx = g.ny = 5;
    g.x0 = g.y0 = -200.0;
    g.dx = g.dy = 100.0;
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
            g.floor.push_back(100.0);
            g.bottom.push_back(100.0);
            g.top.push_back(120.0);
            g.coverage.push_back(i == g.nx - 1 ? 0.0 : 1.0);
        }
    MediumOptions o;
    o.extinction = 0.03;
    o.albedo = 0.95;
    o.anisotropy = 0.7;
    MediumDetail d;
    d.detail = 0.0;
    return Medium(std::move(g), o, d);
}

}  // namespace

TEST(MediumVdb, ReadsBackWithOpenVdb)
{
    const Medium m = sample_medium();
    const auto path = kiri::test::temp_path("medium.vdb");
    VdbExportOptions options;
    options.voxel_size = 2.5;
    const VdbExportReport report = write_medium_vdb(m, path, options);
    EXPECT_EQ(report.voxel_size, 2.5);
    EXPECT_GT(report.active_voxels, 0u);

    openvdb::initialize();
    openvdb::io::File file(path.string());
    file.open();
    openvdb::GridBase::Ptr base = file.readGrid("density");
    file.close();
    auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
    ASSERT_TRUE(grid);
    EXPECT_EQ(grid->getGridClass(), openvdb::GRID_FOG_VOLUME);
    EXPECT_NEAR(grid->voxelSize()[0], 2.5, 1e-12);
    EXPECT_EQ(grid->activeVoxelCount(), openvdb::Index64(report.active_voxels));
    EXPECT_NEAR(grid->metaValue<double>("extinction_at_density_1"), 0.03, 1e-15);
    EXPECT_NEAR(grid->metaValue<double>("albedo"), 0.95, 1e-15);
    EXPECT_NEAR(grid->metaValue<double>("anisotropy"), 0.7, 1e-15);

    // Inside the shell, away from its faces, the profile is linear in z, so the mean of the
    // 2 x 2 x 2 samples is the extinction at the voxel's centre.
    auto accessor = grid->getConstAccessor();
    for (const openvdb::Coord c :
         {openvdb::Coord(0, 0, 44), openvdb::Coord(-40, 20, 46), openvdb::Coord(30, -50, 42)}) {
        const openvdb::Vec3d p = grid->indexToWorld(c);
        EXPECT_NEAR(accessor.getValue(c), m.extinction({p.x(), p.y(), p.z()}), 1e-6) << c;
        EXPECT_GT(accessor.getValue(c), 0.0f);
    }
    // Worked value: at z = 110 (h = 0.5) the profile is 1 - 0.9 * 0.5 = 0.55.
    EXPECT_NEAR(accessor.getValue(openvdb::Coord(0, 0, 44)), 0.03 * 0.55, 1e-6);
    // No fog above, below, or beyond the fade (coverage reaches 0 at x = 200 m).
    EXPECT_EQ(accessor.getValue(openvdb::Coord(0, 0, 52)), 0.0f);
    EXPECT_EQ(accessor.getValue(openvdb::Coord(0, 0, 36)), 0.0f);
    EXPECT_EQ(accessor.getValue(openvdb::Coord(82, 0, 44)), 0.0f);  // x = 205 m: beyond the grid
    // The total optical "mass" matches the medium's: sum of values times voxel volume
    // against the integral of the profile over the covered area (the fade included).
    double mass = 0.0;
    for (auto it = grid->cbeginValueOn(); it; ++it)
        mass += *it;
    mass *= 2.5 * 2.5 * 2.5;
    double expected = 0.0;  // integral of coverage * sigma * (1 - 0.9 h) dz: sigma * 20 * 0.55 per unit area
    for (double y = -200.0 + 1.25; y < 200.0; y += 2.5)
        for (double x = -200.0 + 1.25; x < 200.0; x += 2.5)
            expected += m.column(x, y).coverage;
    expected *= 2.5 * 2.5 * 0.03 * 20.0 * 0.55;
    EXPECT_NEAR(mass, expected, 0.02 * expected);
    std::filesystem::remove(path);
}

TEST(MediumVdb, VoxelSizeFollowsTheMediumAndTheLimit)
{
    const Medium m = sample_medium();
    // An eighth of the 20 m thickness, finer than the 100 m grid.
    EXPECT_NEAR(vdb_voxel_size(m), 2.5, 1e-12);
    VdbExportOptions tight;
    tight.max_voxels = 1000;
    EXPECT_GT(vdb_voxel_size(m, tight), 10.0);
    tight.voxel_size = 0.5;
    EXPECT_THROW(write_medium_vdb(m, kiri::test::temp_path("never.vdb"), tight), kiri::LimitError);
}

namespace {

// A graded shell whose floor lies between voxel centres: floor 100.3, top 124.3 (the profile
// 1 - 0.9 h), coverage fading from 1 at x = 100 to 0 at x = 200, no noise.
Medium offset_medium(double floor = 100.3)
{
    MediumGrid g;
    g.nx = g.ny = 5;
    g.x0 = g.y0 = -200.0;
    g.dx = g.dy = 100.0;
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
            g.floor.push_back(floor);
            g.bottom.push_back(floor);
            g.top.push_back(floor + 24.0);
            g.coverage.push_back(i == g.nx - 1 ? 0.0 : 1.0);
        }
    MediumOptions o;
    o.extinction = 0.03;
    MediumDetail d;
    d.detail = 0.0;
    return Medium(std::move(g), o, d);
}

openvdb::FloatGrid::Ptr read_density(const std::filesystem::path& path)
{
    openvdb::initialize();
    openvdb::io::File file(path.string());
    file.open();
    openvdb::GridBase::Ptr base = file.readGrid("density");
    file.close();
    return openvdb::gridPtrCast<openvdb::FloatGrid>(base);
}

}  // namespace

TEST(MediumVdb, TrilinearReadBackLandsWhereTheMediumIs)
{
    // OpenVDB's convention (its samplers, Houdini): voxel (i, j, k)'s value sits at the grid's
    // transform of (i, j, k). Read back at world points that are not voxel centres, the
    // trilinear sampler returns the Medium there: its profile is linear in z and the fade linear
    // in x, so away from the shell's faces the interpolation is exact. A grid half a voxel off
    // on any axis misses by 0.9 x 0.03 / 24 x 1.25 = 1.4e-3 1/m in z.
    const Medium m = offset_medium();
    const auto path = kiri::test::temp_path("medium_sampler.vdb");
    VdbExportOptions options;
    options.voxel_size = 2.5;
    write_medium_vdb(m, path, options);
    const auto grid = read_density(path);
    ASSERT_TRUE(grid);
    const openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> sampler(*grid);
    int checked = 0;
    for (double z = 106.0; z <= 120.5; z += 1.21)
        for (double x : {-150.3, -7.9, 61.1, 121.7, 163.3})
            for (double y : {-143.2, 17.4, 88.8}) {
                const double got = sampler.wsSample(openvdb::Vec3d(x, y, z));
                EXPECT_NEAR(got, m.extinction({x, y, z}), 2e-6) << x << " " << y << " " << z;
                ++checked;
            }
    EXPECT_EQ(checked, 12 * 5 * 3);
    std::filesystem::remove(path);
}

TEST(MediumVdb, ColumnsStopAtTheFloor)
{
    // Voxels centred below the floor hold no fog and what their cells held above the floor moves
    // up: read back along a column, the optical depth is the Medium's (to 1 %), at least 94.5 %
    // of it above the floor and under 5 % below it, wherever the floor falls between voxel
    // centres (the trilinear read spreads the lowest voxel down by up to a voxel; without the
    // clip 7 % of the column lay under the ground).
    const double v = 2.5;
    for (double floor : {100.0, 100.3, 100.625, 101.25, 101.9, 102.4}) {
        const Medium m = offset_medium(floor);
        const auto path = kiri::test::temp_path("medium_floor.vdb");
        VdbExportOptions options;
        options.voxel_size = v;
        write_medium_vdb(m, path, options);
        const auto grid = read_density(path);
        ASSERT_TRUE(grid);
        const openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> sampler(*grid);
        const double exact = 0.03 * 24.0 * (1.0 + 0.1) / 2.0;  // sigma H (1 + top_density) / 2
        for (double x : {-120.0, 31.3}) {
            double above = 0.0, below = 0.0;
            const double dz = 0.01;
            for (double z = floor - 3.0 * v + 0.5 * dz; z < floor + 24.0 + 3.0 * v; z += dz)
                (z < floor ? below : above) += sampler.wsSample(openvdb::Vec3d(x, 12.0, z)) * dz;
            EXPECT_NEAR(above + below, exact, 0.01 * exact) << "floor " << floor;
            EXPECT_GT(above, 0.945 * exact) << "floor " << floor;
            EXPECT_LT(below, 0.05 * exact) << "floor " << floor;
        }
        std::filesystem::remove(path);
    }
}
