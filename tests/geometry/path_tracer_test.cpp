// The volume path tracer (path_tracer.hpp) against closed forms and independent oracles:
// Beer-Lambert through a slab, the exact single scattering of a slab lit by the sun (and the
// reference ray marcher at one octave), the multiple scattering of a semi-infinite isotropic
// medium (Chandrasekhar's H-function, solved here), the white furnace (a non-absorbing fog in a
// uniformly lit world stays at the world's radiance), a Lambertian ground under sun and sky;
// adaptive sampling by blocks against the closed form; determinism across threads; bad input
// stays finite.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "fog_test_terrains.hpp"
#include "kiri/geometry/medium/medium.hpp"
#include "kiri/geometry/reference/path_tracer.hpp"
#include "kiri/geometry/reference/reference_fog.hpp"
#include "slab_medium.hpp"

using namespace kiri::geometry;

namespace {

// A uniform slab of fog (top_density 1, no noise) between z = bottom and z = top over
// [-half, half]^2.
Medium slab(double bottom, double top, double sigma, double albedo, double g, double half = 5000.0,
            double top_density = 1.0, double detail = 0.0)
{
    return kiri::test::slab_medium(bottom, top, sigma, albedo, g, half, -half, top_density, detail);
}

FogLighting sun_at(double elevation, double azimuth, const glm::dvec3& radiance)
{
    FogLighting l;
    l.sun_direction = {std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                       std::sin(elevation)};
    l.sun_radiance = radiance;
    l.ambient = glm::dvec3(0.0);
    l.terrain_shadows = false;
    l.scattering_octaves = 1;
    return l;
}

// |estimate - expected| within k standard errors plus a relative allowance, per channel.
void expect_within(const PathEstimate& e, const glm::dvec3& expected, double k, double rel)
{
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(e.radiance[c], expected[c], k * e.std_error[c] + rel * std::abs(expected[c]) + 1e-15)
            << "channel " << c << ", standard error " << e.std_error[c];
}

using kiri::test::gauss_legendre;

// The H-function of isotropic scattering with albedo w ([Chandrasekhar60]), from its integral equation
// 1 / H(mu) = 1 - (w / 2) mu integral_0^1 H(mu') / (mu + mu') dmu', solved by iteration on
// Gauss-Legendre nodes and evaluated elsewhere by the same equation (Nystrom).
class HFunction {
public:
    explicit HFunction(double albedo) : w_(albedo)
    {
        const int n = 48;
        for (const auto& [x, weight] : gauss_legendre(n)) {  // mapped to [0, 1]
            nodes_.push_back(0.5 * (1.0 + x));
            weights_.push_back(0.5 * weight);
        }
        h_.assign(n, 1.0);
        for (int it = 0; it < 2000; ++it) {
            std::vector<double> next(n);
            for (int i = 0; i < n; ++i)
                next[i] = (*this)(nodes_[i]);
            h_ = next;
        }
    }
    double operator()(double mu) const
    {
        double integral = 0.0;
        for (std::size_t i = 0; i < nodes_.size(); ++i)
            integral += weights_[i] * h_[i] / (mu + nodes_[i]);
        return 1.0 / (1.0 - 0.5 * w_ * mu * integral);
    }
    //! Its zeroth moment, which has the closed form (2 / w) (1 - sqrt(1 - w)).
    double moment0() const
    {
        double sum = 0.0;
        for (std::size_t i = 0; i < nodes_.size(); ++i)
            sum += weights_[i] * h_[i];
        return sum;
    }

private:
    double w_;
    std::vector<double> nodes_, weights_, h_;
};

}  // namespace

