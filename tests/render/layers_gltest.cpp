// The layer pass on an analytic terrain: fog where the ground is under the stack, none where a
// summit rises above it, nothing drawn below the ground or off-screen, uploads only once.
#include <gtest/gtest.h>

#include <deque>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include <glm/matrix.hpp>

#include "kiri/geometry/medium/fog_lighting.hpp"
#include "kiri/geometry/scene/fog_spec.hpp"
#include "kiri/geometry/layers/layer_stack.hpp"
#include "kiri/geometry/medium/medium.hpp"
#include "kiri/render/tone_map.hpp"
#include "kiri/render/camera.hpp"
#include "kiri/render/renderer.hpp"
#include "render/render_fixture.hpp"

namespace {

using kiri::render::Camera;
using kiri::render::Image;
using kiri::render::Renderer;
namespace g = kiri::geometry;

class LayersGl : public kiri::test::GlTest {
protected:
    // A fog lake over the Gaussian hill: stack from 50 m to 150 m, the 300 m summit above it.
    static void SetUpTestSuite()
    {
        GlTest::SetUpTestSuite();
        hill() = std::make_unique<g::Terrain>(kiri::test::gaussian_hill());
        g::FogSpec spec;
        spec.footprint = g::rectangle_footprint({-560, -560}, {560, 560});
        spec.patch_size = 280.0;
        spec.surface = g::SurfaceKind::gregory;
        spec.fit.mode = g::FitMode::lake;
        spec.fit.altitude = 150.0;
        spec.tessellation.level = 6;
        g::BaseSurface surface = g::fog_control_surface(*hill(), spec);
        g::fit_fog_surface(surface, *hill(), spec);
        g::Tessellation tessellation = g::tessellate(surface, spec.tessellation);
        authored() = std::make_unique<Authored>(Authored{std::move(surface), std::move(tessellation)});
    }
    static void TearDownTestSuite()
    {
        authored().reset();
        hill().reset();
    }
    static std::unique_ptr<g::Terrain>& hill()
    {
        static std::unique_ptr<g::Terrain> t;
        return t;
    }
    // The lake's fitted surface and its tessellation.
    struct Authored {
        g::BaseSurface surface;
        g::Tessellation tessellation;
    };
    static std::unique_ptr<Authored>& authored()
    {
        static std::unique_ptr<Authored> a;
        return a;
    }
    static g::LayerOptions options(double base_offset = -100.0)
    {
        g::LayerOptions o;
        o.count = 10;
        o.thickness = 100.0;
        o.base_offset = base_offset;
        o.shading = g::LayerShading::source;  // the medium's shading has its own test below
        o.opacity = 0.3;
        o.optics.detail = 0.0;
        o.ground_fade = 5.0;
        return o;
    }
    // The layers as slabs of the Medium (LayerShading::medium), 0.01 / m at full density.
    static g::LayerOptions medium_options()
    {
        g::LayerOptions o = options();
        o.shading = g::LayerShading::medium;
        o.optics.extinction = 0.01;
        return o;
    }
    // Black fog (albedo 0, 0.01 / m), the layers flat and 10 m apart (no narrowing, no enlargement):
    // the frame over the bare terrain is the transmittance.
    static g::LayerOptions flat_black_options()
    {
        g::LayerOptions o = medium_options();
        o.optics.albedo = 0.0;
        o.optics.extinction = 0.01;
        o.narrowing = o.enlargement = false;
        return o;
    }
    static Camera above()
    {
        Camera c;
        c.position = {0.0, -1.0, 3000.0};
        c.target = {0.0, 0.0, 0.0};
        c.fov_y_deg = 30.0;
        return c;
    }
    // An eye 25 m over the stack's base (at 75 m) at (380, 380), looking out from the hill and up.
    static Camera climbing(double degrees, double fov)
    {
        const double a = degrees * std::acos(-1.0) / 180.0;
        const glm::dvec2 out = glm::normalize(glm::dvec2(380.0, 380.0));
        Camera c;
        c.position = {380.0, 380.0, 75.0};
        c.target = c.position + glm::dvec3(out * std::cos(a), std::sin(a));
        c.fov_y_deg = fov;
        return c;
    }
    static const std::uint8_t* pixel(const Image& image, const glm::dvec2& p)
    {
        return &image.rgba[(std::size_t(p.y) * image.width + std::size_t(p.x)) * 4];
    }
    // The lake's black fog (albedo 0) against the Medium it stands for, the sun with no sky light:
    // the frame over the bare terrain, then with the layers `o` over it (last_layers: their count).
    struct BlackFog {
        kiri::render::RadianceImage bare, fog;
        int last_layers = 0;
    };
    static BlackFog black_fog(const Camera& cam, int w, int h, const g::Medium& medium, const g::LayerOptions& o)
    {
        kiri::render::SunLight sun;
        sun.ambient = glm::dvec3(0.0);
        Renderer renderer;
        renderer.set_terrain(*hill());
        renderer.set_sun(sun);
        renderer.set_sun_medium(&medium, {});
        BlackFog b;
        renderer.render(cam, w, h);
        b.bare = renderer.read_radiance();
        const g::LayerBase base = g::make_layer_base(authored()->surface, authored()->tessellation, o);
        renderer.set_layers(base, o);
        renderer.render(cam, w, h);
        b.fog = renderer.read_radiance();
        b.last_layers = renderer.last_stats().layers;
        return b;
    }
};

double luminance(const std::uint8_t* p) { return 0.3 * p[0] + 0.6 * p[1] + 0.1 * p[2]; }

// The ray from the camera through the centre of pixel (x, y) (row 0 at the top).
glm::dvec3 pixel_ray(const Camera& c, int x, int y, int w, int h)
{
    const glm::dmat4 to_world = glm::inverse(c.projection(double(w) / double(h)) * c.view());
    const glm::dvec4 p = to_world * glm::dvec4((x + 0.5) / w * 2.0 - 1.0, 1.0 - (y + 0.5) / h * 2.0, 0.5, 1.0);
    return glm::normalize(glm::dvec3(p) / p.w - c.position);
}

// The Medium's transmittance along a ray from `eye` to the terrain (midpoints every 0.25 m): the
// oracle of black fog's frame over the bare one.
double medium_transmittance(const g::Medium& medium, const g::Terrain& terrain, const glm::dvec3& eye,
                            const glm::dvec3& ray, double& reach)
{
    const double dt = 0.25;
    double tau = 0.0;
    for (reach = 0.5 * dt; reach < 5000.0; reach += dt) {
        const glm::dvec3 p = eye + reach * ray;
        if (p.z < terrain.height(p.x, p.y))
            break;
        tau += medium.options().extinction * medium.density(p) * dt;
    }
    return std::exp(-tau);
}

TEST_F(LayersGl, FogCoversTheLowGroundNotTheSummit)
{
    const int w = 200, h = 200;
    Renderer renderer;
    renderer.set_terrain(*hill());
    const Image bare = renderer.render(above(), w, h);
    const g::LayerOptions o = options();
    const g::LayerBase base = g::make_layer_base(authored()->surface, authored()->tessellation, o);
    renderer.set_layers(base, o);
    const Image fog = renderer.render(above(), w, h);
    EXPECT_EQ(renderer.last_stats().layers, 10);
    // The summit (300 m) rises above the stack's top (150 m): unchanged.
    const glm::dvec2 summit = kiri::render::project_to_pixel(above(), {0.0, 0.0, 300.0}, w, h);
    EXPECT_LE(std::abs(luminance(pixel(fog, summit)) - luminance(pixel(bare, summit))), 1.0);
    // The plain at 450 m from the centre (ground ~ 60 m, under 90 m of fog): brighter, greyer.
    for (const glm::dvec2 xy : {glm::dvec2(450, 0), glm::dvec2(0, -450), glm::dvec2(-420, 380)}) {
        const double z = hill()->height(xy.x, xy.y);
        ASSERT_LT(z, 80.0);
        const glm::dvec2 p = kiri::render::project_to_pixel(above(), {xy.x, xy.y, z}, w, h);
        EXPECT_GT(luminance(pixel(fog, p)), luminance(pixel(bare, p)) + 20.0) << xy.x << ", " << xy.y;
    }
}

// Seen straight down over flat fog, the medium-shaded stack is a pile of slabs: layer i has
// alpha 1 - exp(-sigma rho_i r w_i) (w_i its slab's share of r, layer_slab_share) and source J_i = geometry::fog_source(sun through the fog
// above it), composited over the ground: L = J_i alpha_i + (1 - alpha_i) L, bottom to top.
// With the reference stack (narrowing and enlargement off) and with the view-dependent one the
// eye 350 m above the base sees ([Thesis] (2.8)-(2.9) as docs/layers.md reads them): spacing
// r = L / 200 = 1.75 m, a real-valued count n = T0 / r = 57.1 with the top layer faded in by
// n + 1 - i. The enlargement (2.10) is asked for too, and the medium shading leaves it out
// (layers_enlarge): each layer's copy of the base point is the point itself.
TEST_F(LayersGl, MediumShadingIsThePileOfSlabs)
{
    const int w = 64, h = 64;
    const glm::dvec2 xy(380.0, 380.0);  // ground 30 m, under the whole stack (50..150 m), coverage 1
    ASSERT_LT(hill()->height(xy.x, xy.y), 40.0);
    Camera down;
    down.position = {xy.x, xy.y - 1.0, 400.0};
    down.target = {xy.x, xy.y, 0.0};
    down.fov_y_deg = 20.0;
    Renderer renderer;
    renderer.set_terrain(*hill());
    const kiri::render::SunLight sun;  // the renderer's default light
    const Image bare = renderer.render(down, w, h);
    const std::uint8_t* ground_px = pixel(bare, {w / 2, h / 2});
    auto radiance_of = [](double c) { return -std::log(1.0 - std::pow(c / 255.0, 2.2)) / 0.7; };
    const double T0 = 100.0, ground_z = hill()->height(xy.x, xy.y);
    // The stack at its base (50 m, over the ground), and lowered by 51 m so that the ground cuts
    // it 9 m under layer 4 (the reference stack's): the layers under the ground are hidden, the
    // first over it holds the fog down to the ground (layer_slab_over_ground).
    // The pass keeps a base by its vertices' address: every base stays alive, so none reuses one.
    std::deque<g::LayerBase> bases;
    for (const double offset : {0.0, -51.0})
        for (const bool view_dependent : {false, true})
            for (const double sigma : {0.004, 0.03}) {
                const double base_z = 50.0 + offset;
                g::LayerOptions o = options(-100.0 + offset);  // the fixture's surface is at 150 m
                o.shading = g::LayerShading::medium;
                o.narrowing = view_dependent;
                o.enlargement = view_dependent;
                o.optics.extinction = sigma;
                const g::LayerBase& base =
                    bases.emplace_back(g::make_layer_base(authored()->surface, authored()->tessellation, o));
                renderer.set_layers(base, o);
                const Image fog = renderer.render(down, w, h);
                const int top = renderer.last_stats().layers;
                const glm::dvec3 s = glm::normalize(sun.direction);
                const glm::dvec3 view = glm::normalize(glm::dvec3(xy, base_z + 0.5 * T0) - down.position);
                const g::FogLight light{sun.color * sun.intensity, sun.ambient, s.z};
                glm::dvec3 expected(radiance_of(ground_px[0]), radiance_of(ground_px[1]), radiance_of(ground_px[2]));
                for (int i = 0; i <= top; ++i) {
                    double r = T0 / 10.0;
                    if (view_dependent)  // the narrowing at the base point under the pixel
                        r = glm::length(glm::dvec3(xy, base_z) - down.position) / 200.0;
                    const double n = T0 / r, hi = std::min(double(i), n) / n;
                    const double rho = std::clamp(n + 1.0 - i, 0.0, 1.0) * (1.0 - 0.9 * hi);
                    const double clearance = base_z + i * r - ground_z;
                    if (clearance < 0.0)
                        continue;  // under the ground
                    const double slab = g::layer_slab_over_ground(g::layer_slab_share(n, i), i, r, clearance);
                    const double alpha = 1.0 - std::exp(-sigma * rho * r * slab / std::abs(view.z));
                    const double tau_sun = sigma * T0 * ((1.0 - hi) - 0.45 * (1.0 - hi * hi)) / s.z;
                    const glm::dvec3 j = g::fog_source(light, o.optics, glm::dot(view, s), tau_sun);
                    expected = j * alpha + (1.0 - alpha) * expected;
                }
                EXPECT_EQ(top, view_dependent ? (offset == 0.0 ? 58 : 50) : 10);  // ceil(T0 / r) with the narrowing
                const std::uint8_t* got = pixel(fog, {w / 2, h / 2});
                std::printf("    %s, base at %.0f m, sigma %.3f: %d layers, got %d %d %d, expected %.2f %.2f %.2f\n",
                            view_dependent ? "view-dependent" : "reference stack", base_z, sigma, top, got[0], got[1],
                            got[2], 255.0 * kiri::render::tone_map(expected[0]),
                            255.0 * kiri::render::tone_map(expected[1]), 255.0 * kiri::render::tone_map(expected[2]));
                // Measured within 0.6 of a grey level in every case (the 8-bit frame's rounding and
                // the GPU's float).
                for (int c = 0; c < 3; ++c)
                    EXPECT_NEAR(got[c], 255.0 * kiri::render::tone_map(expected[c]), 1.0)
                        << "sigma " << sigma << " channel " << c << (view_dependent ? " view-dependent" : "")
                        << " base offset " << offset;
                if (sigma > 0.01) {
                    int shows = 0;  // the grey fog over the coloured ground, in its most changed channel
                    for (int c = 0; c < 3; ++c)
                        shows = std::max(shows, std::abs(got[c] - ground_px[c]));
                    EXPECT_GT(shows, 8) << "the fog shows";
                }
            }
}

TEST_F(LayersGl, StackBelowTheGroundDrawsNothing)
{
    const int w = 160, h = 120;
    Renderer renderer;
    renderer.set_terrain(*hill());
    const Image bare = renderer.render(above(), w, h);
    const g::LayerOptions o = options(-1000.0);  // 850 .. 950 m below the lake's top: underground
    const g::LayerBase base = g::make_layer_base(authored()->surface, authored()->tessellation, o);
    renderer.set_layers(base, o);
    const Image fog = renderer.render(above(), w, h);
    EXPECT_EQ(renderer.last_stats().layers, 10);  // drawn, and hidden by the depth test
    EXPECT_EQ(fog.rgba, bare.rgba);
}

// The level of detail (layer_lod.hpp): seen from afar every patch is a few pixels and is drawn
// as its two corner triangles; from close by the patches near the eye keep the full grid and
// the far ones get coarser. The picture is the full tessellation's: the cells are points of the
// same surface.
TEST_F(LayersGl, LevelOfDetailCoarsensFarPatchesAndKeepsThePicture)
{
    const int w = 240, h = 160;
    Renderer renderer;
    renderer.set_terrain(*hill());
    g::LayerOptions o = medium_options();
    const g::LayerBase base = g::make_layer_base(authored()->surface, authored()->tessellation, o);
    ASSERT_EQ(base.grid.level, 6);
    const int patches = base.grid.patches, full = int(base.triangles.size() / 3);
    ASSERT_EQ(full, patches * 2 * 6 * 6);
    struct View {
        Camera camera;
        double lod;
    };
    // A frame this small draws its layers at full resolution (the reduced target's floor): cells
    // of 32 pixels there are the default's 16 at half resolution; and cells of 64, to see levels
    // mix.
    View far{{}, 32.0}, low{{}, 64.0};
    far.camera.position = {0.0, -20000.0, 5000.0};
    far.camera.target = {0.0, 0.0, 100.0};
    far.camera.fov_y_deg = 12.0;
    low.camera.position = {-300.0, -700.0, 260.0};
    low.camera.target = {400.0, 600.0, 60.0};
    low.camera.fov_y_deg = 50.0;
    for (const View* v : {&far, &low}) {
        o.lod = 0.0;
        renderer.set_layers(base, o);
        const Image exact = renderer.render(v->camera, w, h);
        EXPECT_EQ(renderer.last_stats().layer_triangles, full);
        o.lod = v->lod;
        renderer.set_layers(base, o);
        const Image lod = renderer.render(v->camera, w, h);
        const int drawn = renderer.last_stats().layer_triangles;
        if (v == &far) {
            EXPECT_EQ(drawn, 2 * patches);
        } else {
            EXPECT_GT(drawn, 2 * patches);
            EXPECT_LT(drawn, full);
        }
        double sum = 0.0;
        int most = 0;
        for (std::size_t k = 0; k < exact.rgba.size(); ++k) {
            const int d = std::abs(int(exact.rgba[k]) - int(lod.rgba[k]));
            sum += d;
            most = std::max(most, d);
        }
        const double mean = sum / double(exact.rgba.size());
        std::printf("level of detail %.0f px: %d of %d triangles, mean difference %.3f, most %d levels\n", v->lod,
                    drawn, full, mean, most);
        EXPECT_LT(mean, 0.25);
        EXPECT_LE(most, 8);
    }
}

TEST_F(LayersGl, OffScreenStackIsCulledAndUploadsHappenOnce)
{
    const int w = 160, h = 120;
    Renderer renderer;
    renderer.set_terrain(*hill());
    const g::LayerOptions o = options();
    const g::LayerBase base = g::make_layer_base(authored()->surface, authored()->tessellation, o);
    renderer.set_layers(base, o);
    renderer.render(above(), w, h);
    EXPECT_EQ(renderer.last_stats().uploads, 3);  // terrain, layer base, ground heights
    renderer.set_layers(base, o);
    renderer.render(above(), w, h);
    EXPECT_EQ(renderer.last_stats().uploads, 0);
    Camera away;
    away.position = {0.0, -2000.0, 400.0};
    away.target = {0.0, -6000.0, 400.0};
    renderer.render(away, w, h);
    EXPECT_EQ(renderer.last_stats().layers, 0);
}

// Combined mode: the layers draw only the fog beyond near_start. A stack wholly nearer than that
// has nothing to draw, and its pass does not run; the picture is the same.
TEST_F(LayersGl, CombinedLayersWithNoShareInReachDrawNothing)
{
    const int w = 160, h = 120;
    Renderer renderer;
    renderer.set_terrain(*hill());
    const g::LayerOptions o = medium_options();
    const g::LayerBase base = g::make_layer_base(authored()->surface, authored()->tessellation, o);
    renderer.set_layers(base, o);
    g::FogPartition near_only;
    near_only.near_start = near_only.near_end = 1e6;  // the whole stack is nearer
    g::FogPartition far_only;
    far_only.near_start = far_only.near_end = 0.0;  // all of it is the layers'
    far_only.particle_share = near_only.particle_share = 0.0;
    renderer.set_fog_partition(far_only);
    const Image drawn = renderer.render(above(), w, h);
    EXPECT_GT(renderer.last_stats().layers, 0);
    renderer.set_fog_partition(near_only);
    const Image skipped = renderer.render(above(), w, h);
    EXPECT_EQ(renderer.last_stats().layers, 0);
    renderer.clear_layers();
    const Image bare = renderer.render(above(), w, h);
    EXPECT_EQ(skipped.rgba, bare.rgba);  // nothing of the layers' drawn
    EXPECT_NE(drawn.rgba, bare.rgba);    // where they have their share, fog
}

}  // namespace

