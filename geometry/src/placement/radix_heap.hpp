#pragma once
// Internal: a monotone priority queue (radix heap, [Ahuja90]) for
// the priority-flood. The flood only ever pushes keys >= the last popped one, which is what a
// radix heap needs: keys live in 65 buckets by the highest bit in which they differ from the
// last popped key; a pop that empties bucket 0 redistributes the lowest non-empty bucket into
// lower ones. Each item moves down at most 64 times, in practice once or twice, and memory is
// touched in order: far faster than a binary heap on tens of millions of cells.
#include <bit>
#include <cstdint>
#include <cstring>
#include <vector>

namespace kiri::geometry::detail {

//! Order-preserving map of finite doubles to unsigned integers (a < b <=> key(a) < key(b)).
inline std::uint64_t order_key(double v)
{
    std::uint64_t u;
    std::memcpy(&u, &v, sizeof u);
    return (u >> 63) ? ~u : (u | (std::uint64_t(1) << 63));
}

inline double key_value(std::uint64_t k)
{
    const std::uint64_t u = (k >> 63) ? (k & ~(std::uint64_t(1) << 63)) : ~k;
    double v;
    std::memcpy(&v, &u, sizeof v);
    return v;
}

struct FloodItem {
    std::uint64_t key;     // order_key of the flood level
    std::uint32_t cell;    // j * nx + i
    std::uint32_t saddle;  // the cell whose ground set this level (where the path peaks)
};

class RadixHeap {
public:
    bool empty() const { return size_ == 0; }
    std::size_t size() const { return size_; }

    //! item.key must be >= the last popped key.
    void push(const FloodItem& item)
    {
        buckets_[bucket(item.key)].push_back(item);
        ++size_;
    }

    FloodItem pop()
    {
        if (buckets_[0].empty()) {
            int b = 1;
            while (buckets_[b].empty())
                ++b;
            std::uint64_t lowest = buckets_[b][0].key;
            for (const FloodItem& it : buckets_[b])
                lowest = it.key < lowest ? it.key : lowest;
            last_ = lowest;
            for (const FloodItem& it : buckets_[b])
                buckets_[bucket(it.key)].push_back(it);
            buckets_[b].clear();
        }
        const FloodItem it = buckets_[0].back();
        buckets_[0].pop_back();
        --size_;
        return it;
    }

private:
    int bucket(std::uint64_t key) const { return key == last_ ? 0 : 64 - std::countl_zero(key ^ last_); }
    std::vector<FloodItem> buckets_[65];
    std::uint64_t last_ = 0;
    std::size_t size_ = 0;
};

}  // namespace kiri::geometry::detail
