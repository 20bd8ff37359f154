#pragma once
// Writes a stage's rows as CSV and draws its plot with gnuplot.
#include <filesystem>
#include <vector>

#include "bench/bench.hpp"

namespace kiri::bench {

void write_csv(const std::filesystem::path& path, const Stage& stage, const std::vector<Row>& rows);
//! Returns false (and says why on stderr) when gnuplot is missing or fails; the CSV stays.
bool write_plot(const std::filesystem::path& png, const Stage& stage, const std::vector<Row>& rows);

}  // namespace kiri::bench
