// The layer stack's formulas ([Thesis] (2.6)-(2.10), layer_stack.hpp) against the source's
// numbers, their limits, the continuous slab they stand for and their symmetries.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "kiri/geometry/layers/layer_stack.hpp"
#include "layer_test_stacks.hpp"

using namespace kiri::geometry;
using kiri::test::options_15;

namespace {

const double pi = std::acos(-1.0);

}  // namespace

// ---- [Thesis] (2.6)-(2.10): the source's numbers and what follows from them ------------------
//
// The thesis prints its settings (the 200 of (2.6), a_0 = 1 and a_l = 0.1 of (2.7), the 1/1000 of
// (2.10), 15 and 30 layers in its Fig. 2.7 and 2.8) but no worked example. These tests hold the
// stack to those numbers and to what must follow from any correct reading: the limits as the eye
// comes close or goes far, the stack's optical depth against the continuous slab it stands for
// (Beer-Lambert), continuity where one rule hands over to the next, (2.9) as the inequality it is
// printed as, and the symmetries of the geometry.

namespace {

// A column straight above p at distance L.
LayerColumn column_at(const LayerOptions& o, double L) { return layer_column(o, {0, 0, L}, {0, 0, 0}, {0, 0, 1}); }

// Sum over the stack of (alpha_i x spacing): the optical depth per unit extinction that the
// medium shading gives a straight-down ray (alpha = 1 - exp(-sigma_t a_i r), docs/layers.md).
double stack_depth(const LayerOptions& o, const LayerColumn& c)
{
    double depth = 0.0;
    for (int i = 0; i <= int(std::ceil(c.count)) + 1; ++i) {
        const LayerVertex v = layer_vertex(o, c, i, {0, 0, 0}, {0, 0});
        depth += v.alpha * c.spacing * v.slab;
    }
    return depth;
}

}  // namespace

TEST(LayerFormulas, TheSourcesReferenceView)
{
    // 15 layers (the source's Fig. 2.7) over a 150 m thick fog: r0 = 10 m, so (2.6) puts the
    // reference view at L0 = 200 x 10 m = 2 km. There and beyond, the stack is the source's.
    LayerOptions o = options_15();
    o.shading = LayerShading::source;
    EXPECT_EQ(layer_spacing(2000.0), 10.0);
    for (double L : {2000.0, 2500.0, 1e5, 1e12}) {
        const LayerColumn c = column_at(o, L);
        EXPECT_EQ(c.spacing, 10.0) << L;
        EXPECT_EQ(c.count, 15.0) << L;
        EXPECT_EQ(layer_vertex(o, c, 0, {0, 0, 0}, {0, 0}).alpha, 1.0);                   // a_0: opaque
        EXPECT_NEAR(layer_vertex(o, c, 15, {0, 0, 0}, {0, 0}).alpha, 0.1, 1e-15);         // a_l = 0.1
        EXPECT_NEAR(layer_vertex(o, c, 15, {0, 0, 0}, {0, 0}).position.z, 150.0, 1e-12);  // T0
        EXPECT_EQ(layer_vertex(o, c, 16, {0, 0, 0}, {0, 0}).alpha, 0.0);
    }
    // Half the reference distance: twice the layers at half the spacing, as the source's Fig. 2.8
    // (30 layers) has twice Fig. 2.7's.
    const LayerColumn half = column_at(o, 1000.0);
    EXPECT_EQ(half.spacing, 5.0);
    EXPECT_EQ(half.count, 30.0);
    EXPECT_NEAR(layer_vertex(o, half, 30, {0, 0, 0}, {0, 0}).alpha, 0.1, 1e-15);
}

TEST(LayerFormulas, AlphaProfileEndsAtTheSourcesValuesAndIsPointSymmetric)
{
    for (int l : {1, 2, 15, 30, 120}) {
        EXPECT_EQ(layer_alpha(0, l), 1.0) << l;
        EXPECT_NEAR(layer_alpha(l, l), 0.1, 1e-15) << l;
        double sum = 0.0;
        for (int i = 0; i <= l; ++i) {
            // A straight line through (0, 1) and (l, 0.1): symmetric about its middle.
            EXPECT_NEAR(layer_alpha(i, l) + layer_alpha(l - i, l), 1.1, 1e-15) << i << "/" << l;
            sum += layer_alpha(i, l);
        }
        EXPECT_NEAR(sum, 0.55 * (l + 1), 1e-12) << l;  // mean of the ends, (1 + 0.1) / 2
    }
    // The profile depends on the height fraction i / l alone: a third of the way up it is 0.7
    // whatever the count, so adding layers (2.9) refines the same continuous profile.
    for (int l : {3, 30, 300})
        EXPECT_NEAR(layer_alpha(l / 3, l), 0.7, 1e-15) << l;
    EXPECT_EQ(layer_alpha(0, 0), 1.0);  // l = 0: the base alone
}

