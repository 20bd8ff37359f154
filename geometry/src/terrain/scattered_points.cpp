// Scattered elevation points -> heightfield through a CGAL 2D Delaunay triangulation.
// CGAL stays in this file (a separate translation unit from the AABB tree: each costs ~30 s).
#include "kiri/geometry/terrain/scattered_points.hpp"

#include <cctype>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <string>

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Projection_traits_xy_3.h>

#include "kiri/geometry/terrain/dem.hpp"
#include "kiri/geometry/core/error.hpp"
#include "terrain/nodata_fill.hpp"

namespace kiri::geometry {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using ProjectionTraits = CGAL::Projection_traits_xy_3<K>;
using Delaunay = CGAL::Delaunay_triangulation_2<ProjectionTraits>;

// Parses one number token fully; false on junk, overflow or a non-finite value.
bool parse_xyz_number(const std::string& token, double& value)
{
    errno = 0;
    char* end = nullptr;
    value = std::strtod(token.c_str(), &end);
    return end == token.c_str() + token.size() && errno != ERANGE && std::isfinite(value);
}

}  // namespace

std::vector<glm::dvec3> read_xyz_points(const std::filesystem::path& path)
{
    const std::string file = path.string();
    std::error_code ec;
    if (!std::filesystem::exists(path, ec))
        throw InputError(file, "file", "no such file");
    std::ifstream in(path);
    if (!in)
        throw IoError(file, "file", "cannot open for reading");
    std::vector<glm::dvec3> points;
    std::string line;
    for (std::size_t number = 1; std::getline(in, line); ++number) {
        if (const auto hash = line.find('#'); hash != std::string::npos)
            line.resize(hash);
        std::replace(line.begin(), line.end(), ',', ' ');  // "x,y,z" as well as "x y z"
        std::vector<std::string> tokens;
        std::size_t pos = 0;
        while (true) {
            pos = line.find_first_not_of(" \t\r", pos);
            if (pos == std::string::npos)
                break;
            const std::size_t end = line.find_first_of(" \t\r", pos);
            tokens.push_back(line.substr(pos, end == std::string::npos ? std::string::npos : end - pos));
            pos = end;
        }
        if (tokens.empty())
            continue;
        const std::string field = "line " + std::to_string(number);
        if (tokens.size() != 3)
            throw InputError(file, field,
                             "expected 3 numbers (x y z), found " + std::to_string(tokens.size()) + " values");
        double v[3];
        for (int k = 0; k < 3; ++k)
            if (!parse_xyz_number(tokens[k], v[k]))
                throw InputError(file, field, "'" + tokens[k] + "' is not a finite number");
        points.emplace_back(v[0], v[1], v[2]);
    }
    if (in.bad())
        throw IoError(file, "file", "read error");
    if (points.empty())
        throw InputError(file, "", "no points (expected rows of x y z)");
    return points;
}

