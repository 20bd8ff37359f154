// The layer stack per vertex (layer_column, layer_vertex), its texture atlas, the stack over a
// fitted network of patches, and its options ([Thesis] (2.6)-(2.10): layer_formulas_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <tuple>

#include <glm/geometric.hpp>

#include "fog_test_terrains.hpp"
#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/layers/layer_stack.hpp"
#include "kiri/geometry/scene/scene.hpp"
#include "layer_test_stacks.hpp"

using namespace kiri::geometry;
using kiri::InputError;
using kiri::test::options_15;

namespace {

const double pi = std::acos(-1.0);

bool finite(const LayerVertex& v)
{
    return std::isfinite(v.position.x) && std::isfinite(v.position.y) && std::isfinite(v.position.z) &&
        std::isfinite(v.alpha) && std::isfinite(v.exponent);
}

}  // namespace

// ---- Per-vertex columns -------------------------------------------------------------------

TEST(LayerColumn, FarEyeGivesTheReferenceStack)
{
    const LayerOptions o = options_15();
    const glm::dvec3 p{0, 0, 100}, n{0, 0, 1};
    for (const glm::dvec3 eye : {glm::dvec3(0, 0, 1e7), glm::dvec3(1e7, 0, 100), glm::dvec3(0, 0, 2100)}) {
        const LayerColumn c = layer_column(o, eye, p, n);
        EXPECT_EQ(c.spacing, 10.0);
        EXPECT_EQ(c.count, 15.0);
        for (int i = 0; i <= 15; ++i) {
            const LayerVertex v = layer_vertex(o, c, i, p, {0, 0});
            EXPECT_NEAR(v.alpha, 1.0 - 0.9 * i / 15, 1e-15);
            EXPECT_EQ(v.exponent, 1.0);
            EXPECT_NEAR(v.position.z, 100.0 + 10.0 * i, 1e-12);
        }
        EXPECT_EQ(layer_vertex(o, c, 16, p, {0, 0}).alpha, 0.0);  // above the stack
    }
}

TEST(LayerColumn, ApproachingFromTheSideKeepsTheThickness)
{
    // Narrowing depends on the distance alone: an eye coming level with the point narrows the
    // spacing as one coming from above, and the added layers keep T0 = r n (2.9).
    const LayerOptions o = options_15();
    const glm::dvec3 p{0, 0, 100}, n{0, 0, 1};
    for (double L : {1999.0, 1000.0, 400.0, 250.0}) {
        const LayerColumn c = layer_column(o, p + glm::dvec3(L, 0, 0), p, n);
        EXPECT_NEAR(c.spacing, L / 200.0, 1e-13) << L;
        EXPECT_NEAR(c.count * c.spacing, o.thickness, 1e-12);
        // The opacity correction's exponent r / r0: thinner layers, each more transparent.
        EXPECT_NEAR(layer_vertex(o, c, 3, p, {0, 0}).exponent, L / 2000.0, 1e-15);
    }
    // Without narrowing the spacing stays.
    LayerOptions fixed = o;
    fixed.narrowing = false;
    EXPECT_EQ(layer_column(fixed, p + glm::dvec3(0, 0, 300), p, n).spacing, 10.0);
}

TEST(LayerColumn, PartialTopLayerFadesIn)
{
    const LayerOptions o = options_15();
    const glm::dvec3 p{0, 0, 0}, n{0, 0, 1};
    const LayerColumn c = layer_column(o, {0, 0, 1900}, p, n);  // n = 15.789...
    ASSERT_GT(c.count, 15.0);
    ASSERT_LT(c.count, 16.0);
    const double top = layer_vertex(o, c, 16, p, {0, 0}).alpha;
    EXPECT_NEAR(top, (c.count - 15.0) * layer_alpha(c.count, c.count), 1e-15);
    // Continuity: just below the reference distance the new layer is almost invisible.
    const LayerColumn near_ref = layer_column(o, {0, 0, 1999.999}, p, n);
    EXPECT_LT(layer_vertex(o, near_ref, 16, p, {0, 0}).alpha, 1e-5);
}

