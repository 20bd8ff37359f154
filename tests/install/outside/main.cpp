// Uses kiri through its installed headers and libraries: a terrain query, a Gregory patch
// evaluation and a camera projection. Prints what it computed; exits non-zero on a mismatch.
#include <cmath>
#include <cstdio>

#include <kiri/geometry/surface/gregory_patch.hpp>
#include <kiri/geometry/terrain/terrain.hpp>
#include <kiri/render/camera.hpp>

int main()
{
    kiri::geometry::Heightfield hf;
    hf.nx = hf.ny = 3;
    hf.z = {0, 1, 2, 1, 2, 3, 2, 3, 4};  // z = i + j: a plane
    hf.valid.assign(9, 1);
    const kiri::geometry::Terrain terrain(hf);
    const double h = terrain.height(0.5, 1.25);

    // A bicubic patch whose control net is the plane z = 0 on [0, 3]^2: S(u, v) = (3u, 3v, 0).
    kiri::geometry::GregoryPatch::Points points{};
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i)
            for (int k = 0; k < 2; ++k)
                points[kiri::geometry::GregoryPatch::index(i, j, k)] = {double(i), double(j), 0.0};
    const kiri::geometry::PatchPoint p = kiri::geometry::evaluate(kiri::geometry::GregoryPatch(points), 0.25, 0.5);

    kiri::render::Camera camera;
    camera.position = {0.0, -10.0, 0.0};
    camera.target = {0.0, 0.0, 0.0};
    const glm::dvec2 px = kiri::render::project_to_pixel(camera, camera.target, 100, 50);

    std::printf("height %.6f patch %.6f %.6f %.6f pixel %.3f %.3f\n", h, p.position.x, p.position.y, p.position.z, px.x,
                px.y);
    const bool ok = std::abs(h - 1.75) < 1e-12 && std::abs(p.position.x - 0.75) < 1e-12 &&
        std::abs(p.position.y - 1.5) < 1e-12 && std::abs(px.x - 50.0) < 1e-9 && std::abs(px.y - 25.0) < 1e-9;
    return ok ? 0 : 1;
}
