// The fog's shade on the ground (render/src/ground_shade.hpp): the sun reaches the ground under
// a fog through its optical depth towards the sun, e^-tau, as the CPU reference lights its
// ground (RayFog::fog_shade). What the sun adds to the ground, with the fog over it against
// without, must be e^-tau in closed form: under a uniform slab of the Medium, and under a height
// fog alone. The fog is not drawn (the sun's Medium only), so the frames differ by the shade.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <glm/geometric.hpp>

#include "kiri/geometry/medium/medium.hpp"
#include "kiri/geometry/volume/height_fog.hpp"
#include "kiri/render/camera.hpp"
#include "kiri/render/renderer.hpp"
#include "geometry/fog_test_terrains.hpp"
#include "render/render_fixture.hpp"

namespace {

namespace g = kiri::geometry;
using kiri::render::Camera;
using kiri::render::RadianceImage;
using kiri::render::Renderer;
using kiri::render::SunLight;

constexpr double sigma = 0.01, thickness = 100.0;  // the slab: 1/m, m

// A Medium of `extinction` (1/m) on `grid`, even from its bottom to its top, without detail.
g::Medium uniform_medium(g::MediumGrid grid, double extinction)
{
    g::MediumOptions options;
    options.extinction = extinction;
    options.top_density = 1.0;
    g::MediumDetail uniform;
    uniform.detail = 0.0;
    return g::Medium(std::move(grid), options, uniform);
}

// The Medium on a grid of `spacing` metres over [-320, 320]^2, from the ground to `thickness`,
// where `covered` says (coverage 1, else 0).
template <class Covered>
g::Medium medium_where(double spacing, double extinction, Covered covered)
{
    g::MediumGrid grid;
    grid.nx = grid.ny = int(std::lround(640.0 / spacing)) + 1;
    grid.dx = grid.dy = spacing;
    grid.x0 = grid.y0 = -320.0;
    const std::size_t n = std::size_t(grid.nx) * std::size_t(grid.ny);
    grid.floor.assign(n, 0.0);
    grid.bottom.assign(n, 0.0);
    grid.top.assign(n, thickness);
    grid.coverage.assign(n, 0.0);
    for (int j = 0; j < grid.ny; ++j)
        for (int i = 0; i < grid.nx; ++i)
            grid.coverage[std::size_t(j) * std::size_t(grid.nx) + std::size_t(i)] =
                covered(grid.x0 + i * spacing) ? 1.0 : 0.0;
    return uniform_medium(std::move(grid), extinction);
}

// A lake of fog of `extinction` (1/m) with a flat top at `top` over [origin, origin + 2 spacing]^2
// (3 x 3 columns), from 200 m below the ground: every path towards the sun leaves through its top.
g::Medium lake_of_fog(double top, double extinction, double origin, double spacing)
{
    g::MediumGrid grid;
    grid.nx = grid.ny = 3;
    grid.dx = grid.dy = spacing;
    grid.x0 = grid.y0 = origin;
    grid.floor.assign(9, -200.0);
    grid.bottom.assign(9, -200.0);
    grid.top.assign(9, top);
    grid.coverage.assign(9, 1.0);
    return uniform_medium(std::move(grid), extinction);
}

// A flat plain at z = 0 under a uniform slab from the ground to `thickness`, 640 m a side: away
// from its sides the sun's path leaves through its top, after thickness / sin(elevation).
g::Medium slab()
{
    return medium_where(20.0, sigma, [](double) { return true; });
}

// The sun 30 degrees up in the east; intensity 0 for the frame without it.
SunLight sun(double intensity)
{
    SunLight s;
    s.direction = glm::normalize(glm::dvec3(std::cos(0.5235987755982988), 0.0, 0.5));
    s.intensity = intensity;
    s.terrain_shadows = false;
    return s;
}

Camera straight_down()
{
    Camera c;
    c.position = {0.0, -1.0, 800.0};
    c.target = {0.0, 0.0, 0.0};
    c.fov_y_deg = 8.0;  // 110 m of ground across: the slab's middle
    return c;
}

double mean_luminance(const RadianceImage& image)
{
    double sum = 0.0;
    const std::size_t n = std::size_t(image.width) * std::size_t(image.height);
    for (std::size_t k = 0; k < n; ++k)
        sum += 0.2126 * image.rgba[4 * k] + 0.7152 * image.rgba[4 * k + 1] + 0.0722 * image.rgba[4 * k + 2];
    return sum / double(n);
}

class GroundShadeGl : public kiri::test::GlTest {
protected:
    // The share of the sun's light on the ground that the fog set by `shade` lets through:
    // (Y(sun, shade) - Y(no sun)) / (Y(sun, no shade) - Y(no sun)).
    template <class Shade>
    static double sun_let_through(Shade shade)
    {
        const g::Terrain plain = kiri::test::gaussian_hill(65, 20.0, 0.0);
        Renderer r;
        r.set_terrain(plain);
        const auto frame = [&](double intensity, bool shaded) {
            r.set_sun(sun(intensity));
            if (shaded)
                shade(r);
            else
                r.clear_sun_medium();
            r.draw(straight_down(), 32, 32);
            return mean_luminance(r.read_radiance());
        };
        const double dark = frame(0.0, false), lit = frame(3.0, false), shaded = frame(3.0, true);
        EXPECT_GT(lit - dark, 0.05) << "the sun lights the plain";
        return (shaded - dark) / (lit - dark);
    }
};

// Straight down from `altitude` at (centre, 0) over `across` metres of `ground`, size x size:
// the frames without the sun, lit, and lit through `fog`'s shade, and the vertices whose shade
// the fine map refines.
struct FromAbove {
    RadianceImage dark, lit, shaded;
    int refined_vertices = 0;
};
FromAbove frames_from_above(const g::Terrain& ground, const g::Medium& fog, double centre, double across,
                            double altitude, int size)
{
    Renderer r;
    r.set_terrain(ground);
    Camera down;
    down.position = {centre, -1.0, altitude};
    down.target = {centre, 0.0, 0.0};
    down.fov_y_deg = 2.0 * std::atan(0.5 * across / altitude) * 180.0 / 3.14159265358979;
    FromAbove f;
    const auto frame = [&](double intensity, bool shaded) {
        r.set_sun(sun(intensity));
        if (shaded)
            r.set_sun_medium(&fog, {});
        else
            r.clear_sun_medium();
        r.draw(down, size, size);
        if (shaded)
            f.refined_vertices = r.last_stats().refined_shade_vertices;
        return r.read_radiance();
    };
    f.dark = frame(0.0, false);
    f.lit = frame(3.0, false);
    f.shaded = frame(3.0, true);
    return f;
}

// Per pixel column of a size x size frame looking straight down at `centre` over `across`
// metres of `plain`: the share of the sun's light on the ground that `fog` lets through.
std::vector<double> sun_let_through_across(const g::Terrain& plain, const g::Medium& fog, double centre, double across,
                                           int size, int* refined_vertices)
{
    const FromAbove f = frames_from_above(plain, fog, centre, across, 3000.0, size);
    *refined_vertices = f.refined_vertices;
    const RadianceImage &dark = f.dark, &lit = f.lit, &shaded = f.shaded;
    const auto y = [](const RadianceImage& image, int x, int row) {
        const float* p = &image.rgba[4 * (std::size_t(row) * std::size_t(image.width) + std::size_t(x))];
        return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
    };
    std::vector<double> through(std::size_t(size), 0.0);
    for (int x = 0; x < size; ++x) {
        double sum = 0.0;
        for (int row = size / 4; row < 3 * size / 4; ++row)
            sum += (y(shaded, x, row) - y(dark, x, row)) / (y(lit, x, row) - y(dark, x, row));
        through[std::size_t(x)] = sum / double(size / 2);
    }
    return through;
}

}  // namespace

