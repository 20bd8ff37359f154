// GregoryPatch against closed forms ([Thesis] (2.1)-(2.5)) and OpenSubdiv's GREGORY_BASIS.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/surface/gregory_opensubdiv.hpp"
#include "kiri/geometry/surface/gregory_patch.hpp"

using namespace kiri::geometry;

namespace {

// A bumpy patch of about 100 m with distinct interior pairs (a genuine Gregory patch).
GregoryPatch::Points random_points(unsigned seed, double size = 100.0, glm::dvec3 offset = glm::dvec3(0.0))
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> d(-0.25, 0.25);
    GregoryPatch::Points p{};
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i)
            p[GregoryPatch::index(i, j, 0)] =
                offset + size * glm::dvec3(i / 3.0 + 0.1 * d(rng), j / 3.0 + 0.1 * d(rng), d(rng));
    for (int j = 1; j < 3; ++j)
        for (int i = 1; i < 3; ++i)
            p[GregoryPatch::index(i, j, 1)] =
                p[GregoryPatch::index(i, j, 0)] + size * glm::dvec3(d(rng), d(rng), d(rng));
    return p;
}

double bern(int i, double t)
{
    static const double C[4] = {1, 3, 3, 1};
    return C[i] * std::pow(t, i) * std::pow(1.0 - t, 3 - i);
}

glm::dvec3 bezier_curve(const glm::dvec3 b[4], double t)
{
    glm::dvec3 s(0.0);
    for (int i = 0; i < 4; ++i)
        s += bern(i, t) * b[i];
    return s;
}

// [Thesis] (2.1)-(2.5) (Bernstein basis corrected) evaluated literally (away from the singular corners).
glm::dvec3 literal(const GregoryPatch& g, double u, double v)
{
    glm::dvec3 s(0.0);
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            glm::dvec3 q = g.point(i, j, 0);
            if (i == 1 && j == 1)
                q = (u * g.point(1, 1, 0) + v * g.point(1, 1, 1)) / (u + v);
            if (i == 1 && j == 2)
                q = (u * g.point(1, 2, 0) + (1 - v) * g.point(1, 2, 1)) / (u + 1 - v);
            if (i == 2 && j == 1)
                q = ((1 - u) * g.point(2, 1, 0) + v * g.point(2, 1, 1)) / (1 - u + v);
            if (i == 2 && j == 2)
                q = ((1 - u) * g.point(2, 2, 0) + (1 - v) * g.point(2, 2, 1)) / (2 - u - v);
            s += bern(i, u) * bern(j, v) * q;
        }
    return s;
}

double patch_size(const GregoryPatch& g) { return glm::length(g.point(3, 3) - g.point(0, 0)); }

bool finite(const glm::dvec3& a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }

const double kGrid[] = {0.0, 4.9e-324, 1e-310, 1e-300, 1e-12, 0.1, 0.37, 0.5, 0.81, 1.0 - 1e-12, 1.0};

}  // namespace

TEST(GregoryPatch, StorageOrderIndex)
{
    EXPECT_EQ(GregoryPatch::index(0, 0, 0), 0);
    EXPECT_EQ(GregoryPatch::index(3, 0, 1), 3);  // boundary: k is irrelevant
    EXPECT_EQ(GregoryPatch::index(2, 1, 0), 6);
    EXPECT_EQ(GregoryPatch::index(1, 1, 1), 16);
    EXPECT_EQ(GregoryPatch::index(2, 1, 1), 17);
    EXPECT_EQ(GregoryPatch::index(1, 2, 1), 18);
    EXPECT_EQ(GregoryPatch::index(2, 2, 1), 19);
}

TEST(GregoryPatch, MatchesTheLiteralFormula)
{
    const GregoryPatch g(random_points(1));
    for (double u : {0.05, 0.3, 0.5, 0.77, 0.95})
        for (double v : {0.05, 0.2, 0.5, 0.6, 0.99}) {
            const glm::dvec3 e = literal(g, u, v);
            EXPECT_LT(glm::length(evaluate(g, u, v).position - e), 1e-12 * patch_size(g)) << u << " " << v;
        }
}

TEST(GregoryPatch, CornersInterpolate)
{
    const GregoryPatch g(random_points(2));
    EXPECT_EQ(evaluate(g, 0, 0).position, g.point(0, 0));
    EXPECT_LT(glm::length(evaluate(g, 1, 0).position - g.point(3, 0)), 1e-13);
    EXPECT_LT(glm::length(evaluate(g, 1, 1).position - g.point(3, 3)), 1e-13);
    EXPECT_LT(glm::length(evaluate(g, 0, 1).position - g.point(0, 3)), 1e-13);
}