TEST(LayerFormulas, SpacingLimitsAsTheEyeComesCloseOrGoesFar)
{
    const LayerOptions o = options_15();  // r0 = 10 m, L0 = 2 km, T0 = 150 m, at most 120 layers
    const double floor_spacing = o.thickness / o.max_count, floor_distance = o.spacing_divisor * floor_spacing;
    // Within the narrowing range an eye coming straight at the point sees (2.6) again: r = L / 200.
    for (double L : {1999.0, 1500.0, 1000.0, 400.0, floor_distance})
        EXPECT_NEAR(column_at(o, L).spacing, L / 200.0, 1e-13) << L;
    // L -> 0: the spacing bottoms out at T0 / max_count with every layer drawn.
    for (double L : {floor_distance - 1e-9, 100.0, 1.0, 1e-9, 0.0}) {
        EXPECT_EQ(column_at(o, L).spacing, floor_spacing) << L;
        EXPECT_EQ(column_at(o, L).count, 120.0) << L;
    }
    // The spacing never falls as the eye recedes.
    double previous = 0.0;
    for (double L = 0.0; L < 3000.0; L += 7.3) {
        const double r = column_at(o, L).spacing;
        EXPECT_GE(r, previous) << L;
        previous = r;
    }
    // Moving away never widens (2.8)'s spacing beyond r0, and a reference eye at O leaves nothing
    // to narrow.
    EXPECT_EQ(narrowed_spacing(10.0, -500.0, 2000.0), 10.0);
    EXPECT_EQ(narrowed_spacing(10.0, 2000.0, 2000.0), 0.0);
    EXPECT_EQ(narrowed_spacing(10.0, 4000.0, 2000.0), 0.0);
    EXPECT_EQ(narrowed_spacing(10.0, 10.0, 0.0), 0.0);
}

TEST(LayerFormulas, AddedLayersSatisfyThePrintedInequality)
{
    // (2.9): a layer is added at spacing r' on top while r'(n + 1) <= T0. So the layers drawn in
    // full are the largest n with r' n <= T0; at most one more, above T0, is fading in.
    LayerOptions o = options_15();
    o.shading = LayerShading::source;
    for (double L = 2100.0; L > 100.0; L -= 37.0) {
        const LayerColumn c = column_at(o, L);
        int full = 0, fading = 0;
        for (int i = 1; i <= 125; ++i) {
            const LayerVertex v = layer_vertex(o, c, i, {0, 0, 0}, {0, 0});
            if (v.position.z <= o.thickness * (1.0 + 1e-12)) {
                EXPECT_GE(v.alpha, 0.1 - 1e-15) << L << " layer " << i;  // below T0: at (2.7)'s value
                ++full;
            } else if (v.alpha > 0.0) {
                EXPECT_LT(v.alpha, 0.1) << L << " layer " << i;
                ++fading;
            }
        }
        EXPECT_LE(c.spacing * full, o.thickness * (1.0 + 1e-12)) << L;
        EXPECT_GT(c.spacing * (full + 1), o.thickness * (1.0 + 1e-12)) << L;
        EXPECT_LE(fading, 1) << L;
        EXPECT_GE(full, 15) << L;
    }
}

