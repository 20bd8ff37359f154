// The layer pass on an analytic terrain: fog where the ground is under the stack, none where a
// summit rises above it, nothing drawn below the ground or off-screen, uploads only once, each
// layer at its own slant, the Medium's extent.
#include "render/layers_fixture.hpp"

namespace {

double luminance(const std::uint8_t* p) { return 0.3 * p[0] + 0.6 * p[1] + 0.1 * p[2]; }

}  // namespace

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
// above where its slab's light comes from), composited over the ground: L = J_i alpha_i + (1 - alpha_i) L, bottom to top.
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
                    // Lit where its slab's light comes from (the centroid of what it scatters,
                    // 1 / d - 1 / (e^d - 1) of the path for its optical depth d across: about the
                    // middle), tau_sun linear across the slab through the layer's: the top's slab
                    // lies under it, the base's over it.
                    const double share = g::layer_slab_share(n, i), above = g::layer_slab_share_above(n, i);
                    const double d = sigma * rho * r * slab / std::abs(view.z);
                    const double centroid = d > 1e-3 ? 1.0 / d - 1.0 / std::expm1(d) : 0.5 - d / 12.0;
                    const double tau_layer = sigma * T0 * ((1.0 - hi) - 0.45 * (1.0 - hi * hi)) / s.z;
                    const double tau_sun = tau_layer + sigma * rho * r * slab * (centroid - above / share) / s.z;
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