// tau = sigma thickness / sin(30 deg) = 2: the ground gets e^-2 of the sun.
TEST_F(GroundShadeGl, UnderAUniformSlabTheSunIsTheClosedForm)
{
    const g::Medium fog = slab();
    const double got = sun_let_through([&](Renderer& r) { r.set_sun_medium(&fog, {}); });
    const double want = std::exp(-sigma * thickness / 0.5);
    EXPECT_NEAR(got, want, 0.02 * want) << "through the slab";
}

// A height fog alone, no Medium: tau in closed form (HeightFog::optical_depth towards the sun).
TEST_F(GroundShadeGl, UnderAHeightFogTheSunIsTheClosedForm)
{
    g::HeightFog haze;
    haze.extinction = 0.02;
    haze.base = -20.0;
    haze.scale_height = 40.0;
    const glm::dvec3 s = sun(1.0).direction;
    const double want = std::exp(-haze.optical_depth({0.0, 0.0, 0.0}, s, 0.0, HUGE_VAL));
    ASSERT_GT(want, 0.2);
    ASSERT_LT(want, 0.6);
    const double got = sun_let_through([&](Renderer& r) { r.set_sun_medium(nullptr, haze); });
    EXPECT_NEAR(got, want, 0.01 * want) << "through the height fog";
}

