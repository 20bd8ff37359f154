// Cell masks to footprint polygons: exact areas of traced outlines, components,
// holes, diagonal contacts, the grid's border, growth into allowed cells, and the control mesh
// built over several polygons.
#include <gtest/gtest.h>

#include <cmath>

#include "fog_test_terrains.hpp"
#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/placement/mask_outline.hpp"
#include "kiri/geometry/terrain/terrain.hpp"

using namespace kiri::geometry;
using kiri::test::make_heightfield;

namespace {

Heightfield grid(int nx = 30, int ny = 20)
{
    return make_heightfield(nx, ny, 10.0, 0.0, 0.0, [](double, double) { return 0.0; });
}

std::vector<std::uint8_t> cells(const Heightfield& g, const std::function<bool(int, int)>& on)
{
    std::vector<std::uint8_t> m(g.size(), 0);
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i)
            m[std::size_t(j) * g.nx + i] = on(i, j);
    return m;
}

double area(const std::vector<glm::dvec2>& p)
{
    double a = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i)
        a += p[i].x * p[(i + 1) % p.size()].y - p[(i + 1) % p.size()].x * p[i].y;
    return 0.5 * a;
}

}  // namespace

TEST(MaskOutline, ABlockOfCellsIsItsRectangle)
{
    const Heightfield g = grid();
    const MaskOutline o =
        mask_outline(g, cells(g, [](int i, int j) { return i >= 3 && i <= 7 && j >= 4 && j <= 5; }), {}, {});
    ASSERT_EQ(o.components, 1);
    const auto& p = o.footprint.polygon;
    ASSERT_EQ(p.size(), 4u);
    EXPECT_DOUBLE_EQ(area(p), 5 * 10.0 * 2 * 10.0);  // counter-clockwise, cell edges at half cells
    EXPECT_DOUBLE_EQ(p[0].x, 25.0);
    EXPECT_DOUBLE_EQ(p[0].y, 35.0);
    EXPECT_TRUE(o.footprint.more.empty());
}

TEST(MaskOutline, AnLShapeKeepsItsAreaExactly)
{
    const Heightfield g = grid();
    const MaskOutline o = mask_outline(g,
                                       cells(g,
                                             [](int i, int j) {
                                                 return (i >= 2 && i <= 10 && j >= 2 && j <= 4) ||
                                                     (i >= 2 && i <= 4 && j <= 12 && j >= 2);
                                             }),
                                       {}, {});
    EXPECT_EQ(o.footprint.polygon.size(), 6u);
    EXPECT_DOUBLE_EQ(area(o.footprint.polygon), (9 * 3 + 3 * 8) * 100.0);
}

TEST(MaskOutline, SeveralComponentsHolesAndNesting)
{
    const Heightfield g = grid(40, 30);
    // A ring (a hole of 5 x 5 inside) with a block in its hole, and a separate block.
    const auto m = cells(g, [](int i, int j) {
        const bool ring = i >= 2 && i <= 12 && j >= 2 && j <= 12 && !(i >= 4 && i <= 10 && j >= 4 && j <= 10);
        const bool inner = i >= 6 && i <= 8 && j >= 6 && j <= 8;
        const bool apart = i >= 20 && i <= 25 && j >= 20 && j <= 22;
        return ring || inner || apart;
    });
    const MaskOutline o = mask_outline(g, m, {}, {});
    EXPECT_EQ(o.components, 2);  // the block in the hole is covered by the ring's outer border
    const auto polys = footprint_polygons(o.footprint);
    ASSERT_EQ(polys.size(), 2u);
    EXPECT_DOUBLE_EQ(area(polys[0]), 11 * 11 * 100.0);
    EXPECT_DOUBLE_EQ(area(polys[1]), 6 * 3 * 100.0);
    EXPECT_NO_THROW(validate_footprint(o.footprint));
    // min_area drops the small block.
    OutlineOptions small;
    small.min_area = 2000.0;
    const MaskOutline big = mask_outline(g, m, {}, small);
    EXPECT_EQ(big.components, 1);
    EXPECT_EQ(big.dropped, 2);
}