TEST(LayerColumn, SingularEyes)
{
    const LayerOptions o = options_15();
    const glm::dvec3 p{5, 5, 100}, n{0, 0, 1};
    // Eye at the point (L = 0): spacing at its floor, count at the cap, everything finite.
    const LayerColumn at = layer_column(o, p, p, n);
    EXPECT_EQ(at.spacing, o.thickness / o.max_count);
    EXPECT_EQ(at.count, double(o.max_count));
    EXPECT_EQ(at.sin_theta, 0.0);
    for (int i : {0, 1, 60, 120, 121})
        EXPECT_TRUE(finite(layer_vertex(o, at, i, p, {0, 0}))) << i;
    // Eye below the base surface: the same column as the mirrored eye above.
    const LayerColumn below = layer_column(o, p + glm::dvec3(30, 0, -400), p, n);
    const LayerColumn above = layer_column(o, p + glm::dvec3(30, 0, 400), p, n);
    EXPECT_EQ(below.spacing, above.spacing);
    EXPECT_EQ(below.count, above.count);
    EXPECT_NEAR(below.sin_theta, above.sin_theta, 1e-15);
    // Eye very far: the reference stack, finite.
    const LayerColumn far = layer_column(o, {1e7, -1e7, 1e7}, p, n);
    EXPECT_EQ(far.count, 15.0);
    EXPECT_TRUE(finite(layer_vertex(o, far, 15, p, {0, 0})));
}

TEST(LayerColumn, ZeroAndOneLayer)
{
    LayerOptions o = options_15();
    o.count = 0;
    const glm::dvec3 p{0, 0, 0}, n{0, 0, 1};
    const LayerColumn c0 = layer_column(o, {0, 0, 50}, p, n);
    EXPECT_EQ(layer_vertex(o, c0, 0, p, {0, 0}).alpha, 1.0);
    EXPECT_EQ(layer_vertex(o, c0, 0, p, {0, 0}).position, p);
    o.count = 1;
    o.thickness = 10.0;  // r0 = 10, L0 = 2000
    const LayerColumn c1 = layer_column(o, {0, 0, 5000}, p, n);
    EXPECT_EQ(c1.count, 1.0);
    EXPECT_EQ(layer_vertex(o, c1, 0, p, {0, 0}).alpha, 1.0);
    EXPECT_NEAR(layer_vertex(o, c1, 1, p, {0, 0}).alpha, 0.1, 1e-15);
    EXPECT_EQ(layer_vertex(o, c1, 1, p, {0, 0}).position.z, 10.0);
}

TEST(LayerColumn, EnlargementAboutTheCentre)
{
    LayerOptions o = options_15();
    o.shading = LayerShading::source;  // the shading the enlargement is drawn in (layers_enlarge)
    const glm::dvec3 p{1000, -500, 0}, n{0, 0, 1};
    const glm::dvec2 centre{200, 100};
    // Straight above (theta = pi/2): P_k = 1 + k / 1000.
    const LayerColumn top = layer_column(o, p + glm::dvec3(0, 0, 3000), p, n);
    EXPECT_NEAR(top.sin_theta, 1.0, 1e-15);
    const LayerVertex v = layer_vertex(o, top, 10, p, centre);
    const glm::dvec2 expect = centre + (1.0 + 10 / 1000.0) * (glm::dvec2(p) - centre);
    EXPECT_NEAR(v.position.x, expect.x, 1e-12);
    EXPECT_NEAR(v.position.y, expect.y, 1e-12);
    // From the side (theta = 0): no enlargement.
    const LayerColumn side = layer_column(o, p + glm::dvec3(3000, 0, 0), p, n);
    EXPECT_EQ(layer_vertex(o, side, 10, p, centre).position.x, p.x);
    o.enlargement = false;
    EXPECT_EQ(layer_vertex(o, layer_column(o, p + glm::dvec3(0, 0, 3000), p, n), 10, p, centre).position.x, p.x);
    // The medium shading stands for the Medium's fog where it lies: never enlarged.
    o.enlargement = true;
    o.shading = LayerShading::medium;
    EXPECT_FALSE(layers_enlarge(o));
    EXPECT_EQ(layer_vertex(o, layer_column(o, p + glm::dvec3(0, 0, 3000), p, n), 10, p, centre).position.x, p.x);
}