TEST(PathTracer, BeerLambertThroughASlab)
{
    // Albedo 0: a sky of radiance L seen from under a slab through optical depth tau is
    // L exp(-tau), whatever else happens; the standard error is the binomial one.
    const double sigma = 0.02, H = 100.0;
    const Medium m = slab(0.0, H, sigma, 0.0, 0.8);
    FogLighting light = sun_at(0.5, 0.0, glm::dvec3(3.0));
    light.ambient = {0.5, 1.0, 2.0};
    PathTracerOptions o;
    o.samples = 40000;
    const glm::dvec3 w = glm::normalize(glm::dvec3(0.3, -0.2, 1.0));
    const PathEstimate e = path_traced_ray({&m, {}}, nullptr, {0.0, 0.0, -50.0}, w, 1e6, light, o);
    const double t = std::exp(-sigma * H / w.z);
    expect_within(e, light.ambient * t, 4.5, 0.0);
    const double binomial = std::sqrt(t * (1.0 - t) / o.samples);
    EXPECT_NEAR(e.std_error.y, binomial, 0.05 * binomial);
    EXPECT_LT(e.std_error.y, 0.02 * t);
    // From inside the slab, halfway up, looking up.
    const PathEstimate inside = path_traced_ray({&m, {}}, nullptr, {0.0, 0.0, 0.5 * H}, w, 1e6, light, o, 7);
    expect_within(inside, light.ambient * std::exp(-sigma * 0.5 * H / w.z), 4.5, 0.0);
}

TEST(PathTracer, SingleScatteringOfASlabLitByTheSun)
{
    // Looking down at a slab [0, H] (no ground, black sky) with mu_v = |w.z|, the sun at
    // mu_s = s.z: a point at depth d under the top is seen through d / mu_v of fog and lit
    // through d / mu_s, so integrating the source a sigma pi E p(w.s) along the ray,
    //   L = a pi E p(w.s) mu_s / (mu_s + mu_v) [1 - exp(-sigma H (1 / mu_v + 1 / mu_s))].
    const double sigma = 0.02, a = 0.9, g = 0.6, H = 100.0;
    const Medium m = slab(0.0, H, sigma, a, g);
    const FogLighting light = sun_at(0.7, 0.4, {3.0, 2.0, 1.0});
    const glm::dvec3 w = glm::normalize(glm::dvec3(0.5, 0.3, -0.8));
    const double mu_v = -w.z, mu_s = light.sun_direction.z;
    const double cos_theta = glm::dot(w, light.sun_direction);
    const glm::dvec3 expected = a * std::numbers::pi * light.sun_radiance * henyey_greenstein(cos_theta, g) * mu_s /
        (mu_s + mu_v) * -std::expm1(-sigma * H * (1.0 / mu_v + 1.0 / mu_s));
    PathTracerOptions o;
    o.samples = 20000;
    o.max_bounces = 1;
    o.sky = PathSky::none;
    const glm::dvec3 eye(0.0, 0.0, 300.0);
    const PathEstimate e = path_traced_ray({&m, {}}, nullptr, eye, w, 1e6, light, o);
    expect_within(e, expected, 4.5, 0.0);
    EXPECT_LT(e.std_error.x, 0.02 * expected.x);
    // The reference ray marcher at one octave integrates the same.
    const RayFog r = reference_ray({&m, {}}, nullptr, eye, w, 1e6, light);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(r.inscatter[c], expected[c], 1e-3 * expected[c]);
    // Every order of scattering adds light: the full path tracer gives more.
    o.max_bounces = 128;
    const PathEstimate all = path_traced_ray({&m, {}}, nullptr, eye, w, 1e6, light, o);
    EXPECT_GT(all.radiance.x, expected.x + 10.0 * all.std_error.x);
    // A graded, thicker slab (the layers' profile, the majorant above the extinction, the sun
    // dimmed to 1 %): the ratio-tracked sun and the marcher's quadrature still agree.
    const Medium graded = slab(0.0, H, 0.05, a, g, 5000.0, 0.1);
    const FogLighting low = sun_at(0.45, 0.4, {3.0, 2.0, 1.0});
    o.max_bounces = 1;
    const PathEstimate pg = path_traced_ray({&graded, {}}, nullptr, eye, w, 1e6, low, o, 3);
    const RayFog rg = reference_ray({&graded, {}}, nullptr, eye, w, 1e6, low);
    expect_within(pg, rg.inscatter, 4.5, 0.001);
    EXPECT_LT(pg.std_error.x, 0.03 * rg.inscatter.x);
    // Near the floor the sun comes through an optical depth of 6 (ratio tracking's roulette).
    const glm::dvec3 level = glm::normalize(glm::dvec3(1.0, 0.2, 0.0));
    o.samples = 150000;
    const PathEstimate deep = path_traced_ray({&graded, {}}, nullptr, {0.0, 0.0, 5.0}, level, 60.0, low, o, 4);
    const RayFog rd = reference_ray({&graded, {}}, nullptr, {0.0, 0.0, 5.0}, level, 60.0, low);
    expect_within(deep, rd.inscatter, 4.5, 0.001);
    EXPECT_LT(deep.std_error.x, 0.03 * rd.inscatter.x);
    // Coverage rising from 0.2 to 1 across a 500 m cell (the sun's rays cross the ramp): the
    // control variate of ratio tracking must stay under the extinction everywhere in a cell.
    MediumGrid grid;
    grid.nx = grid.ny = 3;
    grid.x0 = grid.y0 = -500.0;
    grid.dx = grid.dy = 500.0;
    grid.floor.assign(9, 0.0);
    grid.bottom.assign(9, 0.0);
    grid.top.assign(9, H);
    grid.coverage = {0.2, 1.0, 1.0, 0.2, 1.0, 1.0, 0.2, 1.0, 1.0};
    MediumOptions mo;
    mo.extinction = 0.02;
    mo.albedo = a;
    mo.anisotropy = g;
    mo.top_density = 1.0;
    MediumDetail md;
    md.detail = 0.0;
    const Medium ramp(std::move(grid), mo, md);
    const FogLighting from_west = sun_at(0.3, std::numbers::pi, {3.0, 2.0, 1.0});
    const glm::dvec3 north(0.0, 1.0, 0.0), start(-150.0, -300.0, 30.0);
    o.samples = 40000;
    const PathEstimate pr = path_traced_ray({&ramp, {}}, nullptr, start, north, 600.0, from_west, o, 5);
    const RayFog rr = reference_ray({&ramp, {}}, nullptr, start, north, 600.0, from_west);
    expect_within(pr, rr.inscatter, 4.5, 0.001);
    EXPECT_LT(pr.std_error.x, 0.02 * rr.inscatter.x);
}

