#pragma once
// Rows of work on every core: the CPU judges (reference ray marcher, path tracer, the light
// volume's bake) render an image's rows, the tessellation measures its triangles.
#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

namespace kiri::geometry::detail {

//! Runs `work(next_row)` on `requested` threads (0: one per core; never more than rows), the
//! calling thread among them. Each call takes rows from `next_row()` until it returns `rows`
//! or more, so slow rows balance out; per-thread state lives inside `work`.
template <class Work>
void for_rows_in_parallel(int requested, int rows, Work work)
{
    std::atomic<int> next{0};
    const auto next_row = [&next] { return next++; };
    int threads = requested > 0 ? requested : int(std::thread::hardware_concurrency());
    threads = std::clamp(threads, 1, std::max(1, rows));
    std::vector<std::thread> pool;
    for (int k = 1; k < threads; ++k)
        pool.emplace_back([&] { work(next_row); });
    work(next_row);
    for (std::thread& t : pool)
        t.join();
}

}  // namespace kiri::geometry::detail