TEST(GregoryPatch, BoundaryCurvesAreTheirCubicBeziers)
{
    const GregoryPatch g(random_points(3));
    for (double t : {0.0, 1e-300, 0.13, 0.5, 0.71, 1.0}) {
        glm::dvec3 b0[4], b1[4], b2[4], b3[4];
        for (int i = 0; i < 4; ++i) {
            b0[i] = g.point(i, 0);
            b1[i] = g.point(i, 3);
            b2[i] = g.point(0, i);
            b3[i] = g.point(3, i);
        }
        const double tol = 1e-13 * patch_size(g);
        EXPECT_LT(glm::length(evaluate(g, t, 0).position - bezier_curve(b0, t)), tol);
        EXPECT_LT(glm::length(evaluate(g, t, 1).position - bezier_curve(b1, t)), tol);
        EXPECT_LT(glm::length(evaluate(g, 0, t).position - bezier_curve(b2, t)), tol);
        EXPECT_LT(glm::length(evaluate(g, 1, t).position - bezier_curve(b3, t)), tol);
    }
}

TEST(GregoryPatch, EqualInteriorPairsGiveTheBicubicBezier)
{
    auto p = random_points(4);
    for (int j = 1; j < 3; ++j)
        for (int i = 1; i < 3; ++i)
            p[GregoryPatch::index(i, j, 1)] = p[GregoryPatch::index(i, j, 0)];
    const GregoryPatch g(p);
    for (double u : kGrid)
        for (double v : kGrid) {
            glm::dvec3 s(0.0), su(0.0), sv(0.0);
            for (int j = 0; j < 4; ++j)
                for (int i = 0; i < 4; ++i) {
                    s += bern(i, u) * bern(j, v) * g.point(i, j);
                    // Bezier derivative via the exact polynomial: d/du B_i = 3 (B^2_{i-1} - B^2_i)
                    auto b2 = [](int k, double t) {
                        static const double C[3] = {1, 2, 1};
                        return k < 0 || k > 2 ? 0.0 : C[k] * std::pow(t, k) * std::pow(1 - t, 2 - k);
                    };
                    su += 3 * (b2(i - 1, u) - b2(i, u)) * bern(j, v) * g.point(i, j);
                    sv += 3 * (b2(j - 1, v) - b2(j, v)) * bern(i, u) * g.point(i, j);
                }
            const PatchPoint e = evaluate(g, u, v);
            const double tol = 1e-13 * patch_size(g);
            EXPECT_LT(glm::length(e.position - s), tol) << u << " " << v;
            EXPECT_LT(glm::length(e.du - su), 1e-12 * patch_size(g)) << u << " " << v;
            EXPECT_LT(glm::length(e.dv - sv), 1e-12 * patch_size(g)) << u << " " << v;
        }
}

TEST(GregoryPatch, PartitionOfUnityAndAffineInvariance)
{
    const auto p = random_points(5);
    const GregoryPatch g(p);
    const glm::dmat3 A(1.3, 0.2, -0.4, 0.1, 0.9, 0.3, 0.5, -0.2, 1.1);
    const glm::dvec3 t(12.5, -7.25, 3.0);
    GregoryPatch::Points q;
    for (int k = 0; k < 20; ++k)
        q[k] = A * p[k] + t;
    const GregoryPatch h(q);
    for (double u : kGrid)
        for (double v : kGrid) {
            double w[20], wu[20], wv[20];
            gregory_weights(u, v, w, wu, wv);
            double sw = 0, su = 0, sv = 0;
            for (int k = 0; k < 20; ++k) {
                sw += w[k];
                su += wu[k];
                sv += wv[k];
            }
            EXPECT_NEAR(sw, 1.0, 1e-15);
            EXPECT_NEAR(su, 0.0, 1e-14);
            EXPECT_NEAR(sv, 0.0, 1e-14);
            const PatchPoint a = evaluate(g, u, v), b = evaluate(h, u, v);
            const double tol = 1e-12 * patch_size(h);
            EXPECT_LT(glm::length(b.position - (A * a.position + t)), tol);
            EXPECT_LT(glm::length(b.du - A * a.du), tol);
            EXPECT_LT(glm::length(b.dv - A * a.dv), tol);
        }
}

