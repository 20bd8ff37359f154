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

//! The views bench's canyon (apps/kiri/bench/views_bench.cpp): a meandering canyon 300 m deep in
//! a plateau rising northwards, 240 x 180 samples 10 m apart, centred on the origin.
inline geometry::Terrain views_bench_canyon()
{
    geometry::Heightfield hf;
    hf.nx = 240;
    hf.ny = 180;
    hf.dx = hf.dy = 10.0;
    hf.x0 = -0.5 * (hf.nx - 1) * hf.dx;
    hf.y0 = -0.5 * (hf.ny - 1) * hf.dy;
    hf.z.resize(std::size_t(hf.nx) * std::size_t(hf.ny));
    hf.valid.assign(hf.z.size(), 1);
    for (int j = 0; j < hf.ny; ++j)
        for (int i = 0; i < hf.nx; ++i) {
            const double x = double(i) / (hf.nx - 1), y = double(j) / (hf.ny - 1);
            const double axis = 0.5 + 0.1 * std::sin(6.0 * y);
            hf.z[std::size_t(j) * std::size_t(hf.nx) + std::size_t(i)] = 900.0 -
                300.0 * std::exp(-(x - axis) * (x - axis) / 0.008) + 60.0 * y + 20.0 * std::sin(9.0 * x + 3.0 * y);
        }
    return geometry::Terrain(std::move(hf));
}

}  // namespace kiri::test