Heightfield heightfield_from_points(const std::vector<glm::dvec3>& points, double cell_size)
{
    if (!(cell_size > 0.0 && std::isfinite(cell_size)))
        throw InputError("", "cell_size", "must be a finite number > 0");
    double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
    for (const auto& p : points) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw InputError("", "points", "a point is not finite");
        xmin = std::min(xmin, p.x), xmax = std::max(xmax, p.x);
        ymin = std::min(ymin, p.y), ymax = std::max(ymax, p.y);
    }
    if (points.size() < 3)
        throw InputError("", "points", "at least 3 points are needed, got " + std::to_string(points.size()));

    // Samples every cell_size from the south-west corner of the bounding box, covering it.
    const double fx = std::ceil((xmax - xmin) / cell_size - 1e-9), fy = std::ceil((ymax - ymin) / cell_size - 1e-9);
    const double max_cells = double(DemOptions{}.max_cells);
    if ((fx + 1.0) * (fy + 1.0) > max_cells)
        throw LimitError("", "cell_size",
                         "a " + std::to_string(cell_size) + " m grid over the points' bounding box would have " +
                             std::to_string((fx + 1.0) * (fy + 1.0)) + " cells, above the limit of " +
                             std::to_string(DemOptions{}.max_cells) + " (DemOptions::max_cells)");

    std::vector<K::Point_3> cgal_points;
    cgal_points.reserve(points.size());
    for (const auto& p : points)
        cgal_points.emplace_back(p.x, p.y, p.z);
    // Duplicates in x-y keep one of their heights (CGAL keeps the vertex first inserted).
    Delaunay dt(cgal_points.begin(), cgal_points.end());
    if (dt.dimension() < 2)
        throw InputError("", "points", "the points are collinear in x-y: they span no surface");

    Heightfield hf;
    hf.nx = std::max(2, int(fx) + 1);
    hf.ny = std::max(2, int(fy) + 1);
    hf.dx = hf.dy = cell_size;
    // Local origin at the centre of the grid, as for DEMs; georef keeps where that is.
    const double cx = xmin + 0.5 * (hf.nx - 1) * cell_size, cy = ymin + 0.5 * (hf.ny - 1) * cell_size;
    hf.x0 = -0.5 * (hf.nx - 1) * cell_size;
    hf.y0 = -0.5 * (hf.ny - 1) * cell_size;
    hf.georef.origin_x = cx;
    hf.georef.origin_y = cy;
    hf.georef.geotransform[0] = xmin - 0.5 * cell_size;
    hf.georef.geotransform[1] = cell_size;
    hf.georef.geotransform[3] = ymin - 0.5 * cell_size;
    hf.georef.geotransform[5] = cell_size;  // rows run south to north
    hf.georef.source_width = hf.nx;
    hf.georef.source_height = hf.ny;
    hf.z.assign(std::size_t(hf.nx) * hf.ny, 0.0);
    hf.valid.assign(hf.z.size(), 0);

    std::size_t valid_count = 0;
    Delaunay::Face_handle hint;
    for (int j = 0; j < hf.ny; ++j)
        for (int i = 0; i < hf.nx; ++i) {
            const double x = xmin + i * cell_size, y = ymin + j * cell_size;
            Delaunay::Locate_type lt;
            int li = 0;
            Delaunay::Face_handle f = dt.locate(K::Point_3(x, y, 0.0), lt, li, hint);
            hint = f;
            double z;
            if (lt == Delaunay::VERTEX) {
                z = f->vertex(li)->point().z();
            } else if (lt == Delaunay::FACE || lt == Delaunay::EDGE) {
                if (dt.is_infinite(f))
                    f = f->neighbor(li);  // a hull edge: its finite side
                // Linear interpolation, barycentric coordinates relative to the first vertex.
                const K::Point_3 &a = f->vertex(0)->point(), &b = f->vertex(1)->point(), &c = f->vertex(2)->point();
                const double bx = b.x() - a.x(), by = b.y() - a.y(), cx2 = c.x() - a.x(), cy2 = c.y() - a.y();
                const double px = x - a.x(), py = y - a.y();
                const double det = bx * cy2 - by * cx2;
                const double u = (px * cy2 - py * cx2) / det, v = (bx * py - by * px) / det;
                z = a.z() + u * (b.z() - a.z()) + v * (c.z() - a.z());
                if (!std::isfinite(z))
                    continue;  // a sliver of the hull, numerically flat: filled below
            } else {
                continue;  // outside the convex hull
            }
            const std::size_t k = std::size_t(j) * hf.nx + i;
            hf.z[k] = z;
            hf.valid[k] = 1;
            ++valid_count;
        }

    if (valid_count == 0) {
        // The hull slips between the samples: each takes the height of its nearest point.
        for (int j = 0; j < hf.ny; ++j)
            for (int i = 0; i < hf.nx; ++i)
                hf.z[std::size_t(j) * hf.nx + i] =
                    dt.nearest_vertex(K::Point_3(xmin + i * cell_size, ymin + j * cell_size, 0.0))->point().z();
    } else if (valid_count < hf.z.size()) {
        fill_voids_smoothly(hf.nx, hf.ny, hf.z, hf.valid);
    }
    return hf;
}

bool is_point_file(const std::filesystem::path& path)
{
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext == ".xyz" || ext == ".csv" || ext == ".txt" || ext == ".ply";
}

double point_cell_size(const std::vector<glm::dvec3>& points)
{
    double x0 = points.front().x, x1 = x0, y0 = points.front().y, y1 = y0;
    for (const glm::dvec3& p : points) {
        x0 = std::min(x0, p.x);
        x1 = std::max(x1, p.x);
        y0 = std::min(y0, p.y);
        y1 = std::max(y1, p.y);
    }
    const double cell = std::sqrt(std::max((x1 - x0) * (y1 - y0), 1e-6) / double(points.size()));
    const double unit = std::pow(10.0, std::floor(std::log10(cell)) - 1.0);
    return std::max(std::round(cell / unit) * unit, unit);
}

}  // namespace kiri::geometry
