#include "particles/relax_particles.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "particles/for_slices.hpp"

namespace kiri::geometry::detail {
namespace {

bool has_fog(const MediumColumn& c) { return c.coverage > 0.0 && c.top > c.floor; }

// Points bucketed in cubes of side `cell` over their bounding box.
class PointGrid {
public:
    PointGrid(const std::vector<glm::dvec3>& points, double cell) : cell_(cell)
    {
        lo_ = glm::dvec3(HUGE_VAL);
        glm::dvec3 hi(-HUGE_VAL);
        for (const glm::dvec3& p : points) {
            lo_ = glm::min(lo_, p);
            hi = glm::max(hi, p);
        }
        // Cells no smaller than the points' number allows (about 8 a point at most): a few
        // points spread far apart would otherwise ask for billions.
        const glm::dvec3 extent = glm::max(hi - lo_, glm::dvec3(0.0));
        const double most = 8.0 * double(points.size()) + 64.0;
        while ((extent.x / cell_ + 1.0) * (extent.y / cell_ + 1.0) * (extent.z / cell_ + 1.0) > most)
            cell_ *= 1.25;
        n_ = glm::ivec3(extent / cell_) + 1;
        start_.assign(std::size_t(n_.x) * n_.y * n_.z + 1, 0);
        for (const glm::dvec3& p : points)
            ++start_[index(cell_of(p)) + 1];
        for (std::size_t i = 1; i < start_.size(); ++i)
            start_[i] += start_[i - 1];
        items_.resize(points.size());
        std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
        for (std::size_t k = 0; k < points.size(); ++k)
            items_[fill[index(cell_of(points[k]))]++] = std::uint32_t(k);
    }
    glm::ivec3 cell_of(const glm::dvec3& p) const
    {
        return glm::clamp(glm::ivec3(glm::floor((p - lo_) / cell_)), glm::ivec3(0), n_ - 1);
    }
    //! f(j) for every point in the cells within `reach` metres of p's cell.
    template <class F>
    void near(const glm::dvec3& p, double reach, F&& f) const
    {
        const glm::ivec3 c = cell_of(p);
        const int r = int(std::ceil(reach / cell_));
        for (int z = std::max(c.z - r, 0); z <= std::min(c.z + r, n_.z - 1); ++z)
            for (int y = std::max(c.y - r, 0); y <= std::min(c.y + r, n_.y - 1); ++y)
                for (int x = std::max(c.x - r, 0); x <= std::min(c.x + r, n_.x - 1); ++x) {
                    const std::size_t i = index({x, y, z});
                    for (std::size_t k = start_[i]; k < start_[i + 1]; ++k)
                        f(items_[k]);
                }
    }

private:
    double cell_;
    glm::dvec3 lo_;
    glm::ivec3 n_;
    std::vector<std::size_t> start_;
    std::vector<std::uint32_t> items_;
    std::size_t index(const glm::ivec3& c) const { return (std::size_t(c.z) * n_.y + c.y) * n_.x + c.x; }
};

}  // namespace

void relax_points(std::vector<glm::dvec3>& points, const RelaxFog& fog, int iterations, double reach)
{
    const std::size_t n = points.size();
    if (n < 2 || iterations <= 0 || !(reach > 0.0))
        return;
    for (const glm::dvec3& p : points)  // the grid's box needs finite points (the sampler's are)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            return;
    std::vector<double> h(n);
    const auto spacing_at = [&](const glm::dvec3& p) {
        const double s = fog.spacing(p);
        return std::isfinite(s) && s > 0.0 ? s : 0.0;
    };
    // The fog's edge within reach: those points stay (8 columns on the circle of the reach).
    std::vector<char> pinned(n, 0);
    for_slices(n, [&](std::size_t first, std::size_t end) {
        for (std::size_t k = first; k < end; ++k) {
            const glm::dvec3& p = points[k];
            const double r = reach * spacing_at(p);
            bool edge = !(r > 0.0);
            for (int a = 0; a < 8 && !edge; ++a) {
                const double phi = std::numbers::pi * a / 4.0;
                edge = !has_fog(fog.column(p.x + r * std::cos(phi), p.y + r * std::sin(phi)));
            }
            pinned[k] = edge;
        }
    });
    std::vector<glm::dvec3> next = points;
    for (int it = 0; it < iterations; ++it) {
        double cell = HUGE_VAL;
        for_slices(n, [&](std::size_t first, std::size_t end) {
            for (std::size_t k = first; k < end; ++k)
                h[k] = spacing_at(points[k]);
        });
        for (std::size_t k = 0; k < n; ++k)
            if (h[k] > 0.0)
                cell = std::min(cell, reach * h[k]);
        if (!std::isfinite(cell))
            return;
        const PointGrid grid(points, cell);
        for_slices(n, [&](std::size_t first, std::size_t end) {
            for (std::size_t k = first; k < end; ++k) {
                next[k] = points[k];
                if (pinned[k])
                    continue;
                const glm::dvec3 p = points[k];
                glm::dvec3 push(0.0);
                // Two points keep reach times the mean of their spacings apart; a neighbour whose
                // spacing is larger than the cell's worth beyond this one's may be missed where
                // the fog thins out fast, which only weakens a push.
                grid.near(p, reach * h[k] + cell, [&](std::uint32_t j) {
                    if (j == k || !(h[j] > 0.0))
                        return;
                    const glm::dvec3 d = p - points[j];
                    const double len = glm::length(d), r = reach * 0.5 * (h[k] + h[j]);
                    if (!(len < r) || !(len > 0.0))
                        return;
                    const double s = 1.0 - len / r;
                    push += d / len * (s * s * r);
                });
                push.z = 0.0;
                const double size = glm::length(push);
                if (!(size > 0.0) || !std::isfinite(size))
                    continue;
                push *= std::min(0.25, 0.15 * h[k] / size);
                glm::dvec3 q = p + push;
                const MediumColumn a = fog.column(p.x, p.y), b = fog.column(q.x, q.y);
                if (!has_fog(a) || !has_fog(b))
                    continue;
                q.z = b.floor + (p.z - a.floor) / (a.top - a.floor) * (b.top - b.floor);
                if (std::isfinite(q.z) && fog.density(q) > 0.0)
                    next[k] = q;
            }
        });
        points.swap(next);
    }
}

}  // namespace kiri::geometry::detail
