#include "terrain/nodata_fill.hpp"

#include <cstddef>

namespace kiri::geometry {

void fill_from_nearest_valid(int nx, int ny, std::vector<double>& z, const std::vector<std::uint8_t>& valid)
{
    // known: 1 once a cell has a value (valid or filled in an earlier ring); 2 = queued.
    std::vector<std::uint8_t> known(valid.begin(), valid.end());
    std::vector<std::size_t> ring, next;
    const auto for_neighbours = [nx, ny](std::size_t k, auto&& fn) {
        const int i = int(k % std::size_t(nx)), j = int(k / std::size_t(nx));
        for (int b = -1; b <= 1; ++b)
            for (int a = -1; a <= 1; ++a)
                if ((a || b) && i + a >= 0 && i + a < nx && j + b >= 0 && j + b < ny)
                    fn(std::size_t(j + b) * nx + (i + a));
    };
    for (std::size_t k = 0; k < z.size(); ++k)
        if (!known[k]) {
            bool touches = false;
            for_neighbours(k, [&](std::size_t n) { touches = touches || known[n] == 1; });
            if (touches) {
                known[k] = 2;
                ring.push_back(k);
            }
        }
    std::vector<double> values;
    while (!ring.empty()) {
        // Values of the whole ring first, from cells known before it, so the result does not
        // depend on the order inside a ring.
        values.assign(ring.size(), 0.0);
        for (std::size_t r = 0; r < ring.size(); ++r) {
            double sum = 0.0;
            int count = 0;
            for_neighbours(ring[r], [&](std::size_t n) {
                if (known[n] == 1)
                    sum += z[n], ++count;
            });
            values[r] = sum / count;  // count >= 1: every ring cell touches a known cell
        }
        next.clear();
        for (std::size_t r = 0; r < ring.size(); ++r) {
            z[ring[r]] = values[r];
            known[ring[r]] = 1;
        }
        for (const std::size_t k : ring)
            for_neighbours(k, [&](std::size_t n) {
                if (!known[n]) {
                    known[n] = 2;
                    next.push_back(n);
                }
            });
        ring.swap(next);
    }
}

}  // namespace kiri::geometry