TEST(LayerFormulas, StackDepthConvergesToTheSlab)
{
    // Beer-Lambert: a straight-down ray through the stack sees transmittance
    // exp(-sigma_t sum a_i r w_i) under the medium shading (w_i: layer_slab_share). The slab it
    // stands for has density 1 - 0.9 z / T0, optical depth sigma_t integral_0^T0 (1 - 0.9 z / T0) dz
    // = 0.55 sigma_t T0. The stack is the trapezoid rule of that integral, with the fading top
    // layer as the node at T0 (its density is the top's, h = 1): exact for the linear profile at
    // every count, whole or not. One slab of r per layer (before 2026-12-02) gave 0.55 (T0 + r).
    LayerOptions o = options_15();
    const double T0 = o.thickness, slab = 0.55 * T0;
    for (double L = 3000.0; L >= 0.0; L -= 0.5) {  // counts 15 to 120, whole and between
        const LayerColumn c = column_at(o, L);
        EXPECT_NEAR(stack_depth(o, c), slab, 1e-10 * slab) << L << ", " << c.count << " layers";
    }
    // The shares themselves: half at the base, one between, and the top's half split between the
    // last whole layer and the fading one (faded in by n - m).
    EXPECT_EQ(layer_slab_share(15.0, 0), 0.5);
    EXPECT_EQ(layer_slab_share(15.0, 7), 1.0);
    EXPECT_EQ(layer_slab_share(15.0, 15), 0.5);
    EXPECT_EQ(layer_slab_share(15.25, 15), 0.625);
    EXPECT_EQ(layer_slab_share(15.25, 16), 0.5);
    EXPECT_EQ(layer_slab_share(0.5, 0), 0.25);  // thinner than one spacing: the base and the top
    EXPECT_EQ(layer_slab_share(0.5, 1), 0.5);
    EXPECT_EQ(layer_slab_share(15.0, 17), 0.0);
    EXPECT_EQ(layer_slab_share(0.0, 0), 0.0);

    // The source shading: layer alpha 1 - (1 - o a_i)^(r / r0). Its optical depth
    // -sum (r / r0) ln(1 - o a_i) tends to (1 / r0) integral_0^T0 -ln(1 - o (1 - 0.9 z / T0)) dz,
    // whose closed form with u = 1 - o (1 - 0.9 h) is l0 [u ln u - u] / (0.9 o) between
    // u = 1 - o and u = 1 - 0.1 o.
    o.shading = LayerShading::source;
    const double opacity = o.opacity, l0 = o.count;
    auto antiderivative = [](double u) { return u * std::log(u) - u; };
    const double closed = -l0 * (antiderivative(1.0 - 0.1 * opacity) - antiderivative(1.0 - opacity)) / (0.9 * opacity);
    const LayerColumn nearest = column_at(o, 0.0);
    double depth = 0.0;
    for (int i = 0; i <= 120; ++i) {
        const LayerVertex v = layer_vertex(o, nearest, i, {0, 0, 0}, {0, 0});
        depth -= v.exponent * std::log(1.0 - opacity * v.alpha);
    }
    // The stack is the trapezoid sum of that integral plus its end terms (r / r0) (f(0) + f(T0)) / 2,
    // f = -ln(1 - o a); what is left is the rule's O(r^2) error.
    const double r_over_r0 = nearest.spacing / (o.thickness / o.count);
    const double ends = r_over_r0 * 0.5 * (-std::log(1.0 - opacity) - std::log(1.0 - 0.1 * opacity));
    EXPECT_NEAR(depth, closed + ends, 1e-5 * closed);
    EXPECT_GT(ends, 5e-3 * closed);  // the end terms matter at this tolerance
}

TEST(LayerFormulas, EachSlabLiesWhereItsTrapezoidsHalvesAre)
{
    // A whole count: the slabs tile the fog from the base to the top, each reaching half way to
    // its neighbours, the base's wholly over it and the top's wholly under it (a slab centred on
    // the top layer held half its fog in the clear air over the top).
    for (const double n : {1.0, 2.0, 15.0}) {
        double reached = 0.0;
        for (int i = 0; i <= int(n); ++i) {
            const double above = layer_slab_share_above(n, i), below = layer_slab_share(n, i) - above;
            EXPECT_DOUBLE_EQ(i - below, reached) << n << " layers, layer " << i;
            reached = i + above;
        }
        EXPECT_DOUBLE_EQ(reached, n) << n << " layers";
    }
    // Between whole counts the last trapezoid, [m, n], is layer m's half over it and the fading
    // layer m + 1's (faded in by n - m, standing for the top) under it.
    EXPECT_EQ(layer_slab_share_above(15.25, 15), 0.125);
    EXPECT_EQ(layer_slab_share(15.25, 15) - layer_slab_share_above(15.25, 15), 0.5);
    EXPECT_EQ(layer_slab_share_above(15.25, 16), 0.0);
    EXPECT_EQ(layer_slab_share_above(15.25, 7), 0.5);
    EXPECT_EQ(layer_slab_share_above(0.5, 0), 0.25);  // thinner than one spacing: the base's, all over it
    EXPECT_EQ(layer_slab_share_above(15.0, 17), 0.0);
    EXPECT_EQ(layer_slab_share_above(0.0, 0), 0.0);
}

