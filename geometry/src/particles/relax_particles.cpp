#include "particles/relax_particles.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "particles/for_slices.hpp"

namespace kiri::geometry::detail {
namespace {

bool has_fog(const MediumColumn& c) { return c.coverage > 0.0 && c.top > c.floor; }

// Points bucketed in columns of side `cell` over their bounding box in (x, y), each column's
// points stored together (position, spacing, index) and sorted by height, with the largest
// spacing among them. Columns, not cubes: a blanket one particle deep leaves most cubes of its
// box empty, and a neighbour search would spend its time stepping over them; within a column
// the heights in reach are found by bisection, however deep the fog.
class PointColumns {
public:
    struct Entry {
        glm::dvec3 p;
        double h;
        std::uint32_t index;
    };

    PointColumns(const std::vector<glm::dvec3>& points, const std::vector<double>& h, double cell) : cell_(cell)
    {
        lo_ = glm::dvec2(HUGE_VAL);
        glm::dvec2 hi(-HUGE_VAL);
        for (const glm::dvec3& p : points) {
            lo_ = glm::min(lo_, glm::dvec2(p));
            hi = glm::max(hi, glm::dvec2(p));
        }
        // Columns no narrower than the points' number allows (about 8 a point at most): a few
        // points spread far apart would otherwise ask for billions.
        const glm::dvec2 extent = glm::max(hi - lo_, glm::dvec2(0.0));
        const double most = 8.0 * double(points.size()) + 64.0;
        while ((extent.x / cell_ + 1.0) * (extent.y / cell_ + 1.0) > most)
            cell_ *= 1.25;
        n_ = glm::ivec2(extent / cell_) + 1;
        const std::size_t cells = std::size_t(n_.x) * n_.y;
        start_.assign(cells + 1, 0);
        largest_.assign(cells, 0.0);
        for (std::size_t k = 0; k < points.size(); ++k) {
            const std::size_t c = index(cell_of(points[k]));
            ++start_[c + 1];
            largest_[c] = std::max(largest_[c], h[k]);
        }
        for (std::size_t i = 1; i < start_.size(); ++i)
            start_[i] += start_[i - 1];
        entries_.resize(points.size());
        std::vector<std::size_t> fill(start_.begin(), start_.end() - 1);
        for (std::size_t k = 0; k < points.size(); ++k)
            entries_[fill[index(cell_of(points[k]))]++] = {points[k], h[k], std::uint32_t(k)};
        const auto lower = [](const Entry& a, const Entry& b) {
            return a.p.z < b.p.z || (a.p.z == b.p.z && a.index < b.index);
        };
        for (std::size_t i = 0; i < cells; ++i)
            std::sort(entries_.begin() + std::ptrdiff_t(start_[i]), entries_.begin() + std::ptrdiff_t(start_[i + 1]),
                      lower);
    }
    //! f(entry) for every point j that may lie within reach (h + h_j) / 2 of p (`largest_h` the
    //! largest h_j), in the order of the columns, then of height.
    template <class F>
    void near(const glm::dvec3& p, double h, double reach, double largest_h, F&& f) const
    {
        const glm::ivec2 c = cell_of(p);
        const int r = int(std::ceil(reach * 0.5 * (h + largest_h) / cell_));
        for (int y = std::max(c.y - r, 0); y <= std::min(c.y + r, n_.y - 1); ++y) {
            const double dy = gap(p.y, lo_.y, y);
            for (int x = std::max(c.x - r, 0); x <= std::min(c.x + r, n_.x - 1); ++x) {
                const std::size_t i = index({x, y});
                const double within = reach * 0.5 * (h + largest_[i]), dx = gap(p.x, lo_.x, x);
                if (start_[i] == start_[i + 1] || dx * dx + dy * dy >= within * within)
                    continue;
                const auto first = entries_.begin() + std::ptrdiff_t(start_[i]);
                const auto last = entries_.begin() + std::ptrdiff_t(start_[i + 1]);
                auto e = std::partition_point(first, last, [&](const Entry& q) { return q.p.z < p.z - within; });
                for (; e != last && e->p.z <= p.z + within; ++e)
                    f(*e);
            }
        }
    }

private:
    double cell_;
    glm::dvec2 lo_;
    glm::ivec2 n_;
    std::vector<std::size_t> start_;
    std::vector<double> largest_;
    std::vector<Entry> entries_;
    //! The distance from v to the column's side [lo + i cell, lo + (i + 1) cell] along one axis.
    double gap(double v, double lo, int i) const
    {
        const double a = lo + i * cell_, b = a + cell_;
        return v < a ? a - v : (v > b ? v - b : 0.0);
    }
    glm::ivec2 cell_of(const glm::dvec3& p) const
    {
        return glm::clamp(glm::ivec2(glm::floor((glm::dvec2(p) - lo_) / cell_)), glm::ivec2(0), n_ - 1);
    }
    std::size_t index(const glm::ivec2& c) const { return std::size_t(c.y) * n_.x + c.x; }
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
    const auto spacing_at = [&](const glm::dvec3& p) {
        const double s = fog.spacing(p);
        return std::isfinite(s) && s > 0.0 ? s : 0.0;
    };
    // Each point's spacing and column, kept from the sweep that last moved it; and whether the
    // fog's edge lies within its reach: those points stay (8 columns on the circle of the reach).
    std::vector<double> h(n);
    std::vector<MediumColumn> columns(n);
    std::vector<char> pinned(n, 0);
    for_slices(n, [&](std::size_t first, std::size_t end) {
        for (std::size_t k = first; k < end; ++k) {
            const glm::dvec3& p = points[k];
            h[k] = spacing_at(p);
            columns[k] = fog.column(p.x, p.y);
            const double r = reach * h[k];
            bool edge = !(r > 0.0);
            for (int a = 0; a < 8 && !edge; ++a) {
                const double phi = std::numbers::pi * a / 4.0;
                edge = !has_fog(fog.column(p.x + r * std::cos(phi), p.y + r * std::sin(phi)));
            }
            pinned[k] = edge;
        }
    });
    std::vector<glm::dvec3> next = points;
    std::vector<double> next_h = h;
    for (int it = 0; it < iterations; ++it) {
        double cell = HUGE_VAL, largest = 0.0;
        for (std::size_t k = 0; k < n; ++k)
            if (h[k] > 0.0) {
                cell = std::min(cell, reach * h[k]);
                largest = std::max(largest, h[k]);
            }
        if (!std::isfinite(cell))
            return;
        const PointColumns grid(points, h, cell);
        for_slices(n, [&](std::size_t first, std::size_t end) {
            for (std::size_t k = first; k < end; ++k) {
                next[k] = points[k];
                next_h[k] = h[k];
                if (pinned[k] || !(h[k] > 0.0))
                    continue;
                const glm::dvec3 p = points[k];
                glm::dvec3 push(0.0);
                // Two points keep reach times the mean of their spacings apart.
                grid.near(p, h[k], reach, largest, [&](const PointColumns::Entry& e) {
                    const glm::dvec3 d = p - e.p;
                    const double r = reach * 0.5 * (h[k] + e.h), len2 = glm::dot(d, d);
                    if (e.index == k || !(e.h > 0.0) || !(len2 < r * r * (1.0 + 1e-9)))
                        return;
                    const double len = std::sqrt(len2);
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
                const MediumColumn a = columns[k], b = fog.column(q.x, q.y);
                if (!has_fog(a) || !has_fog(b))
                    continue;
                q.z = b.floor + (p.z - a.floor) / (a.top - a.floor) * (b.top - b.floor);
                if (std::isfinite(q.z) && fog.density(q) > 0.0) {
                    next[k] = q;
                    next_h[k] = spacing_at(q);
                    columns[k] = b;  // read by this point alone
                }
            }
        });
        points.swap(next);
        h.swap(next_h);
    }
}

}  // namespace kiri::geometry::detail