TEST_F(LayersGl, ARayFromInsideCrossesEachLayerAtItsOwnSlant)
{
    // The eye in the stack, 90 m over its base, looking 20 degrees down at the ground: near the eye
    // the narrowing (2.8) spaces the layers by r = r0 L / L0, so layer i rises with the distance
    // from the eye, tilted by up to i r0 / L0 (0.4 here) from the base. A layer's optical depth along
    // the ray is its slab over the cosine between the ray and the layer's own surface. Black fog
    // (albedo 0, no sky light) only hides the ground: the frame over the bare one is the
    // transmittance, against the continuous slab's exp(-sigma integral of the profile / sin 20).
    const int w = 32, h = 32;
    const glm::dvec2 xy(380.0, 380.0);
    const double ground_z = hill()->height(xy.x, xy.y), base_z = 50.0, T0 = 100.0, eye_z = 140.0;
    const double slant = 20.0 * std::acos(-1.0) / 180.0;
    Camera cam;
    cam.position = {xy.x, xy.y - (eye_z - ground_z) / std::tan(slant), eye_z};
    cam.target = {xy.x, xy.y, ground_z};
    cam.fov_y_deg = 10.0;
    kiri::render::SunLight sun;
    sun.ambient = glm::dvec3(0.0);
    Renderer renderer;
    renderer.set_terrain(*hill());
    renderer.set_sun(sun);
    renderer.render(cam, w, h);
    const kiri::render::RadianceImage bare = renderer.read_radiance();
    g::LayerOptions o = options(-100.0);
    o.shading = g::LayerShading::medium;
    o.optics.extinction = 0.01;
    o.optics.albedo = 0.0;
    o.enlargement = false;
    const g::LayerBase base = g::make_layer_base(authored()->surface, authored()->tessellation, o);
    renderer.set_layers(base, o);
    renderer.render(cam, w, h);
    const kiri::render::RadianceImage fog = renderer.read_radiance();
    // From the eye down to the base: the profile 1 - 0.9 (z - base) / T0 integrated over z.
    const auto integral = [&](double z) { return z - 0.45 * z * z / T0; };
    const double expected =
        std::exp(-o.optics.extinction * (integral(eye_z - base_z) - integral(0.0)) / std::sin(slant));
    const std::size_t centre = (std::size_t(h / 2) * w + w / 2) * 4 + 1;  // green
    const double measured = double(fog.rgba[centre]) / double(bare.rgba[centre]);
    std::printf("    transmittance %.4f, the slab's %.4f\n", measured, expected);
    EXPECT_NEAR(measured / expected, 1.0, 0.03);
}

