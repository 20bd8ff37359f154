#include "kiri/geometry/layers/layer_texture.hpp"

#include <algorithm>
#include <cmath>

#include "kiri/geometry/core/error.hpp"

namespace kiri::geometry {
namespace {

double smoothstep01(double x)
{
    if (x <= 0.0)
        return 0.0;
    if (x >= 1.0)
        return 1.0;
    return x * x * (3.0 - 2.0 * x);
}

constexpr glm::dvec2 corner_uv[4] = {{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}};

}  // namespace

BorderMask patch_border_mask(const ControlMesh& control, int face)
{
    const PolyMesh& m = control.mesh;
    const PolyMesh::FaceHandle f(face);
    int corner[4];
    int k = 0;
    for (auto v : m.fv_range(f))
        if (k < 4)
            corner[k++] = v.idx();
    BorderMask mask = 0;
    bool side_border[4] = {false, false, false, false};
    for (int s = 0; s < 4; ++s) {
        const auto he = m.find_halfedge(PolyMesh::VertexHandle(corner[s]), PolyMesh::VertexHandle(corner[(s + 1) % 4]));
        side_border[s] = he.is_valid() && m.is_boundary(m.edge_handle(he));
        if (side_border[s])
            mask |= BorderMask(1u << s);
    }
    for (int c = 0; c < 4; ++c) {
        // Corner c is met by side c (starting there) and side c - 1 (ending there).
        const bool sides = side_border[c] || side_border[(c + 3) % 4];
        if (!sides && m.is_boundary(PolyMesh::VertexHandle(corner[c])))
            mask |= BorderMask(1u << (4 + c));
    }
    return mask;
}

double border_alpha(BorderMask mask, double u, double v, double fade_width)
{
    const double w = fade_width;
    const double side_distance[4] = {v, 1.0 - u, 1.0 - v, u};
    double a = 1.0;
    for (int s = 0; s < 4; ++s)
        if (mask & (1u << s))
            a *= smoothstep01(side_distance[s] / w);
    for (int c = 0; c < 4; ++c)
        if (mask & (1u << (4 + c))) {
            const double d = std::hypot(u - corner_uv[c].x, v - corner_uv[c].y);
            a *= smoothstep01(d / w);
        }
    return a;
}

glm::dvec2 LayerTexture::atlas_uv(BorderMask mask, double u, double v) const
{
    const glm::ivec2 origin = tiles.at(mask);
    const double span = resolution - 1;
    return {(origin.x + 0.5 + u * span) / width, (origin.y + 0.5 + v * span) / height};
}

LayerTexture make_layer_texture(const std::vector<BorderMask>& masks, const LayerTextureOptions& options)
{
    check_fields(options, {}, "layers");
    std::vector<BorderMask> unique = masks;
    std::sort(unique.begin(), unique.end());
    unique.erase(std::unique(unique.begin(), unique.end()), unique.end());
    if (unique.empty())
        unique.push_back(0);

    LayerTexture t;
    t.resolution = options.resolution;
    const int n = int(unique.size());
    const int columns = int(std::ceil(std::sqrt(double(n))));
    const int rows = (n + columns - 1) / columns;
    t.width = columns * t.resolution;
    t.height = rows * t.resolution;
    t.rgba.assign(std::size_t(t.width) * t.height * 4, 0);
    const auto gray = std::uint8_t(std::lround(options.gray * 255.0));
    for (int k = 0; k < n; ++k) {
        const glm::ivec2 origin{(k % columns) * t.resolution, (k / columns) * t.resolution};
        t.tiles[unique[k]] = origin;
        for (int y = 0; y < t.resolution; ++y)
            for (int x = 0; x < t.resolution; ++x) {
                const double u = double(x) / (t.resolution - 1), v = double(y) / (t.resolution - 1);
                const double a = border_alpha(unique[k], u, v, options.fade_width);
                std::uint8_t* px = &t.rgba[(std::size_t(origin.y + y) * t.width + origin.x + x) * 4];
                px[0] = px[1] = px[2] = gray;
                px[3] = std::uint8_t(std::lround(a * 255.0));
            }
    }
    return t;
}

}  // namespace kiri::geometry
