// The layer base's level of detail (layer_lod.hpp): a coarser grid of the same vertices per patch,
// crack-free between levels, the base's own triangles at full level, levels by projected size.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <tuple>
#include <vector>

#include <glm/geometric.hpp>

#include "fog_test_terrains.hpp"
#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/layers/layer_lod.hpp"
#include "kiri/geometry/layers/layer_stack.hpp"
#include "kiri/geometry/scene/scene.hpp"

using namespace kiri::geometry;
using kiri::InputError;

namespace {

struct FittedHills {
    Terrain terrain{kiri::test::make_heightfield(101, 101, 20.0, -1000.0, -1000.0, kiri::test::hills)};
    BaseSurface surface;
    Tessellation tessellation;
    LayerBase base;
    FittedHills()
        : surface(build_control_mesh({{{-900, -850}, {880, -700}, {700, 800}, {-600, 650}}}, terrain, {250.0}),
                  SurfaceKind::gregory)
    {
        surface.fit(terrain, FitOptions{});
        tessellation = tessellate(surface, {8});
        base = make_layer_base(surface, tessellation, LayerOptions{});
    }
};
const FittedHills& hills()
{
    static const FittedHills h;
    return h;
}

using Triangle = std::array<std::uint32_t, 3>;

// A triangle with its smallest index first, the order (the winding) kept.
Triangle canonical(std::uint32_t a, std::uint32_t b, std::uint32_t c)
{
    Triangle t{a, b, c};
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    return t;
}

std::multiset<Triangle> triangles(const std::vector<std::uint32_t>& list)
{
    std::multiset<Triangle> s;
    for (std::size_t k = 0; k + 2 < list.size(); k += 3)
        s.insert(canonical(list[k], list[k + 1], list[k + 2]));
    return s;
}

using Point = std::tuple<double, double, double>;
Point point(const glm::dvec3& p) { return {p.x, p.y, p.z}; }

// Each undirected edge, by its end points' positions (patches hold their own copies), with the
// number of triangles that use it.
std::map<std::pair<Point, Point>, int> edge_uses(const LayerBase& base, const std::vector<std::uint32_t>& list)
{
    std::map<std::pair<Point, Point>, int> uses;
    for (std::size_t k = 0; k + 2 < list.size(); k += 3)
        for (int e = 0; e < 3; ++e) {
            Point a = point(base.position[list[k + e]]), b = point(base.position[list[k + (e + 1) % 3]]);
            if (b < a)
                std::swap(a, b);
            ++uses[{a, b}];
        }
    return uses;
}

double signed_xy_area(const LayerBase& base, const std::vector<std::uint32_t>& list, double& negative)
{
    double area = 0.0;
    negative = 0.0;
    for (std::size_t k = 0; k + 2 < list.size(); k += 3) {
        const glm::dvec3 a = base.position[list[k]], b = base.position[list[k + 1]], c = base.position[list[k + 2]];
        const double z = 0.5 * ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
        area += z;
        negative += std::min(z, 0.0);
    }
    return area;
}

}  // namespace

TEST(LayerLod, TheGridHoldsEveryVertexOnceAndFindsTheNeighbours)
{
    const LayerBase& base = hills().base;
    const LayerPatchGrid& g = base.grid;
    ASSERT_EQ(g.level, 8);
    ASSERT_EQ(g.patches, hills().surface.num_patches());
    ASSERT_GT(g.patches, 8);
    const std::set<std::uint32_t> distinct(g.vertex.begin(), g.vertex.end());
    EXPECT_EQ(distinct.size(), base.position.size());
    EXPECT_EQ(g.vertex.size(), base.position.size());
    // Across each side the neighbour's side holds the same points, in one order or the other.
    int shared = 0;
    for (int f = 0; f < g.patches; ++f)
        for (int s = 0; s < 4; ++s) {
            const int o = g.neighbour[std::size_t(f)][std::size_t(s)];
            if (o < 0)
                continue;
            ++shared;
            EXPECT_NE(o, f);
            const auto& back = g.neighbour[std::size_t(o)];
            EXPECT_NE(std::find(back.begin(), back.end(), f), back.end());
        }
    EXPECT_GT(shared, 2 * g.patches);  // an interior patch has four
}

TEST(LayerLod, FullLevelIsTheBasesOwnTriangles)
{
    const LayerBase& base = hills().base;
    const std::vector<int> full(std::size_t(base.grid.patches), base.grid.level);
    EXPECT_EQ(triangles(layer_lod_triangles(base.grid, full)), triangles(base.triangles));
}