// With a Medium, the medium shading draws the Medium's fog where the Medium has it: its coverage
// (the border fade) and the wall at its grid's edge, as the reference and the froxels see it, not
// the atlas's border mask, which follows the base's patches (they reach past a fill's or a lake's
// cells, and past the grid). A Medium over the east half of the lake (x >= 100 m), at coverage
// 1/2: black fog seen straight down lets through the pile's transmittance with half the density
// there, and the whole frame west of the grid.
TEST_F(LayersGl, TheMediumShadingDrawsTheMediumsExtent)
{
    const int w = 32, h = 32;
    kiri::render::SunLight sun;
    sun.ambient = glm::dvec3(0.0);
    g::LayerOptions o = medium_options();
    o.optics.albedo = 0.0;
    o.optics.extinction = 0.02;
    o.narrowing = o.enlargement = false;
    const g::LayerBase base = g::make_layer_base(authored()->surface, authored()->tessellation, o);
    g::MediumGrid grid;
    grid.nx = 31;
    grid.ny = 61;
    grid.dx = grid.dy = 20.0;
    grid.x0 = 100.0;
    grid.y0 = -600.0;
    for (int j = 0; j < grid.ny; ++j)
        for (int i = 0; i < grid.nx; ++i) {
            const double ground = hill()->height(grid.x0 + i * grid.dx, grid.y0 + j * grid.dy);
            grid.bottom.push_back(50.0);
            grid.top.push_back(150.0);
            grid.floor.push_back(std::max(50.0, ground));
            grid.coverage.push_back(0.5);
        }
    g::MediumOptions mo;
    mo.extinction = o.optics.extinction;
    mo.albedo = 0.0;
    mo.top_density = o.optics.top_density;
    g::MediumDetail detail;
    detail.detail = 0.0;
    const g::Medium medium(grid, mo, detail);
    // Transmittance straight down at (x, 380): the frame with fog over the bare one (green).
    const auto transmittance = [&](double x, bool with_medium) {
        Camera down;
        down.position = {x, 379.0, 400.0};
        down.target = {x, 380.0, 0.0};
        down.fov_y_deg = 10.0;
        Renderer renderer;
        renderer.set_terrain(*hill());
        renderer.set_sun(sun);
        if (with_medium)  // the ground in the Medium's shadow in both frames
            renderer.set_sun_medium(&medium, {});
        renderer.render(down, w, h);
        const kiri::render::RadianceImage bare = renderer.read_radiance();
        renderer.set_layers(base, o);
        renderer.render(down, w, h);
        const kiri::render::RadianceImage fog = renderer.read_radiance();
        const std::size_t centre = (std::size_t(h / 2) * w + w / 2) * 4 + 1;
        return double(fog.rgba[centre]) / double(bare.rgba[centre]);
    };
    const double atlas_east = transmittance(380.0, false), atlas_west = transmittance(-380.0, false);
    const double east = transmittance(380.0, true), west = transmittance(-380.0, true);
    std::printf("    without the Medium east %.4f west %.4f; with it east %.4f west %.4f\n", atlas_east, atlas_west,
                east, west);
    // The atlas alone: the lake's whole stack (30 m of ground under it) on both sides.
    ASSERT_LT(atlas_east, 0.5);
    ASSERT_NEAR(atlas_west, atlas_east, 0.02);
    EXPECT_NEAR(std::log(east) / std::log(atlas_east), 0.5, 0.01);  // half the density: half the depth
    EXPECT_NEAR(west, 1.0, 1e-3);                                   // beyond the Medium's grid: no fog
}

