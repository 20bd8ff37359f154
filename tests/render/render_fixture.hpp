#pragma once
// Shared by the GL tests: one headless context per test program, GL errors fatal, every test
// checked for GL errors when it ends, and small analytic terrains built in code.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "kiri/geometry/terrain/terrain.hpp"
#include "kiri/render/gl_context.hpp"

namespace kiri::test {

class GlTest : public ::testing::Test {
protected:
    static void SetUpTestSuite()
    {
        if (!context())
            context() = render::create_headless_context({.debug = true, .throw_on_gl_error = true});
        context()->make_current();
    }
    // A GL error anywhere in the test (the debug callback counts them, including those a test
    // caught as exceptions) fails it, whatever the test asserted itself.
    void TearDown() override
    {
        EXPECT_EQ(render::gl_error_count(), 0) << "GL errors were reported (the 'kiri gl:' lines above)";
    }
    static std::unique_ptr<render::GlContext>& context()
    {
        static std::unique_ptr<render::GlContext> instance;
        return instance;
    }
};

//! z = peak * exp(-r^2 / (2 sigma^2)) on an n x n grid of spacing d centred on the origin.
inline geometry::Terrain gaussian_hill(int n = 65, double d = 20.0, double peak = 300.0, double sigma = 250.0)
{
    geometry::Heightfield hf;
    hf.nx = hf.ny = n;
    hf.dx = hf.dy = d;
    hf.x0 = hf.y0 = -0.5 * (n - 1) * d;
    hf.z.resize(std::size_t(n) * n);
    hf.valid.assign(hf.z.size(), 1);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const double x = hf.x_of(i), y = hf.y_of(j);
            hf.z[std::size_t(j) * n + i] = peak * std::exp(-(x * x + y * y) / (2.0 * sigma * sigma));
        }
    return geometry::Terrain(std::move(hf));
}

}  // namespace kiri::test