TEST(LayerLod, MixedLevelsAreCrackFreeAndCoverTheSameFootprint)
{
    const LayerBase& base = hills().base;
    const LayerPatchGrid& g = base.grid;
    // Edges used once in the full mesh: the footprint's outline. Every other edge is shared.
    std::set<Point> outline;
    for (const auto& [edge, n] : edge_uses(base, base.triangles))
        if (n == 1)
            outline.insert(edge.first), outline.insert(edge.second);
    double negative = 0.0;
    const double full_area = signed_xy_area(base, base.triangles, negative);
    ASSERT_GT(full_area, 0.0);
    for (const std::vector<int>& pattern :
         {std::vector<int>{1, 2, 4, 8}, std::vector<int>{1}, std::vector<int>{2, 1}, std::vector<int>{8, 1, 1, 4, 2}}) {
        std::vector<int> levels(std::size_t(g.patches));
        for (std::size_t f = 0; f < levels.size(); ++f)
            levels[f] = pattern[f % pattern.size()];
        const std::vector<std::uint32_t> lod = layer_lod_triangles(g, levels);
        ASSERT_EQ(lod.size() % 3, 0u);
        EXPECT_LT(lod.size(), base.triangles.size());
        // A crack is an edge used by one triangle inside the footprint: a T-junction.
        int cracks = 0;
        for (const auto& [edge, n] : edge_uses(base, lod)) {
            EXPECT_LE(n, 2);
            if (n == 1 && !(outline.count(edge.first) && outline.count(edge.second)))
                ++cracks;
        }
        EXPECT_EQ(cracks, 0) << "pattern of " << pattern.size();
        // Counter-clockwise from above, as the base, and the same footprint but for the chords
        // of the coarser patches along its outline.
        const double area = signed_xy_area(base, lod, negative);
        EXPECT_EQ(negative, 0.0);
        EXPECT_NEAR(area, full_area, 0.01 * full_area);
        for (std::uint32_t v : lod)
            ASSERT_LT(v, base.position.size());
    }
}

TEST(LayerLod, LevelsFollowTheProjectedSize)
{
    const LayerBase& base = hills().base;
    const LayerPatchGrid& g = base.grid;
    const int n = g.level;
    // Far away every patch is a pixel: level 1. The eye on the base: its patch at full level.
    const std::vector<int> far = layer_lod_levels(base, {0, 0, 1e7}, 500.0, 8.0, 0.0);
    ASSERT_EQ(far.size(), std::size_t(g.patches));
    EXPECT_EQ(*std::max_element(far.begin(), far.end()), 1);
    const glm::dvec3 on = base.position[g.at(0, n / 2, n / 2)];
    const std::vector<int> near = layer_lod_levels(base, on, 500.0, 8.0, 0.0);
    EXPECT_EQ(near[0], n);
    // A patch's level is the smallest divisor of n at least its projected size over the edge, and
    // grows as the eye comes closer.
    const int f = g.patches / 2;
    const glm::dvec3 p[5] = {base.position[g.at(f, 0, 0)], base.position[g.at(f, n, 0)], base.position[g.at(f, n, n)],
                             base.position[g.at(f, 0, n)], base.position[g.at(f, n / 2, n / 2)]};
    glm::dvec3 centre(0.0);
    for (const glm::dvec3& q : p)
        centre += 0.2 * q;
    double radius = 0.0;
    for (const glm::dvec3& q : p)
        radius = std::max(radius, glm::length(q - centre));
    radius *= 1.0 + 0.5 / n;
    int last = 0;
    for (const double d : {40000.0, 20000.0, 8000.0, 4000.0, 2000.0}) {
        const glm::dvec3 eye = centre + glm::dvec3(0.0, 0.0, d + radius);
        const int level = layer_lod_levels(base, eye, 500.0, 8.0, 0.0)[std::size_t(f)];
        const int want = int(std::ceil(2.0 * radius * 500.0 / d / 8.0));
        int expected = n;
        for (int k = std::max(want, 1); k < n; ++k)
            if (n % k == 0) {
                expected = k;
                break;
            }
        EXPECT_EQ(level, expected) << "at " << d << " m";
        EXPECT_GE(level, last);
        last = level;
    }
    EXPECT_GT(last, 1);
    // The stack's height grows the sphere: never a coarser level.
    const glm::dvec3 eye = centre + glm::dvec3(0.0, 0.0, 8000.0);
    EXPECT_GE(layer_lod_levels(base, eye, 500.0, 8.0, 300.0)[std::size_t(f)],
              layer_lod_levels(base, eye, 500.0, 8.0, 0.0)[std::size_t(f)]);
}

TEST(LayerLod, NonsenseKeepsTheFullLevelAndBadLevelsAreRefused)
{
    const LayerBase& base = hills().base;
    const int n = base.grid.level;
    const double inf = std::numeric_limits<double>::infinity(), nan = std::nan("");
    for (const auto& levels :
         {layer_lod_levels(base, {nan, 0, 0}, 500.0, 8.0, 0.0), layer_lod_levels(base, {0, 0, 1e7}, inf, 8.0, 0.0),
          layer_lod_levels(base, {0, 0, 1e7}, 500.0, 0.0, 0.0), layer_lod_levels(base, {0, 0, 1e7}, 500.0, 8.0, nan)})
        EXPECT_EQ(levels, std::vector<int>(std::size_t(base.grid.patches), n));
    EXPECT_THROW(layer_lod_triangles(base.grid, {1, 2}), InputError);
    EXPECT_THROW(layer_lod_triangles(base.grid, std::vector<int>(std::size_t(base.grid.patches), 3)), InputError);
    EXPECT_THROW(layer_lod_triangles(base.grid, std::vector<int>(std::size_t(base.grid.patches), 0)), InputError);
}

TEST(LayerLod, AnAdaptiveTessellationHasNoGrid)
{
    const auto& h = hills();
    TessellationOptions o;
    o.tolerance = 0.5;
    const Tessellation adaptive = tessellate(h.surface, o);
    const LayerBase base = make_layer_base(h.surface, adaptive, LayerOptions{});
    EXPECT_TRUE(base.grid.empty());
    EXPECT_TRUE(layer_lod_levels(base, {0, 0, 1e7}, 500.0, 8.0, 0.0).empty());
}
