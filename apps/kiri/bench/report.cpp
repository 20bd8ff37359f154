#include "bench/report.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include "kiri/geometry/core/error.hpp"

namespace kiri::bench {
namespace {

std::string quoted(const std::string& s)
{
    std::string out = "\"";
    for (char c : s)
        out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

double column(const Row& r, const std::string& name)
{
    if (name == "time_s")
        return r.time_s;
    if (name == "error_value")
        return r.error_value;
    if (name == "items_per_s")
        return r.items_per_s;
    if (name == "peak_rss_mb")
        return r.peak_rss_mb;
    return r.time_s;
}

}  // namespace

void write_csv(const std::filesystem::path& path, const Stage& stage, const std::vector<Row>& rows)
{
    const std::filesystem::path tmp = path.string() + ".tmp";
    {
        std::ofstream out(tmp);
        out << "stage,series,parameters,x,time_s,error_metric,error_value,items_per_s,peak_rss_mb\n";
        out.precision(9);
        for (const Row& r : rows)
            out << stage.name << ',' << quoted(r.series) << ',' << quoted(r.parameters) << ',' << r.x << ',' << r.time_s
                << ',' << quoted(r.error_metric) << ',' << r.error_value << ',' << r.items_per_s << ',' << r.peak_rss_mb
                << '\n';
        if (!out)
            throw IoError(path.string(), "", "cannot write the CSV");
    }
    std::filesystem::rename(tmp, path);
}

bool write_plot(const std::filesystem::path& png, const Stage& stage, const std::vector<Row>& rows)
{
    // One gnuplot data block per series, in the order the series first appear.
    std::vector<std::string> order;
    struct Point {
        double x, y;
        std::string label;
    };
    std::map<std::string, std::vector<Point>> series;
    for (const Row& r : rows) {
        const double y = column(r, stage.plot.y);
        if ((stage.plot.log_x && !(r.x > 0.0)) || (stage.plot.log_y && !(y > 0.0)) || !std::isfinite(y))
            continue;
        if (!series.count(r.series))
            order.push_back(r.series);
        series[r.series].push_back({r.x, y, r.parameters});
    }
    if (order.empty())
        return false;
    std::ostringstream script;
    script.precision(9);
    for (std::size_t k = 0; k < order.size(); ++k) {
        script << "$s" << k << " << EOD\n";
        for (const Point& p : series[order[k]])
            script << p.x << ' ' << p.y << ' ' << quoted(p.label) << '\n';
        script << "EOD\n";
    }
    const std::string tmp = png.string() + ".tmp";
    script << "set terminal pngcairo size 900,600 font 'sans,10'\n"
           << "set output '" << tmp << "'\n"
           << "set title " << quoted(stage.title) << " noenhanced\n"
           << "set xlabel " << quoted(stage.plot.x_label) << " noenhanced\n"
           << "set ylabel " << quoted(stage.plot.y_label) << " noenhanced\n"
           << "set grid\nset key below noenhanced\n";
    if (stage.plot.log_x)
        script << "set logscale x\n";
    if (stage.plot.log_y)
        script << "set logscale y\n";
    script << "plot ";
    for (std::size_t k = 0; k < order.size(); ++k) {
        script << (k ? ", " : "") << "$s" << k << " using 1:2 with linespoints lw 2 pt 7 lc " << k + 1 << " title "
               << quoted(order[k]);
        if (stage.plot.label_points)
            script << ", $s" << k << " using 1:2:3 with labels offset char 0.6,0.6 left font ',8' tc lt " << k + 1
                   << " noenhanced notitle";
    }
    script << "\n";
    const std::filesystem::path script_path = png.string() + ".gp";
    {
        std::ofstream out(script_path);
        out << script.str();
    }
    const std::string command = "gnuplot " + quoted(script_path.string()) + " 2>/dev/null";
    const int status = std::system(command.c_str());
    std::filesystem::remove(script_path);
    if (status != 0 || !std::filesystem::exists(tmp)) {
        std::fprintf(stderr, "kiri bench: gnuplot could not draw %s (is gnuplot installed?)\n", png.c_str());
        std::filesystem::remove(tmp);
        return false;
    }
    std::filesystem::rename(tmp, png);
    return true;
}

}  // namespace kiri::bench