TEST(PathTracer, GroundUnderAnAbsorbingSlab)
{
    // Level ground under a purely absorbing slab of optical depth tau, a sky of radiance A over
    // the hemisphere and the sun at mu_s: the ground's irradiance is 2 pi A E3(tau) +
    // pi E mu_s exp(-tau / mu_s), so an eye between the two sees
    //   rho (2 A E3(tau) + E mu_s exp(-tau / mu_s)),  E3(x) = (exp(-x) (1 - x) + x^2 E1(x)) / 2.
    const Heightfield ground =
        kiri::test::make_heightfield(11, 11, 1000.0, -5000.0, -5000.0, [](double, double) { return 0.0; });
    const double tau = 1.0;
    const Medium m = slab(50.0, 150.0, tau / 100.0, 0.0, 0.5);
    FogLighting light = sun_at(0.7, 1.0, {3.0, 2.0, 1.0});
    light.ambient = {0.4, 0.6, 0.8};
    light.terrain_shadows = true;
    const double e1 = -std::expint(-tau), e3 = 0.5 * (std::exp(-tau) * (1.0 - tau) + tau * tau * e1);
    const double mu_s = light.sun_direction.z;
    const glm::dvec3 rho(0.16, 0.26, 0.10);  // terrain.frag's valley colour
    const glm::dvec3 expected = rho * (2.0 * light.ambient * e3 + light.sun_radiance * mu_s * std::exp(-tau / mu_s));
    PathTracerOptions o;
    o.samples = 20000;
    const PathEstimate e =
        path_traced_ray({&m, {}}, &ground, {0.0, 0.0, 20.0}, glm::normalize(glm::dvec3(0.2, 0.1, -1.0)), 1e6, light, o);
    expect_within(e, expected, 4.5, 0.0);
    EXPECT_LT(e.std_error.z, 0.01 * expected.z);
}

