#pragma once
//! \file bench.hpp
//! The thin harness behind `kiri bench`: every stage contributes rows of
//! (series, parameters, x, time, error metric, error value, peak memory) to DIR/<stage>.csv
//! and one plot DIR/<stage>.png (gnuplot). Stages register themselves with KIRI_BENCH_STAGE.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace kiri::bench {

struct Row {
    std::string series;      //!< one curve of the plot, e.g. "gregory", "opensubdiv"
    std::string parameters;  //!< human-readable, e.g. "cells=1024^2"
    double x = 0.0;          //!< abscissa of the plot (size, level, resolution, ...)
    double time_s = 0.0;
    std::string error_metric;  //!< e.g. "max |dp| (m)"; empty when there is none
    double error_value = 0.0;
    double items_per_s = 0.0;  //!< throughput where it means something, else 0
    double peak_rss_mb = 0.0;  //!< peak resident memory while the measured code ran
};

//! What the plot of a stage shows: y against x, one line per series.
struct PlotSpec {
    std::string x_label = "size";
    std::string y = "time_s";  //!< a Row column: time_s, error_value, items_per_s, peak_rss_mb
    std::string y_label = "time (s)";
    bool log_x = true;
    bool log_y = true;
    bool label_points = false;  //!< each point labelled with its row's parameters
};

struct Measured {
    double seconds = 0.0;      //!< median over the repeats
    double peak_rss_mb = 0.0;  //!< peak RSS during the calls (reset before measuring)
};

class Context {
public:
    Context(std::filesystem::path out_dir, std::filesystem::path data_dir, bool quick,
            std::vector<std::string> view_filter = {});
    bool quick() const { return quick_; }
    //! Whether a stage with views should run the view with this label: every one unless
    //! `kiri bench --view` named texts, then those whose label holds one of them.
    bool wants_view(const std::string& label) const;
    const std::filesystem::path& out_dir() const { return out_dir_; }
    //! The repository's data/ folder (terrains, scenes).
    const std::filesystem::path& data_dir() const { return data_dir_; }
    //! Calls fn repeats times; returns the median time and the peak RSS while it ran.
    Measured measure(const std::function<void()>& fn, int repeats = 1);
    void add(Row row);
    const std::vector<Row>& rows() const { return rows_; }

private:
    std::filesystem::path out_dir_, data_dir_;
    bool quick_;
    std::vector<std::string> view_filter_;
    std::vector<Row> rows_;
};

struct Stage {
    std::string name;   //!< file stem of the CSV and PNG
    std::string title;  //!< plot title
    PlotSpec plot;
    std::function<void(Context&)> run;
};

//! Adds a stage at static-initialisation time; returns true so it can initialise a constant.
bool register_stage(Stage stage);
std::vector<Stage>& stages();

}  // namespace kiri::bench

#define KIRI_BENCH_CONCAT2(a, b) a##b
#define KIRI_BENCH_CONCAT(a, b) KIRI_BENCH_CONCAT2(a, b)
//! KIRI_BENCH_STAGE({"terrain", "Terrain load + mesh + AABB", {...}, [](Context& c) {...}});
//! Named by __COUNTER__, not __LINE__: stages of two files of one unity batch may share a line.
#define KIRI_BENCH_STAGE(...) \
    static const bool KIRI_BENCH_CONCAT(kiri_bench_stage_, __COUNTER__) = ::kiri::bench::register_stage(__VA_ARGS__)