// A Medium over the lake's footprint, from the stack's base (50 m) to its top (150 m), at full
// coverage, with the stack's optics and detail: what the layers stand for.
g::Medium lake_medium(const g::Terrain& terrain, const g::LayerOptions& o)
{
    g::MediumGrid grid;
    grid.nx = grid.ny = 57;
    grid.dx = grid.dy = 20.0;
    grid.x0 = grid.y0 = -560.0;
    for (int j = 0; j < grid.ny; ++j)
        for (int i = 0; i < grid.nx; ++i) {
            grid.bottom.push_back(50.0);
            grid.top.push_back(150.0);
            grid.floor.push_back(std::clamp(terrain.height(grid.x0 + i * grid.dx, grid.y0 + j * grid.dy), 50.0, 150.0));
            grid.coverage.push_back(1.0);
        }
    return g::Medium(grid, o.optics, g::medium_detail(o.optics, o.count));
}

// Black fog's frame over the bare one against the Medium's transmittance along each pixel's ray,
// for the pixels (x, y) given: the mean and the largest relative difference.
struct Agreement {
    double mean = 0.0, worst = 0.0;
    int pixels = 0;
};
Agreement agreement(const g::Medium& medium, const g::Terrain& terrain, const Camera& cam, int w, int h,
                    const kiri::render::RadianceImage& bare, const kiri::render::RadianceImage& fog,
                    const std::vector<glm::ivec2>& pixels)
{
    Agreement a;
    for (const glm::ivec2 q : pixels) {
        double reach = 0.0;
        const double expected =
            medium_transmittance(medium, terrain, cam.position, pixel_ray(cam, q.x, q.y, w, h), reach);
        const std::size_t at = (std::size_t(q.y) * w + std::size_t(q.x)) * 4 + 1;  // green
        const double got = double(fog.rgba[at]) / double(bare.rgba[at]);
        const double e = std::abs(got / expected - 1.0);
        if (std::getenv("KIRI_TEST_VERBOSE"))
            std::printf("      pixel %d %d: got %.4f expected %.4f reach %.0f\n", q.x, q.y, got, expected, reach);
        a.mean += e;
        a.worst = std::max(a.worst, e);
        ++a.pixels;
    }
    a.mean /= std::max(a.pixels, 1);
    return a;
}