TEST(PathTracer, SemiInfiniteIsotropicMediumMatchesChandrasekhar)
{
    // The diffuse reflection of a semi-infinite, isotropically scattering medium of albedo w lit
    // by a parallel beam of irradiance pi E (normal to the beam) is, to every order,
    //   L(mu, mu0) = E (w / 4) mu0 / (mu + mu0) H(mu) H(mu0)   ([Chandrasekhar60]).
    const double w = 0.9, sigma = 0.05, H = 2000.0;  // optical depth 100: semi-infinite
    const HFunction h(w);
    EXPECT_NEAR(h.moment0(), 2.0 / w * (1.0 - std::sqrt(1.0 - w)), 1e-6);  // the solver itself
    const Medium m = slab(0.0, H, sigma, w, 0.0, 20000.0);
    const FogLighting light = sun_at(std::asin(0.6), 1.0, {2.0, 1.0, 0.5});
    const glm::dvec3 dir = glm::normalize(glm::dvec3(0.6, 0.0, -0.8));
    const double mu = -dir.z, mu0 = light.sun_direction.z;
    const glm::dvec3 expected = light.sun_radiance * (0.25 * w * mu0 / (mu + mu0) * h(mu) * h(mu0));
    PathTracerOptions o;
    o.samples = 40000;
    o.sky = PathSky::none;
    o.max_bounces = 100000;
    const PathEstimate e = path_traced_ray({&m, {}}, nullptr, {0.0, 0.0, H + 100.0}, dir, 1e6, light, o);
    expect_within(e, expected, 4.5, 0.002);
    EXPECT_LT(e.std_error.x, 0.006 * expected.x);
    // Single scattering alone is the H = 1 term's share only.
    EXPECT_GT(e.radiance.x, 1.5 * light.sun_radiance.x * 0.25 * w * mu0 / (mu + mu0));
}

TEST(PathTracer, DoubleScatteringOfAnAnisotropicSlab)
{
    // The light scattered exactly twice, by numerical integration of closed forms: in a slab
    // [0, H] lit by the sun, the singly scattered radiance at height z travelling along u is
    //   L1(z, u) = a sigma pi E p(-s.u) exp(-sigma (H - z) / mu_s) (1 - exp(-k l)) / k,
    //   k = sigma (1 + u_z / mu_s), l the distance back along -u to the slab's face,
    // and the eye above sees L2 = integral over its ray of a sigma exp(-sigma t)
    // integral_sphere p(u.(-w)) L1(z(t), u) du dt. With g = 0.8 this checks the phase sampling.
    const double sigma = 0.02, a = 0.9, g = 0.8, H = 100.0;
    const Medium m = slab(0.0, H, sigma, a, g);
    const FogLighting light = sun_at(0.6, 0.2, glm::dvec3(1.0));
    const glm::dvec3 s = light.sun_direction, w = glm::normalize(glm::dvec3(-0.4, 0.3, -0.7));
    const double mu_s = s.z, mu_v = -w.z;
    auto l1 = [&](double z, const glm::dvec3& u) {
        const double l = u.z > 0.0 ? z / u.z : (H - z) / -u.z;
        const double k = sigma * (1.0 + u.z / mu_s);
        const double path = std::abs(k * l) < 1e-9 ? l : -std::expm1(-k * l) / k;
        return a * sigma * std::numbers::pi * henyey_greenstein(glm::dot(-s, u), g) *
            std::exp(-sigma * (H - z) / mu_s) * path;
    };
    const auto cos_nodes = gauss_legendre(160), t_nodes = gauss_legendre(24);
    const int n_phi = 360;
    const double depth = H / mu_v;  // the eye's ray through the slab
    double l2 = 0.0;
    for (const auto& [tx, tw] : t_nodes) {
        const double t = 0.5 * depth * (tx + 1.0), z = H - t * mu_v;
        double inner = 0.0;
        for (const auto& [c, cw] : cos_nodes)
            for (int j = 0; j < n_phi; ++j) {
                const double phi = 2.0 * std::numbers::pi * (j + 0.5) / n_phi, r = std::sqrt(1.0 - c * c);
                const glm::dvec3 u(r * std::cos(phi), r * std::sin(phi), c);
                inner += cw * henyey_greenstein(glm::dot(u, -w), g) * l1(z, u);
            }
        inner *= 2.0 * std::numbers::pi / n_phi;
        l2 += 0.5 * depth * tw * a * sigma * std::exp(-sigma * t) * inner;
    }
    const double l1_eye = a * std::numbers::pi * henyey_greenstein(glm::dot(w, s), g) * mu_s / (mu_s + mu_v) *
        -std::expm1(-sigma * H * (1.0 / mu_v + 1.0 / mu_s));
    PathTracerOptions o;
    o.samples = 40000;
    o.max_bounces = 2;
    o.sky = PathSky::none;
    const PathEstimate e = path_traced_ray({&m, {}}, nullptr, {0.0, 0.0, 250.0}, w, 1e6, light, o);
    EXPECT_NEAR(e.radiance.x, l1_eye + l2, 4.5 * e.std_error.x + 0.003 * (l1_eye + l2));
    EXPECT_LT(e.std_error.x, 0.2 * l2);
    EXPECT_GT(l2, 0.2 * l1_eye);  // the second order matters here
}