TEST(LayerFormulas, AStackTheGroundCutsHoldsTheFogFromTheGroundUp)
{
    // Medium shading over ground at height g inside the stack: the layers below it are hidden by
    // the terrain, the first above it reaches down to it, so an even fog's optical depth over the
    // column is that of T0 - g, for any g and count; a lifted base (g below it) keeps all of T0.
    LayerOptions o = options_15();
    o.optics.top_density = 1.0;  // even density: the layers' alpha is their fade-in alone
    const double T0 = o.thickness;
    for (double L : {1e6, 1000.0, 333.0})
        for (double g = -20.0; g <= T0; g += 3.7) {
            const LayerColumn c = column_at(o, L);
            double held = 0.0;
            for (int i = 0; i <= int(std::ceil(c.count)) + 1; ++i) {
                const LayerVertex v = layer_vertex(o, c, i, {0, 0, 0}, {0, 0});
                held += v.alpha * c.spacing * layer_slab_over_ground(v.slab, i, c.spacing, v.position.z - g);
            }
            EXPECT_NEAR(held, T0 - std::max(g, 0.0), 1e-9 * T0) << "ground " << g << ", " << c.count << " layers";
        }
    EXPECT_EQ(layer_slab_over_ground(1.0, 3, 10.0, -0.1), 0.0);  // below the ground: hidden
    EXPECT_EQ(layer_slab_over_ground(1.0, 3, 10.0, 10.0), 1.0);  // the layer under it shows
    EXPECT_EQ(layer_slab_over_ground(1.0, 3, 10.0, 4.0), 0.9);   // from the ground to its top half
    EXPECT_EQ(layer_slab_over_ground(0.5, 0, 10.0, 0.0), 0.5);   // the base on the ground
}

TEST(LayerFormulas, HandOversAreContinuous)
{
    // Where narrowing begins (L0) and where the spacing reaches its floor (200 T0 / max_count),
    // and where a whole layer count is crossed (the top layer fading in), two micrometres of eye
    // movement move layer i by at most i x 2 um / 200 and change its alpha by as little.
    LayerOptions o = options_15();
    const double eps = 1e-6;
    const double hand_overs[] = {o.spacing_divisor * o.thickness / o.count,
                                 o.spacing_divisor * o.thickness / o.max_count, 1000.0, 2000.0 * 15.0 / 16.0};
    for (double L : hand_overs) {
        const LayerColumn a = column_at(o, L - eps), b = column_at(o, L + eps);
        EXPECT_LE(std::abs(a.spacing - b.spacing), 2.0 * eps / 200.0 * (1.0 + 1e-6)) << L;
        for (int i = 0; i <= 121; ++i) {
            const LayerVertex va = layer_vertex(o, a, i, {0, 0, 0}, {0, 0});
            const LayerVertex vb = layer_vertex(o, b, i, {0, 0, 0}, {0, 0});
            EXPECT_LE(std::abs(va.position.z - vb.position.z), i * 2.0 * eps / 200.0 + 1e-12) << L << " layer " << i;
            EXPECT_LE(std::abs(va.alpha - vb.alpha), 1e-6) << L << " layer " << i;
            EXPECT_LE(std::abs(va.exponent - vb.exponent), 1e-6) << L << " layer " << i;
        }
    }
}

