// The particles' relaxation (geometry/src/particles/relax_particles.hpp) against an oracle that
// pairs every point with every other: its neighbour search must find each pair within reach,
// however deep the fog and however much the spacing varies between the two.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "particles/relax_particles.hpp"

namespace kiri::geometry {
namespace {

// Fog over a square 4 km wide from 0 to 600 m (no edge within reach of the points, so none is
// pinned), its spacing four times as large in the east half as in the west (the sampler's
// spacing spans 4x, from full density to the thin rims): a point in the west reaches its eastern
// neighbours only through their spacing, not its own.
detail::RelaxFog open_fog()
{
    MediumColumn fog;
    fog.floor = 0.0;
    fog.top = 600.0;
    fog.coverage = 1.0;
    return {[](const glm::dvec3& p) { return p.x < 0.0 ? 20.0 : 80.0; },
            [](const glm::dvec3& p) { return std::abs(p.x) < 2000.0 && std::abs(p.y) < 2000.0 ? 1.0 : 0.0; },
            [fog](double x, double y) { return std::abs(x) < 2000.0 && std::abs(y) < 2000.0 ? fog : MediumColumn{}; }};
}

// n points uniform in a box 600 m wide within the fog, far from its edges.
std::vector<glm::dvec3> points_in_the_fog(std::size_t n, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> across(-300.0, 300.0), up(10.0, 590.0);
    std::vector<glm::dvec3> points(n);
    for (glm::dvec3& p : points)
        p = {across(rng), across(rng), up(rng)};
    return points;
}

// One sweep as relax_points documents it, every pair tried.
std::vector<glm::dvec3> one_sweep_by_every_pair(const std::vector<glm::dvec3>& points, const detail::RelaxFog& fog,
                                                double reach)
{
    std::vector<glm::dvec3> next = points;
    for (std::size_t k = 0; k < points.size(); ++k) {
        const double hk = fog.spacing(points[k]);
        glm::dvec3 push(0.0);
        for (std::size_t j = 0; j < points.size(); ++j) {
            const double r = reach * 0.5 * (hk + fog.spacing(points[j])), d = glm::distance(points[k], points[j]);
            if (j != k && d < r && d > 0.0)
                push += (points[k] - points[j]) / d * ((1.0 - d / r) * (1.0 - d / r) * r);
        }
        push.z = 0.0;
        const double size = glm::length(push);
        if (size > 0.0)
            next[k] += push * std::min(0.25, 0.15 * hk / size);  // the column is the same everywhere
    }
    return next;
}

TEST(RelaxPoints, OneSweepPushesEachPointByEveryNeighbourWithinReachOfTheirMeanSpacing)
{
    std::vector<glm::dvec3> points = points_in_the_fog(3000, 7);
    const detail::RelaxFog fog = open_fog();
    const std::vector<glm::dvec3> expected = one_sweep_by_every_pair(points, fog, 1.6);
    std::vector<glm::dvec3> relaxed = points;
    detail::relax_points(relaxed, fog, 1, 1.6);
    std::size_t moved = 0;
    for (std::size_t k = 0; k < points.size(); ++k) {
        ASSERT_LT(glm::distance(relaxed[k], expected[k]), 1e-9) << "point " << k << " at x " << points[k].x;
        moved += relaxed[k] != points[k];
    }
    EXPECT_GT(moved, points.size() * 9 / 10);  // the sweep did move them: the comparison is not idle
}

TEST(RelaxPoints, TheSameWhateverThePointsOrder)
{
    std::vector<glm::dvec3> points = points_in_the_fog(2000, 11);
    std::vector<glm::dvec3> reversed(points.rbegin(), points.rend());
    const detail::RelaxFog fog = open_fog();
    detail::relax_points(points, fog, 5, 1.6);
    detail::relax_points(reversed, fog, 5, 1.6);
    std::reverse(reversed.begin(), reversed.end());
    for (std::size_t k = 0; k < points.size(); ++k)
        ASSERT_LT(glm::distance(points[k], reversed[k]), 1e-6) << "point " << k;
}

}  // namespace
}  // namespace kiri::geometry
