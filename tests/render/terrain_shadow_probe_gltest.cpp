// The terrain's shadow as the fog's lighting reads it (the exponential shadow map,
// terrain_shadow.glsl) against the heightfield's exact shadow, at points in the air of a canyon
// under a sun across it: the views bench's canyon as `kiri new` derives its sun (30 degrees up
// from the west-north-west), the west wall's shadow filling most of the canyon.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include <glm/geometric.hpp>

#include "kiri/geometry/terrain/terrain.hpp"
#include "render/render_fixture.hpp"
#include "shadow_map_pass.hpp"
#include "terrain_pass.hpp"

namespace {

namespace g = kiri::geometry;
using kiri::render::detail::ShadowMapPass;
using kiri::render::detail::TerrainPass;

bool sun_visible(const g::Terrain& t, const glm::dvec3& p, const glm::dvec3& sun)
{
    for (double s = 0.5; s < 5000.0; s += 0.5) {
        const glm::dvec3 q = p + sun * s;
        if (q.z > 1100.0)
            return true;
        if (q.z < t.height(q.x, q.y))
            return false;
    }
    return true;
}

class TerrainShadowProbeGl : public kiri::test::GlTest {};

TEST_F(TerrainShadowProbeGl, TheMapsShadowInTheAirOfACanyonIsTheHeightfields)
{
    const g::Terrain t = kiri::test::views_bench_canyon();
    TerrainPass terrain;
    terrain.set_terrain(t, 1.0);
    ShadowMapPass map;
    const glm::dvec3 sun = glm::normalize(glm::dvec3(-0.784778, 0.36623, 0.5));
    map.update(terrain, glm::vec3(sun), t.bounds().min, t.bounds().max, 1024, 4.0);
    std::vector<glm::vec3> points;
    std::vector<glm::dvec3> where;
    for (double y = -800.0; y <= 800.0; y += 100.0)
        for (double x = -400.0; x <= 400.0; x += 5.0)
            for (double z = 600.0; z <= 900.0; z += 5.0) {
                const glm::dvec3 p(x, y, z);
                if (p.z < t.height(p.x, p.y) + 1.0)
                    continue;
                where.push_back(p);
                points.emplace_back(p);
            }
    const std::vector<float> v = map.probe(points);
    int wrong = 0, shaded = 0;
    for (std::size_t k = 0; k < where.size(); ++k) {
        const bool exact = sun_visible(t, where[k], sun);
        shaded += exact ? 0 : 1;
        wrong += std::abs(v[k] - (exact ? 1.0f : 0.0f)) > 0.5f ? 1 : 0;
    }
    std::printf("%d of %zu points on the wrong side of the shadow (%d in it)\n", wrong, where.size(), shaded);
    EXPECT_GT(shaded, 100);
    EXPECT_LT(wrong, shaded / 20);
}

}  // namespace