TEST(LayerFormulas, EnlargementLimitsAndSymmetry)
{
    // (2.10) about the centre c: layer k's vertex at x moves to c + (1 + k sin(theta) / 1000)(x - c).
    LayerOptions o = options_15();
    o.shading = LayerShading::source;  // the shading the enlargement is drawn in (layers_enlarge)
    const glm::dvec2 centre{200, 100};
    const glm::dvec3 p{1200, -400, 0}, mirrored{2 * centre.x - p.x, 2 * centre.y - p.y, 0}, n{0, 0, 1};
    const double d = glm::length(glm::dvec2(p) - centre);
    // Straight above: the source's top layer of 15 is 1.5 % wider; the base is never enlarged.
    const LayerColumn above = layer_column(o, p + glm::dvec3(0, 0, 3000), p, n);
    EXPECT_NEAR(glm::length(glm::dvec2(layer_vertex(o, above, 15, p, centre).position) - centre), 1.015 * d, 1e-9);
    EXPECT_EQ(glm::dvec2(layer_vertex(o, above, 0, p, centre).position), glm::dvec2(p));
    // The centre stays put in every layer.
    const glm::dvec3 at_centre{centre.x, centre.y, 0};
    const LayerColumn over_centre = layer_column(o, at_centre + glm::dvec3(0, 0, 3000), at_centre, n);
    EXPECT_EQ(glm::dvec2(layer_vertex(o, over_centre, 15, at_centre, centre).position), centre);
    // Point symmetry about the centre: a vertex and its mirror image move to mirror images.
    const LayerColumn mirror_above = layer_column(o, mirrored + glm::dvec3(0, 0, 3000), mirrored, n);
    for (int k : {1, 7, 15}) {
        const glm::dvec2 a = glm::dvec2(layer_vertex(o, above, k, p, centre).position);
        const glm::dvec2 b = glm::dvec2(layer_vertex(o, mirror_above, k, mirrored, centre).position);
        EXPECT_NEAR(glm::length(a + b - 2.0 * centre), 0.0, 1e-9) << k;
    }
    // Grazing: theta -> 0 leaves every layer at its size; the growth is monotone in theta.
    double previous = -1.0;
    for (double theta = 0.0; theta <= pi / 2 + 1e-12; theta += pi / 40) {
        const glm::dvec3 eye = p + 3000.0 * glm::dvec3(std::cos(theta), 0, std::sin(theta));
        const LayerColumn c = layer_column(o, eye, p, n);
        const double grown = glm::length(glm::dvec2(layer_vertex(o, c, 15, p, centre).position) - centre) - d;
        EXPECT_NEAR(grown, 0.015 * d * std::sin(theta), 1e-9) << theta;
        EXPECT_GT(grown, previous) << theta;
        previous = grown;
    }
    // The column depends on the eye's distance and elevation only: turning the eye about the
    // normal changes nothing, and an eye below sees the mirrored eye's column.
    for (double azimuth : {0.3, 1.7, 4.0}) {
        const glm::dvec3 eye = p + glm::dvec3(800 * std::cos(azimuth), 800 * std::sin(azimuth), 600);
        const LayerColumn c = layer_column(o, eye, p, n);
        const LayerColumn ref = layer_column(o, p + glm::dvec3(800, 0, 600), p, n);
        EXPECT_NEAR(c.spacing, ref.spacing, 1e-12);
        EXPECT_NEAR(c.count, ref.count, 1e-12);
        EXPECT_NEAR(c.sin_theta, 0.6, 1e-12);
        const LayerColumn below = layer_column(o, p + glm::dvec3(eye.x - p.x, eye.y - p.y, -600), p, n);
        EXPECT_NEAR(below.sin_theta, c.sin_theta, 1e-15);
        EXPECT_NEAR(below.count, c.count, 1e-12);
    }
}

TEST(LayerFormulas, ElevationAngle)
{
    const glm::dvec3 up{0, 0, 1}, p{10, 20, 30};
    EXPECT_NEAR(elevation_angle(p + glm::dvec3(0, 0, 500), p, up), pi / 2.0, 1e-15);
    EXPECT_EQ(elevation_angle(p + glm::dvec3(500, 0, 0), p, up), 0.0);
    EXPECT_NEAR(elevation_angle(p + glm::dvec3(100, 0, 100), p, up), pi / 4.0, 1e-15);
    // Below the plane: the same angle as the mirrored eye.
    EXPECT_NEAR(elevation_angle(p + glm::dvec3(100, 0, -100), p, up), pi / 4.0, 1e-15);
    EXPECT_EQ(elevation_angle(p, p, up), 0.0);  // eye at the point (L = 0)
    EXPECT_NEAR(elevation_angle(p + glm::dvec3(0, 0, 1e7), p, up), pi / 2.0, 1e-15);
}