// The narrowing adds layers near the eye (120 within its flat radius here, where the reference
// stack has 10), and each shows the Medium's detail noise at its own height, h l0 layers of the
// reference stack up, as the Medium takes it (Medium::detail_factor): with the i-th narrowed
// layer shifted as the i-th of the reference stack, the layers near the eye drew other noise
// than the fog they stand for. Black fog seen from 90 m over the base, 20 degrees down, a detail
// of 0.6 in features of 60 m: the frame's transmittance over 42 pixels against the Medium's.
TEST_F(LayersGl, TheLayersNearTheEyeShowTheMediumsDetailAtTheirHeight)
{
    const int w = 48, h = 48;
    const double slant = 20.0 * std::acos(-1.0) / 180.0;
    Camera cam;
    cam.position = {380.0, 380.0 - 110.0 / std::tan(slant), 140.0};
    cam.target = {380.0, 380.0, 30.0};
    cam.fov_y_deg = 24.0;
    g::LayerOptions o = medium_options();
    o.optics.albedo = 0.0;
    o.optics.extinction = 0.008;
    o.optics.detail = 0.6;
    o.optics.detail_scale = 60.0;
    o.enlargement = false;
    const g::Medium medium = lake_medium(*hill(), o);
    const BlackFog frames = black_fog(cam, w, h, medium, o);
    ASSERT_GT(frames.last_layers, 100);
    // 7 x 6 pixels, the top row's rays (800 m to the ground) left out: they leave the lake's
    // footprint, where the layers' Medium ends in a wall.
    std::vector<glm::ivec2> pixels;
    for (int j = 1; j < 7; ++j)
        for (int i = 0; i < 7; ++i)
            pixels.push_back({3 + 7 * i, 3 + 7 * j});
    const Agreement a = agreement(medium, *hill(), cam, w, h, frames.bare, frames.fog, pixels);
    std::printf("    %d pixels: transmittance off the Medium's by %.2f %% on average, %.2f %% at most\n", a.pixels,
                100.0 * a.mean, 100.0 * a.worst);
    // Measured 0.36 % and 4.5 %; with the narrowed layers' own index as the noise's layer, about 6 % and 22 %.
    EXPECT_LT(a.mean, 0.02);
    EXPECT_LT(a.worst, 0.07);
}