TEST(PathTracer, WhiteFurnace)
{
    // A non-absorbing fog (albedo 1, Medium and height fog) in a world lit uniformly from every
    // direction: whatever enters leaves, so every path carries the sky's radiance, exactly.
    const Medium m = slab(0.0, 100.0, 0.02, 1.0, 0.7, 5000.0, 0.3, 0.6);
    HeightFog haze;
    haze.extinction = 0.004;
    haze.base = 20.0;
    haze.scale_height = 60.0;
    haze.albedo = 1.0;
    haze.anisotropy = -0.3;
    FogLighting light;
    light.sun_radiance = glm::dvec3(0.0);
    light.ambient = {0.3, 0.5, 0.7};
    PathTracerOptions o;
    o.sky = PathSky::sphere;
    o.samples = 2;
    o.max_bounces = 1 << 20;
    ReferenceView view;
    view.eye = {0.0, -400.0, 50.0};
    view.target = {0.0, 0.0, 0.0};
    view.width = 12;
    view.height = 8;
    view.fov_y_deg = 80.0;
    const PathTracedImage image = render_path_traced({&m, haze}, nullptr, view, light, o);
    ASSERT_EQ(image.radiance.size(), 96u);
    EXPECT_GT(image.vertices, 96);  // the paths did scatter
    for (std::size_t k = 0; k < image.radiance.size(); ++k)
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(image.radiance[k][c], light.ambient[c], 1e-12) << k;
            EXPECT_NEAR(image.std_error[k][c], 0.0, 1e-12) << k;
        }
    // With an albedo below 1 the fog absorbs: darker, never brighter.
    const Medium grey = slab(0.0, 100.0, 0.02, 0.8, 0.7);
    const PathTracedImage dim = render_path_traced({&grey, {}}, nullptr, view, light, o);
    double sum = 0.0;
    for (const glm::dvec3& v : dim.radiance) {
        EXPECT_LE(v.z, light.ambient.z + 1e-12);
        sum += v.z;
    }
    EXPECT_LT(sum / double(dim.radiance.size()), 0.95 * light.ambient.z);
}