// The shade is built once per sun and fog: the pass reports only when it ran, and a fog gone
// lights the ground fully again.
TEST_F(GroundShadeGl, BuiltOncePerSunAndFog)
{
    const g::Terrain plain = kiri::test::gaussian_hill(65, 20.0, 0.0);
    const g::Medium fog = slab();
    Renderer r;
    r.set_terrain(plain);
    r.set_sun(sun(3.0));
    const auto ran = [&] {
        const auto& passes = r.last_stats().passes;
        return std::any_of(passes.begin(), passes.end(), [](const auto& p) { return p.pass == "ground shade"; });
    };
    r.draw(straight_down(), 16, 16);
    EXPECT_FALSE(ran()) << "no fog, nothing to shade";
    const double bare = mean_luminance(r.read_radiance());
    r.set_sun_medium(&fog, {});
    r.draw(straight_down(), 16, 16);
    EXPECT_TRUE(ran());
    EXPECT_LT(mean_luminance(r.read_radiance()), 0.8 * bare);
    Camera moved = straight_down();
    moved.position.x += 50.0;
    r.draw(moved, 16, 16);
    EXPECT_FALSE(ran()) << "another view, the same sun and fog";
    SunLight higher = sun(3.0);
    higher.direction = glm::normalize(glm::dvec3(0.5, 0.0, 1.0));
    r.set_sun(higher);
    r.draw(straight_down(), 16, 16);
    EXPECT_TRUE(ran()) << "a new sun";
    r.set_sun(sun(3.0));
    r.clear_sun_medium();
    r.draw(straight_down(), 16, 16);
    EXPECT_NEAR(mean_luminance(r.read_radiance()), bare, 1e-6 * bare) << "the fog gone, the ground lit again";
}

// A fog's wall crossing a cell of the terrain's grid (80 m) between two vertices: the sun,
// 30 degrees up beyond the wall, reaches the ground behind it through the wall, within a cell
// of it through the fog's top. The shade bends twice within two cells; interpolated between the
// vertices it spilled 0.23 of the sun's transmittance over the sunlit ground beside the wall.
// GroundShade marks the vertices there and the ground reads a finer map: each pixel column's
// transmittance must follow the closed form exp(-sigma L), L the sun's path in the fog.
TEST_F(GroundShadeGl, AFogsWallWithinACellShadesTheGroundWhereTheWallStands)
{
    constexpr double extinction = 0.02, wall = 31.0;  // the coverage falls from 1 at 30 m to 0 at 32 m
    const g::Terrain plain = kiri::test::gaussian_hill(17, 80.0, 0.0);
    const g::Medium fog = medium_where(2.0, extinction, [&](double x) { return x < wall; });
    constexpr double centre = -60.0, across = 400.0;
    constexpr int size = 64;
    int refined = 0;
    const std::vector<double> got = sun_let_through_across(plain, fog, centre, across, size, &refined);
    EXPECT_GT(refined, 0) << "the vertices beside the wall are marked";
    EXPECT_LT(refined, 17 * 17 * 4 / 10) << "and not the whole plain";
    const double cos_elevation = std::cos(0.5235987755982988), sin_elevation = 0.5;
    double sum = 0.0, worst = 0.0;
    for (int x = 0; x < size; ++x) {
        const double ground = centre + ((x + 0.5) / size - 0.5) * across;
        const double path = std::min(thickness / sin_elevation, std::max(wall - ground, 0.0) / cos_elevation);
        const double want = std::exp(-extinction * path);
        const double off = std::abs(got[std::size_t(x)] - want);
        sum += off;
        worst = std::max(worst, off);
    }
    EXPECT_LT(sum / size, 0.01) << "mean |dT| over the pixel columns (interpolated: 0.036)";
    EXPECT_LT(worst, 0.12) << "at the wall's kink, between the fine map's samples (interpolated: 0.35)";
}