// An eye on a layer looking level at the hill: its rays run in the space between the layers
// either side of it all the way to the hill's slope, and cross no layer there. The fog they cross
// is the stretch before the terrain (layers_end.frag), from the eye; before, the hill showed
// through bare. Black fog, flat layers 10 m apart, the eye on layer 4 (90 m), the slope 150 m off:
// the frame's transmittance over the rows about the horizon against the Medium's.
TEST_F(LayersGl, AnEyeOnALayerLookingLevelSeesTheFogUpToTheHill)
{
    const int w = 48, h = 48;
    Camera cam;
    cam.position = {380.0, 380.0, 90.0};
    cam.target = {0.0, 0.0, 90.0};
    cam.fov_y_deg = 6.0;
    const g::LayerOptions o = flat_black_options();
    const g::Medium medium = lake_medium(*hill(), o);
    const BlackFog frames = black_fog(cam, w, h, medium, o);
    std::vector<glm::ivec2> pixels;
    for (int y = h / 2 - 3; y <= h / 2 + 2; ++y)
        for (int x = 4; x < w; x += 8)
            pixels.push_back({x, y});
    double reach = 0.0;
    const double level = medium_transmittance(medium, *hill(), cam.position, pixel_ray(cam, w / 2, h / 2, w, h), reach);
    std::printf("    the level ray meets the hill %.0f m off, transmittance %.3f\n", reach, level);
    ASSERT_LT(level, 0.5);  // enough fog to see
    const Agreement a = agreement(medium, *hill(), cam, w, h, frames.bare, frames.fog, pixels);
    std::printf("    %d pixels: transmittance off the Medium's by %.2f %% on average, %.2f %% at most\n", a.pixels,
                100.0 * a.mean, 100.0 * a.worst);
    EXPECT_LT(a.mean, 0.03);
    EXPECT_LT(a.worst, 0.08);
}