TEST(PathTracer, LambertianGroundUnderSunAndSky)
{
    // Flat ground, no fog: a Lambertian surface of albedo rho under the sun (irradiance
    // pi E sin(e)) and a sky of radiance A over the hemisphere reflects rho (E sin(e) + A),
    // every path exactly; the reference's terrain shading says the same on level ground.
    const Heightfield ground =
        kiri::test::make_heightfield(11, 11, 100.0, -500.0, -500.0, [](double, double) { return 10.0; });
    FogLighting light = sun_at(0.6, 2.0, {3.0, 2.5, 2.0});
    light.ambient = {0.2, 0.3, 0.4};
    light.terrain_shadows = true;
    PathTracerOptions o;
    o.samples = 64;
    const glm::dvec3 eye(0.0, -300.0, 200.0), dir = glm::normalize(glm::dvec3(0.1, 1.0, -0.9));
    const PathEstimate e = path_traced_ray({}, &ground, eye, dir, 1e6, light, o);
    const glm::dvec3 rho(0.16, 0.26, 0.10);  // terrain.frag's valley colour (level ground at the lowest height)
    const glm::dvec3 expected = rho * (light.sun_radiance * std::sin(0.6) + light.ambient);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(e.radiance[c], expected[c], 1e-12 * expected[c]);
        EXPECT_NEAR(e.std_error[c], 0.0, 1e-12);
    }
    const RayFog r = reference_ray({}, &ground, eye, dir, 1e6, light);
    ASSERT_TRUE(r.hit_terrain);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(r.surface[c], expected[c], 1e-12);
    // A black ground reflects nothing; no sky leaves the sun alone.
    o.ground = PathGround::black;
    EXPECT_EQ(path_traced_ray({}, &ground, eye, dir, 1e6, light, o).radiance, glm::dvec3(0.0));
    o.ground = PathGround::lambertian;
    light.sky = false;
    const PathEstimate sun_only = path_traced_ray({}, &ground, eye, dir, 1e6, light, o);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(sun_only.radiance[c], rho[c] * light.sun_radiance[c] * std::sin(0.6), 1e-12);
}

TEST(PathTracer, SingleScatteringAgreesWithTheReferenceOnNoisyFogAndTerrainShadows)
{
    // Two independent integrators of the same single scattering: a noisy, graded Medium over
    // hills with a ridge, the ridge's shadow in the fog, and a height fog. Per pixel the path
    // tracer's error is its noise: (difference / standard error)^2 averages about 1.
    const Heightfield hills = kiri::test::make_heightfield(81, 81, 25.0, -1000.0, -1000.0,
                                                           [](double x, double y) { return kiri::test::hills(x, y); });
    MediumGrid grid;
    grid.nx = grid.ny = 41;
    grid.x0 = grid.y0 = -1000.0;
    grid.dx = grid.dy = 50.0;
    for (int j = 0; j < grid.ny; ++j)
        for (int i = 0; i < grid.nx; ++i) {
            const double x = grid.x0 + i * grid.dx, y = grid.y0 + j * grid.dy;
            const double z = kiri::test::hills(x, y);
            grid.floor.push_back(z);
            grid.bottom.push_back(300.0);
            grid.top.push_back(560.0);
            grid.coverage.push_back(std::clamp((900.0 - std::hypot(x, y)) / 300.0, 0.0, 1.0));
        }
    MediumOptions mo;
    mo.extinction = 0.012;
    mo.albedo = 0.95;
    mo.anisotropy = 0.75;
    MediumDetail md;
    md.detail = 0.6;
    md.detail_scale = 200.0;
    const Medium m(std::move(grid), mo, md);
    HeightFog haze;
    haze.extinction = 0.002;
    haze.base = 350.0;
    haze.scale_height = 80.0;
    haze.albedo = 0.9;
    haze.anisotropy = 0.5;
    FogLighting light = sun_at(0.35, 3.3, {3.0, 2.8, 2.5});
    light.terrain_shadows = true;
    ReferenceView view;
    view.eye = {-1400.0, -900.0, 700.0};
    view.target = {100.0, 100.0, 400.0};
    view.width = 10;
    view.height = 6;
    view.fov_y_deg = 30.0;
    PathTracerOptions o;
    o.samples = 1500;
    o.max_bounces = 1;
    o.sky = PathSky::none;
    o.ground = PathGround::black;
    const FogVolume fog{&m, haze};
    const PathTracedImage pt = render_path_traced(fog, &hills, view, light, o);
    ReferenceOptions ro;
    ro.shade_terrain = false;
    light.sky = false;
    const ReferenceImage ref = render_reference_fog(fog, &hills, view, light, ro);
    double chi2 = 0.0, sum_pt = 0.0, sum_ref = 0.0;
    int n = 0;
    for (std::size_t k = 0; k < pt.radiance.size(); ++k) {
        const double ref_l = luminance(ref.composed(k)), pt_l = luminance(pt.radiance[k]);
        const double se = luminance(pt.std_error[k]);
        sum_pt += pt_l;
        sum_ref += ref_l;
        if (se > 0.0) {
            chi2 += (pt_l - ref_l) * (pt_l - ref_l) / (se * se);
            ++n;
        }
    }
    ASSERT_GT(n, 40);
    EXPECT_LT(chi2 / n, 1.6);
    EXPECT_GT(chi2 / n, 0.5);
    EXPECT_NEAR(sum_pt, sum_ref, 0.01 * sum_ref);
}