// A dense fog's shore on a slope: a lake of fog (0.3 per metre, 10 m of visibility) with a flat
// top 43 m up over ground rising eastwards at 1 in 10 (z = 0.1 (x + 320), 17 samples 80 m apart),
// the shore at x = 110 within a cell, the sun 30 degrees up in the east: under the fog the sun's
// path leaves through the top, tau = sigma (43 - z) / sin(30 deg), growing by 0.06 a metre away
// from the shore, and nothing shades the ground beyond it. Read as 0 on the shore's sunlit side,
// tau filtered between the fine map's texels (27 m apart) spilled the fog's shade over the
// sunlit ground up to a texel beyond the shore: there the Medium's part is carried on below 0.
TEST_F(GroundShadeGl, ADenseFogsShoreOnASlopeShadesTheGroundUpToTheShore)
{
    constexpr double extinction = 0.3, top = 43.0, rise = 0.1, shore = top / rise - 320.0;
    const g::Terrain ramp(kiri::test::make_heightfield(17, 17, 80.0, -640.0, -640.0,
                                                       [](double x, double) { return rise * (x + 320.0); }));
    const g::Medium fog = lake_of_fog(top, extinction, -640.0, 640.0);
    constexpr double centre = shore, across = 240.0;
    constexpr int size = 64;
    int refined = 0;
    const std::vector<double> got = sun_let_through_across(ramp, fog, centre, across, size, &refined);
    double sum = 0.0, worst = 0.0, lit_sum = 0.0;
    int lit = 0;
    for (int x = 0; x < size; ++x) {
        const double ground = centre + ((x + 0.5) / size - 0.5) * across;
        const double z = rise * (ground + 320.0);
        const double want = std::exp(-extinction * std::max(top - z, 0.0) / 0.5);
        const double off = std::abs(got[std::size_t(x)] - want);
        sum += off;
        worst = std::max(worst, off);
        if (ground > shore + 2.0) {
            lit_sum += got[std::size_t(x)];
            ++lit;
        }
    }
    std::printf(
        "    %d vertices refined; mean |dT| %.4f, worst %.4f; the sunlit ground beyond the shore lets %.4f through\n",
        refined, sum / size, worst, lit_sum / std::max(lit, 1));
    EXPECT_GT(refined, 0);
    EXPECT_GT(lit, 20);
    // Measured: 0.0009, 0.0051 and 1.0000; with tau read as 0 beyond the shore 0.0100, 0.149
    // and 0.988.
    EXPECT_LT(sum / size, 0.004) << "mean |dT| over the pixel columns";
    EXPECT_LT(worst, 0.05) << "at the shore";
    EXPECT_GT(lit_sum / std::max(lit, 1), 0.995) << "the sunlit ground beyond the shore keeps its sun";
}

// Beyond the DEM's edge the fog's wall shades the surround: a slab 60 m deep over the whole
// DEM (5 x 5 samples 160 m apart), the sun 30 degrees up in the east, so the ground west of the
// DEM lies in the wall's shadow up to 104 m out, where the sun's path passes over the wall's top
// (tau falls linearly to 0 there, then stays 0). The surround's vertices take tau_sun marched,
// and the ground interpolates between them: with its first ring a cell out (160 m, the kink
// between it and the edge) the shade spilled over the sunlit ground beyond (mean |dT| 0.073,
// worst 0.33); the rings start at a third of a cell (render/src/terrain_pass.cpp, ring_offsets:
// 0.008, 0.093). Each pixel column's transmittance must follow the closed form exp(-sigma L), L the
// sun's path in the fog.
TEST_F(GroundShadeGl, AFogsWallAtTheDemsEdgeShadesTheSurroundWhereItsShadowFalls)
{
    constexpr double extinction = 0.01, depth = 60.0, edge = -320.0;
    const g::Terrain plain = kiri::test::gaussian_hill(5, 160.0, 0.0);
    g::MediumGrid grid;
    grid.nx = grid.ny = 33;
    grid.dx = grid.dy = 20.0;
    grid.x0 = grid.y0 = edge;
    const std::size_t n = std::size_t(grid.nx) * std::size_t(grid.ny);
    grid.floor.assign(n, 0.0);
    grid.bottom.assign(n, 0.0);
    grid.top.assign(n, depth);
    grid.coverage.assign(n, 1.0);
    const g::Medium fog = uniform_medium(std::move(grid), extinction);
    constexpr double centre = edge - 100.0, across = 320.0;
    constexpr int size = 64;
    int refined = 0;
    const std::vector<double> got = sun_let_through_across(plain, fog, centre, across, size, &refined);
    const double tan_elevation = std::tan(0.5235987755982988), sin_elevation = 0.5;
    double sum = 0.0, worst = 0.0;
    for (int x = 0; x < size; ++x) {
        const double ground = centre + ((x + 0.5) / size - 0.5) * across;
        const double out = std::max(edge - ground, 0.0);  // beyond the edge
        const double path = std::max(depth - out * tan_elevation, 0.0) / sin_elevation;
        const double want = std::exp(-extinction * path);
        const double off = std::abs(got[std::size_t(x)] - want);
        sum += off;
        worst = std::max(worst, off);
    }
    std::printf("    mean |dT| %.4f, worst %.4f\n", sum / size, worst);
    EXPECT_LT(sum / size, 0.02) << "mean |dT| over the pixel columns";
    EXPECT_LT(worst, 0.15) << "at the kink, between two rings";
}