// A ray down onto the hill's flank meets the ground inside a slab. The layer it crossed last took
// its slab down to the ground under the layer, a vertical clearance: on a slope that is not where
// the ray meets it (looking downhill the ground under the layer is higher, and the slab came out
// short), and where the ground lay below the slab's lower boundary the stretch pass
// (layers_end.frag) added that stretch a second time. Now the slab ends where the ray meets the
// ground, and the stretch pass holds what lies beyond its boundary. Black fog, flat layers 10 m
// apart, seen 60 degrees down the flank between the stack's base and its top: every pixel whose
// ray ends in the stack, against the Medium's transmittance.
TEST_F(LayersGl, ARayDownOntoTheSlopeTakesTheFogOverTheGroundOnce)
{
    const int w = 40, h = 40;
    const double down = 60.0 * std::acos(-1.0) / 180.0;
    const glm::dvec3 flank(269.0, 269.0, 100.0);
    Camera cam;
    cam.position = flank +
        700.0 *
            glm::dvec3(-0.5 * std::sqrt(2.0) * std::cos(down), -0.5 * std::sqrt(2.0) * std::cos(down), std::sin(down));
    cam.target = flank;
    cam.fov_y_deg = 20.0;
    const g::LayerOptions o = flat_black_options();
    const g::Medium medium = lake_medium(*hill(), o);
    const BlackFog frames = black_fog(cam, w, h, medium, o);
    std::vector<glm::ivec2> pixels;
    for (int y = 1; y < h; y += 2)
        for (int x = 1; x < w; x += 2) {
            const glm::dvec3 ray = pixel_ray(cam, x, y, w, h);
            double reach = 0.0;
            medium_transmittance(medium, *hill(), cam.position, ray, reach);
            const double z = cam.position.z + reach * ray.z;
            if (z > 52.0 && z < 148.0)
                pixels.push_back({x, y});
        }
    ASSERT_GT(pixels.size(), 120u);
    const Agreement a = agreement(medium, *hill(), cam, w, h, frames.bare, frames.fog, pixels);
    std::printf("    %d pixels: transmittance off the Medium's by %.2f %% on average, %.2f %% at most\n", a.pixels,
                100.0 * a.mean, 100.0 * a.worst);
    // Measured 0.18 % and 0.62 %; with the slab to the ground under the layer, 0.98 % and 3.24 %.
    EXPECT_LT(a.mean, 0.005);
    EXPECT_LT(a.worst, 0.015);
}

// An eye inside the stack looking up crosses the layers over it from the lowest: far to near is
// top first for them, and bottom first for those under the eye (layers_under_eye). Flat layers
// (no narrowing) seen 35 degrees up from 25 m over the base: the frame is the pile of slabs over
// the eye composited near to far, each lit through the slab above it, over the sky behind.
TEST_F(LayersGl, AnEyeInsideTheStackSeesTheLayersOverItFarToNear)
{
    const int w = 32, h = 32;
    const double base_z = 50.0, T0 = 100.0, eye_z = 75.0, sigma = 0.03;
    const Camera up = climbing(35.0, 6.0);
    const glm::dvec3 view = glm::normalize(up.target - up.position);
    ASSERT_EQ(up.position.z, eye_z);
    // The ground under the layers the ray crosses lies under the base: no layer is cut.
    for (double t = 0.0; t <= (base_z + T0 - eye_z) / view.z; t += 10.0)
        ASSERT_LT(hill()->height(up.position.x + t * view.x, up.position.y + t * view.y), base_z) << t;
    kiri::render::SunLight sun;
    Renderer renderer;
    renderer.set_terrain(*hill());
    renderer.set_sun(sun);
    renderer.render(up, w, h);
    const kiri::render::RadianceImage bare = renderer.read_radiance();
    g::LayerOptions o = options(-100.0);
    o.shading = g::LayerShading::medium;
    o.optics.extinction = sigma;
    o.narrowing = o.enlargement = false;
    const g::LayerBase base = g::make_layer_base(authored()->surface, authored()->tessellation, o);
    renderer.set_layers(base, o);
    renderer.render(up, w, h);
    const kiri::render::RadianceImage fog = renderer.read_radiance();
    ASSERT_EQ(g::layers_under_eye(base, o, up.position, 10), 3);  // layers 0, 1 and 2 lie under the eye
    const glm::dvec3 s = glm::normalize(sun.direction);
    const g::FogLight light{sun.color * sun.intensity, sun.ambient, s.z};
    const std::size_t centre = (std::size_t(h / 2) * w + w / 2) * 4;
    glm::dvec3 near_to_far(0.0), far_to_near(0.0), through(1.0);
    // Near to far: layers 3 (80 m) .. 10 (150 m), each behind those before it.
    for (int i = 3; i <= 10; ++i) {
        const double hi = i / 10.0, rho = 1.0 - 0.9 * hi;
        const double alpha = 1.0 - std::exp(-sigma * rho * 10.0 * g::layer_slab_share(10.0, i) / view.z);
        const double tau_sun = sigma * T0 * ((1.0 - hi) - 0.45 * (1.0 - hi * hi)) / s.z;
        const glm::dvec3 j = g::fog_source(light, o.optics, glm::dot(view, s), tau_sun);
        near_to_far += through * j * alpha;
        through *= 1.0 - alpha;
        far_to_near = j * alpha + (1.0 - alpha) * far_to_near;  // the wrong order, for the message
    }
    for (int c = 0; c < 3; ++c) {
        const double sky = bare.rgba[centre + std::size_t(c)];
        const double expected = near_to_far[c] + through[c] * sky, wrong = far_to_near[c] + through[c] * sky;
        const double got = fog.rgba[centre + std::size_t(c)];
        std::printf("    channel %d: got %.4f, near to far %.4f, far to near %.4f\n", c, got, expected, wrong);
        EXPECT_NEAR(got / expected, 1.0, 0.01) << "channel " << c;
        ASSERT_GT(std::abs(wrong / expected - 1.0), 0.03) << "the order shows";
    }
}