TEST(LayerColumn, DissipationThinsTopLayersFirst)
{
    LayerOptions o = options_15();
    EXPECT_EQ(layer_dissipation(o, 10, 15), 1.0);  // no half-life: no dissipation
    o.optics.dissipation_half_life = 60.0;
    o.optics.time = 0.0;
    EXPECT_EQ(layer_dissipation(o, 10, 15), 1.0);
    o.optics.time = 60.0;
    EXPECT_NEAR(layer_dissipation(o, 0, 15), 0.5, 1e-15);
    EXPECT_NEAR(layer_dissipation(o, 15, 15), 0.25, 1e-15);
    double previous = 1.0;
    for (double t : {10.0, 30.0, 90.0, 300.0}) {
        o.optics.time = t;
        const double d = layer_dissipation(o, 5, 15);
        EXPECT_LT(d, previous);
        EXPECT_LT(layer_dissipation(o, 12, 15), d);
        previous = d;
    }
}

// ---- Texture --------------------------------------------------------------------------------

TEST(LayerTexture, BorderAlpha)
{
    const BorderMask all_sides = 0x0F;
    EXPECT_EQ(border_alpha(all_sides, 0.5, 0.5, 0.5), 1.0);  // a single patch: opaque centre
    EXPECT_EQ(border_alpha(all_sides, 0.0, 0.5, 0.5), 0.0);
    EXPECT_EQ(border_alpha(all_sides, 0.5, 1.0, 0.5), 0.0);
    EXPECT_NEAR(border_alpha(all_sides, 0.25, 0.5, 0.5), 0.5, 1e-15);  // smoothstep(1/2)
    EXPECT_EQ(border_alpha(0, 0.0, 0.0, 0.5), 1.0);                    // interior patch: uniform
    // Side v = 0 only: alpha depends on v alone, zero on that side, one from w on.
    EXPECT_EQ(border_alpha(0x01, 0.3, 0.0, 0.4), 0.0);
    EXPECT_EQ(border_alpha(0x01, 0.0, 0.4, 0.4), 1.0);
    EXPECT_EQ(border_alpha(0x01, 0.9, 0.2, 0.4), border_alpha(0x01, 0.1, 0.2, 0.4));
    // A border corner (0,0): radial fade meeting the neighbours' side fades along the sides.
    EXPECT_EQ(border_alpha(0x10, 0.0, 0.0, 0.5), 0.0);
    EXPECT_EQ(border_alpha(0x10, 0.0, 0.2, 0.5), border_alpha(0x01, 0.7, 0.2, 0.5));
}

TEST(LayerTexture, AtlasHasOneTilePerMaskAndStaysInsideIt)
{
    LayerTextureOptions options;
    options.resolution = 16;
    const LayerTexture t = make_layer_texture({0, 3, 3, 0x0F, 0x10, 0}, options);
    EXPECT_EQ(t.tiles.size(), 4u);
    EXPECT_EQ(t.width % 16, 0);
    for (const auto& [mask, origin] : t.tiles) {
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x) {
                const double a = border_alpha(mask, x / 15.0, y / 15.0, options.fade_width);
                const auto texel = t.rgba[(std::size_t(origin.y + y) * t.width + origin.x + x) * 4 + 3];
                EXPECT_EQ(texel, std::lround(a * 255.0));
            }
        const glm::dvec2 lo = t.atlas_uv(mask, 0, 0), hi = t.atlas_uv(mask, 1, 1);
        EXPECT_NEAR(lo.x * t.width, origin.x + 0.5, 1e-12);
        EXPECT_NEAR(hi.y * t.height, origin.y + 15.5, 1e-12);
    }
    options.resolution = 2;
    EXPECT_THROW(make_layer_texture({0}, options), InputError);
}

// ---- The stack over a fitted network ------------------------------------------------------