TEST(PathTracer, DeterministicOnAnyNumberOfThreads)
{
    const Medium m = slab(0.0, 100.0, 0.02, 0.99, 0.8, 5000.0, 0.1, 0.6);
    FogLighting light = sun_at(0.5, 0.3, glm::dvec3(3.0));
    light.ambient = {0.2, 0.3, 0.4};
    ReferenceView view;
    view.eye = {0.0, -500.0, 60.0};
    view.target = {0.0, 0.0, 40.0};
    view.width = 8;
    view.height = 6;
    PathTracerOptions o;
    o.samples = 8;
    o.threads = 1;
    const PathTracedImage a = render_path_traced({&m, {}}, nullptr, view, light, o);
    o.threads = 3;
    const PathTracedImage b = render_path_traced({&m, {}}, nullptr, view, light, o);
    EXPECT_EQ(a.radiance, b.radiance);
    EXPECT_EQ(a.std_error, b.std_error);
    EXPECT_EQ(a.vertices, b.vertices);
    o.seed = 2;
    const PathTracedImage c = render_path_traced({&m, {}}, nullptr, view, light, o);
    EXPECT_NE(a.radiance, c.radiance);
}

TEST(PathTracer, AdaptiveSamplingTakesNoisyBlocksUnderTheTargetAndStaysExact)
{
    // A thin slab (vertical optical depth 0.2) seen from above at one bounce: steep rays meet the
    // fog less often than slanted ones, so their blocks are noisier and take more rounds. Every
    // pixel against the closed form of SingleScatteringOfASlabLitByTheSun, in its own standard
    // errors: a merge of the rounds that dropped or misweighted paths would show.
    const double sigma = 0.002, a = 0.9, g = 0.6, H = 100.0;
    const Medium m = slab(0.0, H, sigma, a, g);
    const FogLighting light = sun_at(0.7, 0.4, {3.0, 2.0, 1.0});
    ReferenceView view;
    view.eye = {0.0, 0.0, 300.0};
    view.target = {300.0, 0.0, 0.0};
    view.fov_y_deg = 40.0;
    view.width = 16;
    view.height = 12;
    PathTracerOptions o;
    o.samples = 160;
    o.max_bounces = 1;
    o.sky = PathSky::none;
    o.noise_target = 0.03;
    o.max_samples = 4096;
    o.threads = 2;
    const PathTracedImage image = render_path_traced({&m, {}}, nullptr, view, light, o);
    ASSERT_EQ(image.pixel_samples.size(), std::size_t(16 * 12));
    const auto [fewest, most] = std::minmax_element(image.pixel_samples.begin(), image.pixel_samples.end());
    // The slanted rays' blocks are under the target at once, the steep ones' took a round or more.
    EXPECT_EQ(*fewest, o.samples);
    EXPECT_GE(*most, 4 * o.samples);
    EXPECT_GT(image.rounds, 1);
    // Each 4x4 block: its mean's relative standard error under the target, or its pixels at the most.
    for (int by = 0; by < 3; ++by)
        for (int bx = 0; bx < 4; ++bx) {
            double sum = 0.0, variance = 0.0;
            int at_most = 0;
            for (int y = 4 * by; y < 4 * by + 4; ++y)
                for (int x = 4 * bx; x < 4 * bx + 4; ++x) {
                    const std::size_t k = std::size_t(y) * 16 + x;
                    sum += luminance(image.radiance[k]);
                    variance += std::pow(luminance(image.std_error[k]), 2);
                    at_most += image.pixel_samples[k] == 4096;
                }
            EXPECT_TRUE(std::sqrt(variance) <= 0.03 * sum || at_most == 16)
                << "block " << bx << ", " << by << ": " << std::sqrt(variance) / sum;
        }
    double chi2 = 0.0, bias = 0.0;
    for (int y = 0; y < 12; ++y)
        for (int x = 0; x < 16; ++x) {
            const glm::dvec3 w = view.ray(x, y);
            const double mu_v = -w.z, mu_s = light.sun_direction.z;
            const double exact = a * std::numbers::pi * light.sun_radiance.x *
                henyey_greenstein(glm::dot(w, light.sun_direction), g) * mu_s / (mu_s + mu_v) *
                -std::expm1(-sigma * H * (1.0 / mu_v + 1.0 / mu_s));
            const std::size_t k = std::size_t(y) * 16 + x;
            const double z = (image.radiance[k].x - exact) / image.std_error[k].x;
            chi2 += z * z / (16 * 12);
            bias += z / (16 * 12);
        }
    EXPECT_GT(chi2, 0.6);
    EXPECT_LT(chi2, 1.5);
    EXPECT_LT(std::abs(bias), 4.0 / std::sqrt(16.0 * 12.0));
    // The same image on one thread; no rounds without a target.
    o.threads = 1;
    const PathTracedImage again = render_path_traced({&m, {}}, nullptr, view, light, o);
    EXPECT_EQ(again.radiance, image.radiance);
    EXPECT_EQ(again.pixel_samples, image.pixel_samples);
    o.noise_target = 0.0;
    const PathTracedImage plain = render_path_traced({&m, {}}, nullptr, view, light, o);
    EXPECT_EQ(plain.rounds, 1);
    EXPECT_EQ(plain.pixel_samples, std::vector<int>(16 * 12, o.samples));
}

