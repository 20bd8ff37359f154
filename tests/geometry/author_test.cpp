// The authoring pipeline on the real Jacksboro DEM (data/terrains), the path `kiri author` takes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "kiri/geometry/scene/author_report.hpp"
#include "kiri/geometry/scene/pipeline.hpp"

using namespace kiri::geometry;

namespace {
// The DEM at its own heights with `fog` over it.
Scene jacksboro(const FogSpec& fog)
{
    Scene scene;
    scene.file = "jacksboro.json";
    scene.terrain.path = KIRI_DATA_DIR "/terrains/jacksboro_fault_dem.tif";
    scene.fog = fog;
    return scene;
}

// The tessellated surface's height at every terrain grid vertex it covers (linear on its
// triangles), as a raster; NaN where no triangle covers the vertex.
std::vector<double> raster(const TriMesh& m, const Heightfield& hf)
{
    std::vector<double> z(hf.size(), NAN);
    for (auto f : m.faces()) {
        TriMesh::Point p[3];
        int k = 0;
        for (auto v : m.fv_range(f))
            p[k++] = m.point(v);
        const double d = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
        const int i0 = std::max(0, int(std::ceil((std::min({p[0][0], p[1][0], p[2][0]}) - hf.x0) / hf.dx)));
        const int i1 = std::min(hf.nx - 1, int(std::floor((std::max({p[0][0], p[1][0], p[2][0]}) - hf.x0) / hf.dx)));
        const int j0 = std::max(0, int(std::ceil((std::min({p[0][1], p[1][1], p[2][1]}) - hf.y0) / hf.dy)));
        const int j1 = std::min(hf.ny - 1, int(std::floor((std::max({p[0][1], p[1][1], p[2][1]}) - hf.y0) / hf.dy)));
        for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i) {
                const double x = hf.x_of(i), y = hf.y_of(j);
                const double a = ((p[1][0] - x) * (p[2][1] - y) - (p[2][0] - x) * (p[1][1] - y)) / d;
                const double b = ((p[2][0] - x) * (p[0][1] - y) - (p[0][0] - x) * (p[2][1] - y)) / d;
                if (a >= 0 && b >= 0 && a + b <= 1)
                    z[std::size_t(j) * hf.nx + i] = a * p[0][2] + b * p[1][2] + (1 - a - b) * p[2][2];
            }
    }
    return z;
}
}  // namespace

TEST(Author, JacksboroBlanketHugsTheRidgesWithoutDippingIntoThem)
{
    FogSpec spec;
    spec.margin = 500.0;
    const Scene scene = jacksboro(spec);
    Pipeline pipeline;
    const PipelineProducts& a = pipeline.run(scene);
    const Terrain& t = *a.terrain;
    const FitReport& fit = a.surface->fit;
    EXPECT_GE(fit.min_clearance, spec.fit.clearance);
    EXPECT_GT(fit.grid_vertex_samples, 120000);
    const auto z = raster(a.tessellation->mesh, t.heightfield());
    double min_clear = 1e300, covered = 0, close = 0;
    for (std::size_t k = 0; k < z.size(); ++k)
        if (!std::isnan(z[k])) {
            const double c = z[k] - t.heightfield().z[k];
            min_clear = std::min(min_clear, c);
            ++covered;
            close += c < spec.fit.clearance + 20.0;  // hugging: within 20 m of its bound
        }
    EXPECT_GT(covered, 0.9 * double(z.size()));
    // The triangles lie within the tessellation error of the surface.
    EXPECT_GE(min_clear, spec.fit.clearance - a.tessellation->max_error - 1e-6);
    EXPECT_GT(close / covered, 0.01) << "the blanket never comes near the ridges";
    const auto report = nlohmann::json::parse(author_report_json(scene, a, pipeline.stages()));
    EXPECT_EQ(report["fit"]["min_clearance_m"].get<double>(), fit.min_clearance);
    EXPECT_EQ(report["counts"]["triangles"].get<std::size_t>(), a.tessellation->mesh.n_faces());
    EXPECT_EQ(report["fog"]["mode"], "blanket");
}

TEST(Author, JacksboroLakeFillsTheValleys)
{
    FogSpec spec;
    spec.margin = 500.0;
    spec.fit.mode = FitMode::lake;
    spec.fit.altitude = 420.0;
    const PipelineProducts a = author_scene(jacksboro(spec));
    const Terrain& t = *a.terrain;
    for (auto v : a.tessellation->mesh.vertices())
        ASSERT_NEAR(a.tessellation->mesh.point(v)[2], 420.0, 1e-9);
    // Fog where the terrain is below 420 m: the samples' fraction matches the DEM's own.
    const auto& z = t.heightfield().z;
    const double below = double(std::count_if(z.begin(), z.end(), [](double h) { return h < 420.0; })) / z.size();
    EXPECT_NEAR(a.surface->fit.fog_fraction, below, 0.03);
    EXPECT_GT(a.surface->fit.fog_fraction, 0.1);
}
