#pragma once
// GL's images run from the bottom row up, kiri's from the top row down.
#include <algorithm>
#include <cstddef>
#include <vector>

namespace kiri::render::detail {

//! Reverses the order of the rows (of `row` values each) of `data`, in place.
template <class T>
void flip_rows(std::vector<T>& data, std::size_t row)
{
    const std::size_t rows = row > 0 ? data.size() / row : 0;
    for (std::size_t y = 0; y < rows / 2; ++y)
        std::swap_ranges(data.begin() + std::ptrdiff_t(y * row), data.begin() + std::ptrdiff_t((y + 1) * row),
                         data.begin() + std::ptrdiff_t((rows - 1 - y) * row));
}

}  // namespace kiri::render::detail
