#include "particles/sample_elimination.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace kiri::geometry::detail {
namespace {

// Yuksel's r_max for a spacing h in 3D: r_max = cbrt(V / (4 sqrt(2) N)) = h / cbrt(4 sqrt 2).
const double r_max_per_spacing = 1.0 / std::cbrt(4.0 * std::sqrt(2.0));
constexpr double limit_beta = 0.65, limit_gamma = 1.5;  // weight limiting

// Max-heap of weights with positions, so a weight can drop and sift down in place.
class WeightHeap {
public:
    explicit WeightHeap(const std::vector<double>& w) : w_(w), heap_(w.size()), pos_(w.size())
    {
        for (std::size_t i = 0; i < heap_.size(); ++i)
            heap_[i] = pos_[i] = i;
        for (std::size_t i = heap_.size() / 2; i-- > 0;)
            down(i);
    }
    bool empty() const { return heap_.empty(); }
    std::size_t pop()
    {
        const std::size_t top = heap_.front();
        swap(0, heap_.size() - 1);
        heap_.pop_back();
        pos_[top] = npos;
        if (!heap_.empty())
            down(0);
        return top;
    }
    bool contains(std::size_t i) const { return pos_[i] != npos; }
    void decrease(std::size_t i, double by)
    {
        w_[i] -= by;
        down(pos_[i]);
    }

private:
    static constexpr std::size_t npos = std::size_t(-1);
    std::vector<double> w_;
    std::vector<std::size_t> heap_, pos_;
    // Ties go to the lower index, so the order does not depend on the heap's history alone.
    bool above(std::size_t a, std::size_t b) const { return w_[a] > w_[b] || (w_[a] == w_[b] && a < b); }
    void swap(std::size_t a, std::size_t b)
    {
        std::swap(heap_[a], heap_[b]);
        pos_[heap_[a]] = a;
        pos_[heap_[b]] = b;
    }
    void down(std::size_t i)
    {
        for (;;) {
            std::size_t best = i;
            for (std::size_t c = 2 * i + 1; c <= 2 * i + 2 && c < heap_.size(); ++c)
                if (above(heap_[c], heap_[best]))
                    best = c;
            if (best == i)
                return;
            swap(i, best);
            i = best;
        }
    }
};

}  // namespace

std::vector<std::size_t> eliminate_samples(const std::vector<glm::dvec3>& points, const std::vector<double>& spacing,
                                           double cell, std::size_t target)
{
    const std::size_t m = points.size();
    std::vector<std::size_t> kept;
    if (target >= m) {
        for (std::size_t i = 0; i < m; ++i)
            kept.push_back(i);
        return kept;
    }
    // Neighbour grid: a dense array of cells (counting sort), grown when the box would need more
    // than ~16 cells per point.
    glm::dvec3 lo = points.front(), hi = points.front();
    for (const glm::dvec3& p : points) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    glm::ivec3 dims;
    for (;;) {
        dims = glm::ivec3(glm::floor((hi - lo) / cell)) + 1;
        if (double(dims.x) * dims.y * dims.z <= 16.0 * double(m) + 64.0)
            break;
        cell *= 1.5;
    }
    const auto cell_of = [&](const glm::dvec3& p) {
        return glm::clamp(glm::ivec3(glm::floor((p - lo) / cell)), glm::ivec3(0), dims - 1);
    };
    const auto flat = [&](const glm::ivec3& c) { return (std::size_t(c.z) * dims.y + c.y) * dims.x + c.x; };
    std::vector<std::uint32_t> start(std::size_t(dims.x) * dims.y * dims.z + 1, 0), sorted(m);
    for (const glm::dvec3& p : points)
        ++start[flat(cell_of(p)) + 1];
    for (std::size_t c = 1; c < start.size(); ++c)
        start[c] += start[c - 1];
    {
        std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
        for (std::size_t i = 0; i < m; ++i)
            sorted[fill[flat(cell_of(points[i]))]++] = std::uint32_t(i);
    }
    // Work in cell order: neighbours then sit next to each other in memory.
    std::vector<glm::dvec3> pts(m);
    std::vector<double> h(m);
    for (std::size_t s = 0; s < m; ++s) {
        pts[s] = points[sorted[s]];
        h[s] = spacing[sorted[s]];
    }

    const double limit = limit_beta * (1.0 - std::pow(double(target) / double(m), limit_gamma));
    const auto pair_weight = [&](std::size_t i, std::size_t j) {
        const double two_r = r_max_per_spacing * (h[i] + h[j]);
        const double d = std::max(glm::distance(pts[i], pts[j]), limit * two_r);
        if (!(d < two_r))
            return 0.0;
        const double x = 1.0 - d / two_r, x2 = x * x, x4 = x2 * x2;
        return x4 * x4;  // alpha = 8
    };
    // Neighbours (CSR) within 2 r_ij: found from the point with the larger spacing, whose search
    // radius r_max (h_i + h_j) <= 2 r_max h_i covers the pair.
    std::vector<std::vector<std::uint32_t>> near(m);
    for (std::size_t i = 0; i < m; ++i) {
        const glm::ivec3 c = cell_of(pts[i]);
        const int reach = int(std::ceil(2.0 * r_max_per_spacing * h[i] / cell));
        const glm::ivec3 a = glm::max(c - reach, glm::ivec3(0)), b = glm::min(c + reach, dims - 1);
        for (int z = a.z; z <= b.z; ++z)
            for (int y = a.y; y <= b.y; ++y)
                for (std::uint32_t j = start[flat({a.x, y, z})], e = start[flat({b.x, y, z}) + 1]; j < e; ++j) {
                    if (j == i || h[j] > h[i] || (h[j] == h[i] && j < i))
                        continue;
                    if (pair_weight(i, j) > 0.0) {
                        near[i].push_back(j);
                        near[j].push_back(std::uint32_t(i));
                    }
                }
    }
    std::vector<double> weight(m, 0.0);
    for (std::size_t i = 0; i < m; ++i) {
        std::sort(near[i].begin(), near[i].end());  // summation order independent of the grid's
        for (std::uint32_t j : near[i])
            weight[i] += pair_weight(i, j);
    }
    WeightHeap heap(weight);
    for (std::size_t alive = m; alive > target; --alive) {
        const std::size_t i = heap.pop();
        for (std::uint32_t j : near[i])
            if (heap.contains(j))
                heap.decrease(j, pair_weight(i, j));
    }
    for (std::size_t s = 0; s < m; ++s)
        if (heap.contains(s))
            kept.push_back(sorted[s]);
    std::sort(kept.begin(), kept.end());
    return kept;
}

}  // namespace kiri::geometry::detail