namespace {
struct FittedHills {
    Terrain terrain{kiri::test::make_heightfield(101, 101, 20.0, -1000.0, -1000.0, kiri::test::hills)};
    BaseSurface surface;
    Tessellation tessellation;
    FittedHills()
        : surface(build_control_mesh({{{-900, -850}, {880, -700}, {700, 800}, {-600, 650}}}, terrain, {250.0}),
                  SurfaceKind::gregory)
    {
        surface.fit(terrain, FitOptions{});
        tessellation = tessellate(surface, {6});
    }
};
const FittedHills& hills()
{
    static const FittedHills h;
    return h;
}
}  // namespace

TEST(LayerStack, NoCracksBetweenPatchesInAnyLayer)
{
    const auto& h = hills();
    LayerOptions o = options_15();
    const LayerBase base = make_layer_base(h.surface, h.tessellation, o);
    ASSERT_GT(h.surface.num_patches(), 8);
    // Group base vertices by position: copies on shared edges and corners.
    std::map<std::tuple<double, double, double>, std::vector<std::size_t>> copies;
    for (std::size_t v = 0; v < base.position.size(); ++v)
        copies[{base.position[v].x, base.position[v].y, base.position[v].z}].push_back(v);
    int shared = 0;
    for (const glm::dvec3 eye : {glm::dvec3(-200, -300, 800), glm::dvec3(3000, -4000, 2500), glm::dvec3(0, 0, 450)}) {
        const std::vector<LayerMesh> layers = build_layers(base, o, eye);
        ASSERT_GE(layers.size(), 16u);
        for (const auto& [key, list] : copies) {
            if (list.size() < 2)
                continue;
            ++shared;
            for (const LayerMesh& layer : layers)
                for (std::size_t k = 1; k < list.size(); ++k) {
                    const LayerVertex& a = layer.vertices[list[0]];
                    const LayerVertex& b = layer.vertices[list[k]];
                    ASSERT_EQ(a.position, b.position) << "layer " << layer.index;
                    ASSERT_EQ(a.alpha, b.alpha);
                    ASSERT_EQ(a.exponent, b.exponent);
                }
        }
    }
    EXPECT_GT(shared, 100);
}

TEST(LayerStack, TextureIsContinuousAcrossSharedEdges)
{
    const auto& h = hills();
    const TriMesh& m = h.tessellation.mesh;
    OpenMesh::VPropHandleT<int> pid;
    ASSERT_TRUE(m.get_property_handle(pid, patch_id_property));
    std::map<std::tuple<double, double>, std::vector<double>> alpha_at;
    for (auto v : m.vertices()) {
        const auto& p = m.point(v);
        const auto& t = m.texcoord2D(v);
        const BorderMask mask = patch_border_mask(h.surface.control(), m.property(pid, v));
        alpha_at[{p[0], p[1]}].push_back(border_alpha(mask, t[0], t[1], 0.5));
    }
    int checked = 0, zero = 0;
    for (const auto& [key, list] : alpha_at) {
        for (double a : list)
            EXPECT_NEAR(a, list[0], 1e-12);
        checked += list.size() > 1;
        zero += list[0] == 0.0;
    }
    EXPECT_GT(checked, 100);
    EXPECT_GT(zero, 20);  // the outer border is transparent
}

TEST(LayerStack, EyeDecidesTheCount)
{
    const auto& h = hills();
    LayerOptions o = options_15();
    const LayerBase base = make_layer_base(h.surface, h.tessellation, o);
    EXPECT_EQ(layers_for_eye(base, o, {0, 0, 1e7}), 15);
    EXPECT_EQ(layers_for_eye(base, o, base.position[0]), o.max_count);
    const int near = layers_for_eye(base, o, {0, -1500, 700});
    EXPECT_GT(near, 15);
    EXPECT_LE(near, o.max_count);
    o.narrowing = false;
    EXPECT_EQ(layers_for_eye(base, o, base.position[0]), 15);
    // The centre of enlargement lies inside the footprint.
    EXPECT_GT(base.centre.x, -600.0);
    EXPECT_LT(base.centre.x, 600.0);
}