TEST(PathTracer, BadInputStaysFinite)
{
    const Heightfield ground =
        kiri::test::make_heightfield(5, 5, 100.0, -200.0, -200.0, [](double x, double) { return 0.05 * x; });
    ReferenceView view;
    view.eye = {0.0, -300.0, 80.0};
    view.target = {0.0, 0.0, 20.0};
    view.width = 4;
    view.height = 3;
    PathTracerOptions o;
    o.samples = 4;
    auto check = [&](const FogVolume& fog, const FogLighting& light, const char* what) {
        const PathTracedImage image = render_path_traced(fog, &ground, view, light, o);
        EXPECT_EQ(image.dropped, 0) << what;
        for (std::size_t k = 0; k < image.radiance.size(); ++k)
            for (int c = 0; c < 3; ++c) {
                EXPECT_TRUE(std::isfinite(image.radiance[k][c])) << what;
                EXPECT_GE(image.radiance[k][c], 0.0) << what;
                EXPECT_TRUE(std::isfinite(image.std_error[k][c])) << what;
            }
    };
    FogLighting light = sun_at(0.5, 0.0, glm::dvec3(3.0));
    light.ambient = glm::dvec3(0.3);
    const Medium nan_density = slab(0.0, 50.0, std::nan(""), 0.9, 0.8);
    check({&nan_density, {}}, light, "NaN extinction");
    const Medium zero_density = slab(0.0, 50.0, 0.0, 0.9, 0.8);
    check({&zero_density, {}}, light, "zero extinction");
    for (double g : {1.0, -1.0, 0.9999999, std::nan("")}) {
        const Medium extreme = slab(0.0, 50.0, 0.03, 1.0, g);
        check({&extreme, {}}, light, "g at +-1");
    }
    const Medium fog = slab(0.0, 50.0, 0.03, 0.9, 0.8);
    FogLighting below = sun_at(-0.3, 0.0, glm::dvec3(3.0));
    below.terrain_shadows = true;
    check({&fog, {}}, below, "sun below the horizon");
    FogLighting broken = light;
    broken.sun_direction = glm::dvec3(0.0);
    broken.sun_radiance = {std::nan(""), 1.0, std::numeric_limits<double>::infinity()};
    broken.ambient = {-1.0, std::nan(""), 0.2};
    check({&fog, {}}, broken, "zero sun direction, non-finite radiance");
    HeightFog haze;
    haze.extinction = 0.01;
    haze.scale_height = 0.0;
    check({&fog, haze}, light, "height fog without a scale height");
}