TEST(MaskOutline, DiagonalContactsAreClosedIntoOneSimplePolygon)
{
    const Heightfield g = grid();
    const MaskOutline o = mask_outline(
        g, cells(g, [](int i, int j) { return (i == 5 && j == 5) || (i == 6 && j == 6) || (i == 7 && j == 5); }), {},
        {});
    EXPECT_EQ(o.components, 1);
    EXPECT_NO_THROW(validate_footprint(o.footprint));
    EXPECT_DOUBLE_EQ(area(o.footprint.polygon), 4 * 100.0);  // cell (6, 5) added joins all three
}

TEST(MaskOutline, OutlinesStayInsideTheTerrainAtItsBorder)
{
    const Heightfield g = grid();
    const MaskOutline o = mask_outline(g, cells(g, [](int i, int) { return i < 5; }), {}, {});
    for (const glm::dvec2 q : o.footprint.polygon) {
        EXPECT_GE(q.x, g.x0);
        EXPECT_LE(q.x, g.x_max());
        EXPECT_GE(q.y, g.y0);
        EXPECT_LE(q.y, g.y_max());
    }
    EXPECT_DOUBLE_EQ(area(o.footprint.polygon), 45.0 * 190.0);  // x from 0 to 45, y from 0 to 190
}

TEST(MaskOutline, GrowsOnlyIntoAllowedCellsAndSimplifies)
{
    const Heightfield g = grid(60, 60);
    const auto m = cells(g, [](int i, int j) { return std::hypot(i - 20.0, j - 30.0) < 8.0; });
    // Growth is allowed left of i = 40 only.
    const auto allowed = cells(g, [](int i, int) { return i < 40; });
    OutlineOptions opt;
    opt.margin = 50.0;  // five cells
    opt.tolerance = 4.0;
    const MaskOutline o = mask_outline(g, m, allowed, opt);
    double max_x = -1e300;
    for (const glm::dvec2 q : o.footprint.polygon)
        max_x = std::max(max_x, q.x);
    EXPECT_LE(max_x, 39.5 * 10.0);
    EXPECT_GT(area(o.footprint.polygon), M_PI * 130.0 * 130.0 * 0.9);  // the disc of radius 8 + 5 cells
    EXPECT_LT(o.vertices, 60u);                                        // a circle's staircase, simplified
    EXPECT_DOUBLE_EQ(o.tolerance, 4.0);
}

TEST(MaskOutline, TheControlMeshCoversSeveralPolygons)
{
    const Heightfield hf =
        make_heightfield(101, 101, 20.0, -1000.0, -1000.0, [](double x, double) { return 300.0 + 0.1 * x; });
    const Terrain terrain{Heightfield(hf)};
    const MaskOutline o =
        mask_outline(hf,
                     cells(hf,
                           [](int i, int j) {
                               return (i > 5 && i < 40 && j > 10 && j < 60) || (i > 60 && i < 95 && j > 50 && j < 90);
                           }),
                     {}, {});
    ASSERT_EQ(o.components, 2);
    ControlMeshOptions cmo;
    cmo.patch_size = 100.0;
    const ControlMesh cm = build_control_mesh(o.footprint, terrain, cmo);
    int left = 0, right = 0;
    for (auto f : cm.mesh.faces()) {
        const auto p = cm.mesh.calc_face_centroid(f);
        (p[0] < 0.0 ? left : right) += 1;
    }
    // 34 x 49 cells of 20 m and 34 x 39: about (680 x 980) / 100^2 and (680 x 780) / 100^2 patches.
    EXPECT_NEAR(left, 66, 10);
    EXPECT_NEAR(right, 53, 10);
}

TEST(MaskOutline, RefusesAnEmptyOrMisSizedMask)
{
    const Heightfield g = grid();
    EXPECT_THROW(mask_outline(g, std::vector<std::uint8_t>(g.size(), 0), {}, {}), kiri::InputError);
    EXPECT_THROW(mask_outline(g, std::vector<std::uint8_t>(5, 1), {}, {}), kiri::InputError);
}
