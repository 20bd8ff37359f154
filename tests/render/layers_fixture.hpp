#pragma once
// The layer pass's tests' fixture: a fog lake over the Gaussian hill, its fitted base, the frames
// of black fog over the bare terrain, and the Medium along a pixel's ray as their oracle.
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

}  // namespace