TEST(GregoryPatch, DerivativesMatchCentralDifferences)
{
    const GregoryPatch g(random_points(6));
    const double h = 1e-5;
    for (double u : {0.02, 0.1, 0.37, 0.5, 0.81, 0.98})
        for (double v : {0.03, 0.2, 0.5, 0.66, 0.97}) {
            const PatchPoint e = evaluate(g, u, v);
            const glm::dvec3 fu = (evaluate(g, u + h, v).position - evaluate(g, u - h, v).position) / (2 * h);
            const glm::dvec3 fv = (evaluate(g, u, v + h).position - evaluate(g, u, v - h).position) / (2 * h);
            // Truncation ~ h^2 |S'''| / 6 with |S'''| ~ size / min(u, v...)^2 near the corners.
            const double tol = 1e-6 * patch_size(g);
            EXPECT_LT(glm::length(e.du - fu), tol) << u << " " << v;
            EXPECT_LT(glm::length(e.dv - fv), tol) << u << " " << v;
        }
}

TEST(GregoryPatch, CornerLimitsOfValueAndDerivatives)
{
    const GregoryPatch g(random_points(7));
    // Analytic limits: S(c) = corner point; dS/du, dS/dv = 3 (boundary neighbour - corner).
    struct C {
        double u, v;
        int i, j, di, dj;  // corner (i, j) and the directions of its neighbours
    };
    const C corners[] = {{0, 0, 0, 0, 1, 1}, {1, 0, 3, 0, -1, 1}, {0, 1, 0, 3, 1, -1}, {1, 1, 3, 3, -1, -1}};
    for (const C& c : corners) {
        const glm::dvec3 P = g.point(c.i, c.j);
        const glm::dvec3 du = 3.0 * c.di * (g.point(c.i + c.di, c.j) - P);
        const glm::dvec3 dv = 3.0 * c.dj * (g.point(c.i, c.j + c.dj) - P);
        const glm::dvec3 n = glm::normalize(glm::cross(du, dv));
        for (double d : {0.0, 4.9e-324, 1e-310, 1e-300, 1e-200, 1e-100, 1e-30, 1e-15, 1e-8}) {
            for (double a : {0.0, 0.3, 1.0, 3.0}) {  // approach directions
                const double u = c.u == 0 ? d : 1.0 - d;
                const double v = c.v == 0 ? d * a : 1.0 - d * a;
                const PatchPoint e = evaluate(g, u, v);
                ASSERT_TRUE(finite(e.position) && finite(e.du) && finite(e.dv) && finite(e.normal));
                // Distance d from the corner moves S by O(d) and the derivatives by O(d).
                const double tol = 1e-13 * patch_size(g) + 50 * d * patch_size(g) * (1 + a);
                EXPECT_LT(glm::length(e.position - P), tol) << c.u << c.v << " d=" << d;
                EXPECT_LT(glm::length(e.du - du), tol) << c.u << c.v << " d=" << d << " a=" << a;
                EXPECT_LT(glm::length(e.dv - dv), tol) << c.u << c.v << " d=" << d << " a=" << a;
                EXPECT_LT(glm::length(e.normal - n), 1e-12 + 50 * d * (1 + a)) << c.u << c.v << " d=" << d;
            }
        }
    }
}

TEST(GregoryPatch, OpenSubdivGregoryBasisAgrees)
{
    const GregoryPatch g(random_points(8));
    const double size = patch_size(g);
    double worst = 0.0;
    for (double u : kGrid)
        for (double v : kGrid) {
            if ((u == 0 || u == 1) && (v == 0 || v == 1))
                continue;  // OpenSubdiv's 0/0 guard there is its own business
            if ((u > 0 && u < 1e-307) || (v > 0 && v < 1e-307))
                continue;  // OpenSubdiv's GREGORY_BASIS weights are NaN at subnormal parameters
            double w[20], wu[20], wv[20], o[20], ou[20], ov[20];
            gregory_weights(u, v, w, wu, wv);
            opensubdiv_gregory_weights(u, v, o, ou, ov);
            glm::dvec3 a(0.0), b(0.0);
            for (int k = 0; k < 20; ++k) {
                EXPECT_NEAR(w[k], o[k], 1e-14) << "k=" << k << " u=" << u << " v=" << v;
                a += w[k] * g.points()[k];
                b += o[k] * g.points()[k];
            }
            worst = std::max(worst, glm::length(a - b) / size);
        }
    EXPECT_LT(worst, 1e-12);
    // Through the batch path too (same 20 points, OpenSubdiv's order).
    std::vector<double> us, vs;
    for (double u : {0.01, 0.3, 0.5, 0.9})
        for (double v : {0.02, 0.4, 0.99}) {
            us.push_back(u);
            vs.push_back(v);
        }
    PatchSamples a = evaluate(g, us, vs, false), b;
    b.resize(us.size(), false);
    evaluate_into_opensubdiv(g, us, vs, b.spans());
    for (std::size_t i = 0; i < us.size(); ++i)
        EXPECT_LT(glm::length(a.position(i) - b.position(i)), 1e-12 * size);
}