// The eye's place in the stack is taken over its own (x, y), where the drawn triangles put the
// layers: on a sloping base the nearest vertex lies higher or lower than the base under the eye,
// by more than a spacing here. A base of two triangles on the plane z = 0.2 x + 100, its vertices
// 100 m apart; the eye 60 m from the nearest one, 10.7 m above the plane under it.
TEST(LayerStack, TheEyesPlaceIsTakenOverItsOwnPoint)
{
    LayerOptions o = options_15();
    o.narrowing = false;  // r = 10 m everywhere
    LayerBase base;
    const auto plane = [](double x) { return 0.2 * x + 100.0; };
    for (const glm::dvec2 xy : {glm::dvec2(0, 0), glm::dvec2(100, 0), glm::dvec2(0, 100), glm::dvec2(100, 100)}) {
        base.position.push_back({xy.x, xy.y, plane(xy.x)});
        base.normal.push_back(glm::normalize(glm::dvec3(-0.2, 0.0, 1.0)));
        base.atlas_uv.push_back({0.0, 0.0});
    }
    base.triangles = {0, 1, 3, 0, 3, 2};
    const glm::dvec3 eye(60.0, 20.0, plane(60.0) + 10.7);
    const LayerStackUnder under = layer_stack_under(base, o, eye);
    EXPECT_NEAR(under.base_z, plane(60.0), 1e-12);
    EXPECT_NEAR(under.spacing, 10.0, 1e-12);
    // Layers 0 and 1 lie under the eye (its nearest vertex, (100, 0, 120), 2.7 m under it, says one).
    EXPECT_EQ(layers_under_eye(base, o, eye, 15), 2);
    EXPECT_EQ(layers_under_eye(base, o, eye - glm::dvec3(0.0, 0.0, 0.8), 15), 1);
    EXPECT_EQ(layers_under_eye(base, o, eye - glm::dvec3(0.0, 0.0, 12.0), 15), 0);  // under the base
    // Beyond the base's edge: the nearest vertex's column.
    const LayerStackUnder outside = layer_stack_under(base, o, {-50.0, 50.0, 200.0});
    EXPECT_EQ(outside.base_z, plane(0.0));
}

TEST(LayerOptionsJson, RoundTripAndRefusals)
{
    const std::string scene = R"({"terrain": {"path": "x.tif"}, "fog": {"thickness": 120},
        "layers": {"count": 30, "opacity": 0.2, "narrowing": false, "wind": [3, -1], "dissipation_half_life": 90}})";
    const Scene s = parse_scene(scene, "s.json", ".");
    EXPECT_EQ(s.layers.count, 30);
    EXPECT_EQ(s.layers.opacity, 0.2);
    EXPECT_FALSE(s.layers.narrowing);
    EXPECT_EQ(s.medium.wind, glm::dvec2(3, -1));  // the old names of the medium's keys
    const Scene back = parse_scene(scene_to_json(s), "s.json", ".");
    EXPECT_EQ(back.layers.count, 30);
    EXPECT_EQ(back.medium.dissipation_half_life, 90.0);
    const LayerOptions world = world_layer_options(s);
    EXPECT_EQ(world.thickness, 120.0);
    auto refused = [](const std::string& layers, const std::string& pointer) {
        try {
            parse_scene(R"({"terrain": {"path": "x.tif"}, "layers": )" + layers + "}", "s.json", ".");
        } catch (const InputError& e) {
            EXPECT_EQ(e.field(), pointer) << e.what();
            return;
        }
        ADD_FAILURE() << layers << " was accepted";
    };
    refused(R"({"count": -1})", "/layers/count");
    refused(R"({"count": 2.5})", "/layers/count");
    refused(R"({"opacity": 1})", "/layers/opacity");
    refused(R"({"fade_width": 0})", "/layers/fade_width");
    refused(R"({"texture_size": 2})", "/layers/texture_size");
    refused(R"({"narrowing": "yes"})", "/layers/narrowing");
    refused(R"({"colour": 1})", "/layers/colour");
    refused(R"({"count": 30, "max_count": 20})", "/layers/max_count");
}