// The narrowed stack from inside: near the eye the layers are flat (the narrowing's floor
// T0 / max_count, here within 50 m), further out each is a cone rising away from the eye, which a
// climbing ray meets from the highest down. The pass draws the cones first, bottom first, then the
// flat layers, over the eye top first. Against the layer surfaces traced on the CPU
// (layer_column, layer_vertex): every crossing of the ray with a layer, its slab at the layer's own
// slant (the first from the eye on), lit through the slab above it, composited near to far over
// the sky.
TEST_F(LayersGl, AClimbingRayFromInsideCrossesTheNarrowedStackFarToNear)
{
    const int w = 32, h = 32;
    const double base_z = 50.0, T0 = 100.0, eye_z = 75.0, sigma = 0.02;
    const Camera up = climbing(25.0, 4.0);
    const glm::dvec3 view = glm::normalize(up.target - up.position);
    ASSERT_EQ(up.position.z, eye_z);
    kiri::render::SunLight sun;
    Renderer renderer;
    renderer.set_terrain(*hill());
    renderer.set_sun(sun);
    renderer.render(up, w, h);
    const kiri::render::RadianceImage bare = renderer.read_radiance();
    g::LayerOptions o = options(-100.0);
    o.shading = g::LayerShading::medium;
    o.optics.extinction = sigma;
    o.narrowing = true;
    o.enlargement = false;
    o.max_count = 400;  // the floor T0 / 400 within L0 10 / 400 = 50 m of the eye
    const g::LayerBase base = g::make_layer_base(authored()->surface, authored()->tessellation, o);
    renderer.set_layers(base, o);
    renderer.render(up, w, h);
    const kiri::render::RadianceImage fog = renderer.read_radiance();
    const int top = renderer.last_stats().layers;
    // Layer i over (x, y): the CPU's column there.
    const auto column = [&](glm::dvec2 q) { return g::layer_column(o, up.position, {q, base_z}, {0.0, 0.0, 1.0}); };
    const auto height = [&](int i, glm::dvec2 q) { return base_z + i * column(q).spacing; };
    const glm::dvec3 s = glm::normalize(sun.direction);
    const g::FogLight light{sun.color * sun.intensity, sun.ambient, s.z};
    struct Crossing {
        double t;
        glm::dvec3 source;
        double sigma, path;  // the slab's extinction and the ray's path through it
    };
    std::vector<Crossing> crossings;
    const double t_end = (base_z + T0 + 5.0 - eye_z) / view.z, dt = 0.25;
    for (int i = 0; i <= top; ++i) {
        const auto f = [&](double t) {
            const glm::dvec3 p = up.position + t * view;
            return p.z - height(i, glm::dvec2(p));
        };
        for (double t0 = 0.0; t0 < t_end; t0 += dt) {
            double a = t0, b = t0 + dt;
            if ((f(a) > 0.0) == (f(b) > 0.0))
                continue;
            for (int k = 0; k < 40; ++k)
                ((f(a) > 0.0) == (f(0.5 * (a + b)) > 0.0) ? a : b) = 0.5 * (a + b);
            const double t = 0.5 * (a + b);
            const glm::dvec3 p = up.position + t * view;
            const glm::dvec2 q(p);
            const g::LayerColumn c = column(q);
            const g::LayerVertex v = g::layer_vertex(o, c, i, {q, base_z}, base.centre);
            const double clearance = p.z - hill()->height(q.x, q.y);
            if (v.alpha <= 0.0 || clearance < 0.0)
                continue;
            const double e = 0.01;  // the layer's own slant: its surface's gradient
            const glm::dvec3 normal =
                glm::normalize(glm::dvec3(-(height(i, q + glm::dvec2(e, 0.0)) - height(i, q)) / e,
                                          -(height(i, q + glm::dvec2(0.0, e)) - height(i, q)) / e, 1.0));
            const double slab = g::layer_slab_over_ground(v.slab, i, c.spacing, clearance);
            const double path = c.spacing * slab * normal.z / std::max(std::abs(glm::dot(normal, view)), 0.02);
            const double hi = std::min(double(i), c.count) / c.count;
            const double tau_sun = sigma * T0 * ((1.0 - hi) - 0.45 * (1.0 - hi * hi)) / s.z;
            crossings.push_back({t, g::fog_source(light, o.optics, glm::dot(view, s), tau_sun), sigma * v.alpha, path});
        }
    }
    std::sort(crossings.begin(), crossings.end(), [](const Crossing& a, const Crossing& b) { return a.t < b.t; });
    glm::dvec3 near_to_far(0.0), through(1.0);
    int cones = 0;
    for (const Crossing& x : crossings) {
        // The first layer crossed also holds the fog between the eye and its slab, which no
        // layer crosses (the space between the two layers either side of the eye).
        const double path = &x == &crossings.front() ? std::max(x.path, x.t + 0.5 * x.path) : x.path;
        const double alpha = 1.0 - std::exp(-x.sigma * path);
        near_to_far += through * x.source * alpha;
        through *= 1.0 - alpha;
        cones += glm::length(glm::dvec2(view) * x.t) > 50.0 ? 1 : 0;
    }
    std::printf("    %d layers, %zu crossings (%d in the cones), transmittance %.4f\n", top, crossings.size(), cones,
                through.y);
    ASSERT_GT(cones, 10);        // the ray climbs through the cones
    ASSERT_GT(through.y, 0.05);  // and the sky shows behind
    const std::size_t centre = (std::size_t(h / 2) * w + w / 2) * 4;
    for (int c = 0; c < 3; ++c) {
        const double expected = near_to_far[c] + through[c] * bare.rgba[centre + std::size_t(c)];
        const double got = fog.rgba[centre + std::size_t(c)];
        std::printf("    channel %d: got %.4f, the traced stack near to far %.4f\n", c, got, expected);
        // Measured -1.8, -1.0 and +0.6 % (the GPU's layers are linear over each triangle, the
        // traced ones exact); against the trace without the eye's stretch in the first crossing
        // (before 2026-12-02) with the flat layers' order for the cones too -5.7, -4.5 and -2.2 %,
        // all bottom first -9.7 % in red.
        EXPECT_NEAR(got / expected, 1.0, 0.03) << "channel " << c;
    }
}