TEST(GregoryPatch, BatchEqualsSinglePoint)
{
    const GregoryPatch g(random_points(9));
    std::vector<double> us, vs;
    for (double u : kGrid)
        for (double v : kGrid) {
            us.push_back(u);
            vs.push_back(v);
        }
    const PatchSamples s = evaluate(g, us, vs);
    ASSERT_EQ(s.size(), us.size());
    for (std::size_t i = 0; i < us.size(); ++i) {
        const PatchPoint e = evaluate(g, us[i], vs[i]);
        EXPECT_LT(glm::length(s.position(i) - e.position), 1e-12);
        EXPECT_LT(glm::length(s.du(i) - e.du), 1e-12);
        EXPECT_LT(glm::length(s.dv(i) - e.dv), 1e-12);
        EXPECT_LT(glm::length(s.normal(i) - e.normal), 1e-12);
    }
    PatchSamples small;
    small.resize(2, false);
    EXPECT_THROW(evaluate_into(g, us, vs, small.spans()), kiri::InputError);
}

TEST(GregoryPatchStress, HugeOffsetChangesNothingRelativeToTheLocalOrigin)
{
    const glm::dvec3 off(1e7, -1e7, 1e7);
    const GregoryPatch g(random_points(10)), h(random_points(10, 100.0, off));
    for (double u : kGrid)
        for (double v : kGrid) {
            const PatchPoint a = evaluate(g, u, v), b = evaluate(h, u, v);
            // Positions: the final rounding at 1e7 (ulp 1.9e-9) and the rounding of the inputs.
            EXPECT_LT(glm::length((b.position - off) - a.position), 1e-8);
            EXPECT_LT(glm::length(b.du - a.du), 1e-7);
            EXPECT_LT(glm::length(b.dv - a.dv), 1e-7);
            EXPECT_LT(glm::length(b.normal - a.normal), 1e-9);
        }
}

TEST(GregoryPatchStress, DegeneratePatchesStayFinite)
{
    // Collapsed edge: the v = 0 boundary is one point (a triangle-like patch).
    auto p = random_points(11);
    for (int i = 0; i < 4; ++i)
        p[GregoryPatch::index(i, 0, 0)] = p[0];
    // Zero area: all points equal.
    GregoryPatch::Points z;
    z.fill(glm::dvec3(5.0, 6.0, 7.0));
    // A flat and a nearly vertical patch.
    auto flat = random_points(12);
    auto wall = random_points(13);
    for (auto& q : flat)
        q.z = 1e-9 * q.z;
    for (auto& q : wall) {
        const double y = q.y;
        q.y = 1e-9 * q.z;
        q.z = y;
    }
    for (const auto& pts : {p, z, flat, wall}) {
        const GregoryPatch g(pts);
        for (double u : kGrid)
            for (double v : kGrid) {
                const PatchPoint e = evaluate(g, u, v);
                ASSERT_TRUE(finite(e.position) && finite(e.du) && finite(e.dv) && finite(e.normal));
                EXPECT_NEAR(glm::length(e.normal), 1.0, 1e-12);
            }
    }
    // The collapsed edge's normal at its corners is the limit from inside.
    const GregoryPatch g(p);
    const glm::dvec3 n0 = evaluate(g, 0, 0).normal, n1 = evaluate(g, 1e-5, 1e-5).normal;
    EXPECT_LT(glm::length(n0 - n1), 1e-3);
    // Flat patch: normal is +-z; vertical one: normal is horizontal.
    const PatchPoint f = evaluate(GregoryPatch(flat), 0.3, 0.6), w = evaluate(GregoryPatch(wall), 0.3, 0.6);
    EXPECT_GT(std::abs(f.normal.z), 1.0 - 1e-6);
    EXPECT_LT(std::abs(w.normal.z), 1e-6);
    // NaN and out-of-range parameters: centre and clamped.
    const GregoryPatch r(random_points(14));
    EXPECT_EQ(evaluate(r, std::nan(""), 0.5).position, evaluate(r, 0.5, 0.5).position);
    EXPECT_EQ(evaluate(r, -3.0, 2.0).position, evaluate(r, 0.0, 1.0).position);
}