// A dense fog's shores winding over curved ground: a lake of fog (0.3 per metre) with a flat top
// 35 m up over hills and hollows (40 m cells), the sun 30 degrees up in the east. Under the fog
// tau = sigma (35 - z) / sin(30 deg), z the mesh's own ground at the point, and beyond a shore
// nothing shades the ground. Carried on below 0 along a row or a column of the fine map (phase
// 3's runs), tau met 0 where the shore ran on a plane but not where it turned within a cell, and
// the fog's shade spilled over the sunlit ground beside it (measured: mean |dT| 0.0192, 91
// pixels more than 0.3 off, the sunlit ground 0.9833); carried on in each sample's own column
// at the rate tau grows under the top, 0.0047, 9 and 0.9997 (0.0073, 7 and 0.9997 with a pixel's
// samples weighed by how much of their ground would show through the fog, terrain.frag, which
// this frame does not draw: the closed form is the pixel's centre's). Each pixel's share of the
// sun, seen from straight above, must follow the closed form.
TEST_F(GroundShadeGl, ADenseFogsWindingShoresShadeTheGroundUpToTheShore)
{
    constexpr double extinction = 0.3, top = 35.0, spacing = 40.0;
    const auto height = [](double x, double y) {
        return 30.0 + 20.0 * std::sin(x / 40.0) * std::sin(y / 50.0) + 8.0 * std::sin((x + 2.0 * y) / 25.0);
    };
    const g::Terrain hills(kiri::test::make_heightfield(17, 17, spacing, -320.0, -320.0, height));
    const g::Medium fog = lake_of_fog(top, extinction, -320.0, 320.0);
    // Straight down from 20 km over 240 m a side: a pixel's ground lies within 0.3 m of its
    // centre's (x, y) whatever its height.
    constexpr double across = 240.0, altitude = 20000.0;
    constexpr int size = 64;
    const FromAbove f = frames_from_above(hills, fog, 0.0, across, altitude, size);
    const RadianceImage &dark = f.dark, &lit = f.lit, &shaded = f.shaded;
    const auto y = [](const RadianceImage& image, std::size_t k) {
        return 0.2126 * image.rgba[4 * k] + 0.7152 * image.rgba[4 * k + 1] + 0.0722 * image.rgba[4 * k + 2];
    };
    double sum = 0.0, sunlit_sum = 0.0;
    int judged = 0, sunlit = 0, far_off = 0, shores = 0;
    for (int row = 0; row < size; ++row)
        for (int x = 0; x < size; ++x) {
            const std::size_t k = std::size_t(row) * size + std::size_t(x);
            const double sun_part = y(lit, k) - y(dark, k);
            if (!(sun_part > 0.02))
                continue;  // turned from the sun
            const double gx = ((x + 0.5) / size - 0.5) * across, gy = (0.5 - (row + 0.5) / size) * across;
            const double z = hills.height(gx, gy);  // the mesh's own: two triangles a cell
            const double want = std::exp(-extinction * std::max(top - z, 0.0) / 0.5);
            const double got = (y(shaded, k) - y(dark, k)) / sun_part;
            const double off = std::abs(got - want);
            sum += off;
            ++judged;
            far_off += off > 0.3;
            shores += std::abs(top - z) < 2.0;
            if (z > top + 1.0) {
                sunlit_sum += got;
                ++sunlit;
            }
        }
    std::printf(
        "    %d pixels judged, %d within 2 m of a shore; mean |dT| %.4f, %d more than 0.3 off; the sunlit "
        "ground beyond the shores lets %.4f through\n",
        judged, shores, sum / std::max(judged, 1), far_off, sunlit_sum / std::max(sunlit, 1));
    ASSERT_GT(judged, size * size / 2);
    ASSERT_GT(shores, 100) << "the shores wind through the view";
    ASSERT_GT(sunlit, 200);
    EXPECT_LT(sum / judged, 0.01) << "mean |dT| over the pixels";
    EXPECT_LE(far_off, 25) << "pixels more than 0.3 off";
    EXPECT_GT(sunlit_sum / sunlit, 0.995) << "the sunlit ground beyond the shores keeps its sun";
}
