#pragma once
// Internal: work over the particles on every core, a contiguous slice each.
#include <algorithm>
#include <cstddef>
#include <thread>
#include <vector>

namespace kiri::geometry::detail {

//! Runs body(first, end) over [0, n) in one slice a core (at most one a thousand items), the
//! calling thread taking the first. For work whose items depend on nothing the others write:
//! the same result on any number of threads.
template <class Body>
void for_slices(std::size_t n, Body&& body)
{
    const std::size_t threads =
        std::clamp<std::size_t>(std::thread::hardware_concurrency(), 1, std::max<std::size_t>(n / 1000, 1));
    std::vector<std::thread> pool;
    for (std::size_t t = 1; t < threads; ++t)
        pool.emplace_back([&body, n, t, threads] { body(n * t / threads, n * (t + 1) / threads); });
    body(0, n / threads);
    for (std::thread& t : pool)
        t.join();
}

}  // namespace kiri::geometry::detail
