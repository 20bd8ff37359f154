#include "kiri/geometry/scene/scene_defaults.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <glm/geometric.hpp>

#include "kiri/geometry/medium/medium.hpp"
#include "kiri/geometry/terrain/scattered_points.hpp"

namespace kiri::geometry {
namespace {

constexpr double pi = 3.14159265358979323846;

// The quantile q of v (v is reordered).
double quantile(std::vector<double>& v, double q)
{
    if (v.empty())
        return 0.0;
    const auto k = static_cast<std::ptrdiff_t>(std::llround(q * double(v.size() - 1)));
    std::nth_element(v.begin(), v.begin() + k, v.end());
    return v[std::size_t(k)];
}

// The smallest of 1, 2, 2.5, 5 x 10^k at least x (x > 0): values a user would have written.
double round_up_nicely(double x)
{
    const double decade = std::pow(10.0, std::floor(std::log10(x)));
    for (double m : {1.0, 2.0, 2.5, 5.0, 10.0})
        if (m * decade >= x * (1.0 - 1e-9))
            return m * decade;
    return 10.0 * decade;
}

// x to two significant digits.
double round_to_two_digits(double x)
{
    if (!(x > 0.0))
        return x;
    const double unit = std::pow(10.0, std::floor(std::log10(x)) - 1.0);
    return std::round(x / unit) * unit;
}

std::string number(double x)
{
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", x);
    return text;
}

std::string vector_text(const glm::dvec3& v)
{
    // Appended, not "[" + ...: GCC 12 warns -Wrestrict on a literal plus a temporary string (a
    // false positive, its bug 105651).
    std::string text = "[";
    for (int k = 0; k < 3; ++k)
        text.append(number(v[k])).append(k < 2 ? ", " : "]");
    return text;
}

// A camera looking along `forward` at `target`, as close as it can be while the box (lo, hi)
// spans the frame's width and leaves the top 10 % for the sky: the terrain fills the frame,
// its near corner may leave it at the bottom.
CameraSpec frame_box(const std::string& name, const glm::dvec3& lo, const glm::dvec3& hi, const glm::dvec3& target,
                     const glm::dvec3& forward, double fov_y_deg, double aspect)
{
    const glm::dvec3 f = glm::normalize(forward);
    const glm::dvec3 r = glm::normalize(glm::cross(f, glm::dvec3(0.0, 0.0, 1.0)));
    const glm::dvec3 u = glm::cross(r, f);
    const double ty = std::tan(0.5 * fov_y_deg * pi / 180.0), tx = aspect * ty;
    // The ground's corners at the target's height span the width; the top of the relief stays
    // below the frame's top tenth.
    const auto fits = [&](double d) {
        const glm::dvec3 eye = target - d * f;
        for (int k = 0; k < 8; ++k) {
            const bool top = (k & 4) != 0;
            const glm::dvec3 c((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, top ? hi.z : target.z);
            const glm::dvec3 v = c - eye;
            const double z = glm::dot(v, f);
            if (z <= 0.0)
                return false;
            if ((!top && std::abs(glm::dot(v, r)) > tx * z) || glm::dot(v, u) > 0.8 * ty * z)
                return false;
        }
        return true;
    };
    const double size = std::max(glm::length(hi - lo), 1.0);
    double near = 0.05 * size, far = 20.0 * size;
    for (int k = 0; k < 60; ++k) {
        const double mid = 0.5 * (near + far);
        (fits(mid) ? far : near) = mid;
    }
    CameraSpec c;
    c.name = name;
    c.target = target;
    c.position = target - far * f;
    c.fov_y_deg = fov_y_deg;
    return c;
}

// From the south-south-west, as the bundled scenes' cameras look: with the sun from the
// west-north-west, slopes facing the camera are half lit and the shadows fall across the view.
const glm::dvec2 view_heading = glm::normalize(glm::dvec2(0.45, 0.9));
const glm::dvec2 sun_heading = glm::normalize(glm::dvec2(-0.75, 0.35));

}  // namespace

std::string DerivedDefaults::summary() const
{
    std::string s;
    for (const DerivedValue& v : values)
        s += (s.empty() ? "" : "; ") + v.key + " " + v.value + " (" + v.reason + ")";
    return s;
}

TerrainFigures terrain_figures(const Heightfield& hf, double exaggeration)
{
    TerrainFigures t;
    const double e = exaggeration > 0.0 ? exaggeration : 1.0;
    t.width = hf.dx * (hf.nx - 1);
    t.depth = hf.dy * (hf.ny - 1);
    t.cell = std::max(hf.dx, hf.dy);
    std::size_t below = 0, above = 0, valid = 0;
    for (std::size_t k = 0; k < hf.z.size(); ++k) {
        if (hf.valid.empty() || hf.valid[k]) {
            ++valid;
            below += hf.z[k] <= 0.0;  // SRTM's sea is exactly 0
            above += hf.z[k] > 0.0;
        }
    }
    t.coast = valid > 0 && below >= 0.02 * double(valid) && above >= 0.02 * double(valid);
    const auto land = [&](std::size_t k) { return (hf.valid.empty() || hf.valid[k]) && (!t.coast || hf.z[k] > 0.0); };
    std::vector<double> heights;
    heights.reserve(hf.z.size());
    double slope = 0.0;
    std::size_t slopes = 0;
    for (int j = 0; j < hf.ny; ++j)
        for (int i = 0; i < hf.nx; ++i) {
            const std::size_t k = std::size_t(j) * hf.nx + i;
            if (!land(k))
                continue;
            heights.push_back(hf.z[k] / e);
            if (i + 1 < hf.nx && j + 1 < hf.ny && land(k + 1) && land(k + hf.nx)) {
                const double gx = (hf.z[k + 1] - hf.z[k]) / hf.dx, gy = (hf.z[k + hf.nx] - hf.z[k]) / hf.dy;
                slope += std::sqrt(gx * gx + gy * gy) / e;
                ++slopes;
            }
        }
    if (heights.empty()) {  // no land (all sea): the valid cells
        for (std::size_t k = 0; k < hf.z.size(); ++k)
            if (hf.valid.empty() || hf.valid[k])
                heights.push_back(hf.z[k] / e);
        t.coast = false;
    }
    t.low = quantile(heights, 0.02);
    t.fill_level = quantile(heights, 0.30);
    t.median = quantile(heights, 0.50);
    t.high = quantile(heights, 0.98);
    t.mean_slope = slopes ? slope / double(slopes) : 0.0;

    // The lowest valley: the lowest mean of blocks of about 1/32 of the extent, away from the
    // edges (a single pit or a border of filled voids is no valley).
    const int bx = std::max(1, hf.nx / 32), by = std::max(1, hf.ny / 32);
    double lowest = std::numeric_limits<double>::infinity();
    t.lowest = {hf.x0 + 0.5 * t.width, hf.y0 + 0.5 * t.depth};
    for (int j0 = hf.ny / 8; j0 + by <= hf.ny - hf.ny / 8; j0 += by)
        for (int i0 = hf.nx / 8; i0 + bx <= hf.nx - hf.nx / 8; i0 += bx) {
            double sum = 0.0;
            int n = 0;
            for (int j = j0; j < j0 + by; ++j)
                for (int i = i0; i < i0 + bx; ++i)
                    if (const std::size_t k = std::size_t(j) * hf.nx + i; land(k)) {
                        sum += hf.z[k];
                        ++n;
                    }
            if (n * 2 >= bx * by && sum / n < lowest) {
                lowest = sum / n;
                t.lowest = {hf.x_of(i0) + 0.5 * (bx - 1) * hf.dx, hf.y_of(j0) + 0.5 * (by - 1) * hf.dy};
            }
        }
    return t;
}

double derive_exaggeration(const Heightfield& hf)
{
    const TerrainFigures t = terrain_figures(hf);
    const double side = std::max(std::min(t.width, t.depth), 1.0);
    const double wanted = 0.04 * side;  // the relief that reads as relief from an oblique view
    if (t.relief() < 1.0)
        return 1.0;  // a plain: nothing to stretch
    for (double e : {1.0, 1.5, 2.0, 3.0, 4.0})
        if (e * t.relief() >= wanted)
            return e;
    return 5.0;
}

Scene derive_scene_defaults(const Scene& scene, const Terrain& terrain, double exaggeration, DerivedDefaults& record)
{
    Scene s = scene;
    record = {};
    if (!scene.given)
        return s;
    const double e = exaggeration;
    s.terrain.exaggeration = e;
    const Heightfield& hf = terrain.heightfield();
    const TerrainFigures t = terrain_figures(hf, e);
    const auto add = [&](std::string key, std::string value, std::string reason) {
        record.values.push_back({std::move(key), std::move(value), std::move(reason)});
    };
    // A key is open to derivation when the file leaves it out and nothing has changed it since
    // (the preview's panels edit the parsed scene).
    const auto open = [&](std::string_view key, bool at_default) { return at_default && !scene.gives(key); };
    if (open("/terrain/exaggeration", scene.terrain.exaggeration == TerrainSpec{}.exaggeration))
        add("/terrain/exaggeration", number(e),
            "relief " + number(round_to_two_digits(t.relief())) + " m over " +
                number(round_to_two_digits(std::min(t.width, t.depth))) + " m");

    if (is_point_file(scene.terrain.path) && open("/terrain/cell_size", scene.terrain.cell_size == 0.0)) {
        s.terrain.cell_size = hf.dx;
        add("/terrain/cell_size", number(hf.dx), "about one point a cell");
    }

    double fog_depth = 0.0;  // the fog's depth in metres of the DEM, for its visibility
    if (s.fog) {
        FogSpec& fog = *s.fog;
        const double area = std::max(t.width * t.depth, 1.0);
        const bool patch_open = open("/fog/patch_size", fog.patch_size == FogSpec{}.patch_size);
        if (patch_open) {
            const double per_cells = round_up_nicely(8.0 * t.cell);
            const double per_budget = round_up_nicely(std::sqrt(area / max_patches));
            fog.patch_size = std::max(per_cells, per_budget);
            add("/fog/patch_size", number(fog.patch_size),
                per_cells >= per_budget ? "8 cells of " + number(round_to_two_digits(t.cell)) + " m"
                                        : "at most " + std::to_string(max_patches) + " patches");
        }
        if (patch_open && open("/fog/tessellation", fog.tessellation == TessellationOptions{})) {
            // The default level unless the patches would make more triangles than the budget (a
            // patch size the scene gives sets the cost itself: fog placed by the terrain covers
            // less than the terrain, which is all these rules know of it).
            const double patches = std::max(1.0, area / (fog.patch_size * fog.patch_size));
            const int by_budget = int(std::max(1.0, std::floor(std::sqrt(max_triangles / (2.0 * patches)))));
            if (by_budget < fog.tessellation.level) {
                fog.tessellation.level = by_budget;
                add("/fog/tessellation/level", std::to_string(by_budget),
                    "at most " + std::to_string(max_triangles) + " triangles");
            }
        }
        if (fog.placement) {
            for (std::size_t k = 0; k < fog.placement->regions.size(); ++k) {
                const std::string key =
                    scene.gives("/fog/fill/" + std::to_string(k)) ? "/fog/fill/" + std::to_string(k) : "/fog/fill";
                FillRegionSpec& region = fog.placement->regions[k];
                if (open(key + "/top", region.top == FillRegionSpec{}.top)) {
                    region.top = std::round(std::max(t.fill_level, t.low + 0.2 * std::max(t.relief(), 8.0)));
                    add(key + "/top", number(region.top),
                        "30 % of the land below it, a fifth of the relief deep at least");
                }
                if (t.coast && open(key + "/max_thickness", region.max_thickness == 0.0) && region.top > 0.0) {
                    // Fog lies on the sea, not on its floor: down to 0 m at most.
                    region.max_thickness = std::max(region.top, region.min_thickness + 1.0);
                    add(key + "/max_thickness", number(region.max_thickness), "the sea's fog lies on its surface");
                }
                fog_depth = std::max(fog_depth, 0.5 * (region.top - t.low));
            }
        } else if (fog.fit.mode == FitMode::blanket) {
            fog_depth = fog.fit.thickness;
            if (open("/fog/offset", fog.fit.offset == FitOptions{}.offset) &&
                open("/fog/thickness", fog.fit.thickness == FitOptions{}.thickness)) {
                fog.fit.thickness =
                    std::max(round_to_two_digits(std::clamp(0.12 * t.relief(), 30.0, 1500.0)), fog.fit.clearance);
                fog.fit.offset = round_to_two_digits(0.3 * fog.fit.thickness);
                fog_depth = fog.fit.thickness;
                const std::string reason = "relief " + number(round_to_two_digits(t.relief())) + " m";
                add("/fog/thickness", number(fog.fit.thickness), reason);
                add("/fog/offset", number(fog.fit.offset), reason);
            }
        }
    }
    const bool medium_given = scene.gives("/medium/extinction") || scene.gives("/medium/visibility") ||
        scene.gives("/medium/liquid_water_content") || scene.gives("/layers/extinction");
    if (s.fog && !medium_given && s.medium.extinction == MediumOptions{}.extinction && fog_depth > 0.0) {
        // The optical depth through the fog's depth (world metres: the volume is stretched too).
        const double depth = fog_depth * e;
        const double tau = s.medium.extinction * depth;
        const double wanted = std::clamp(tau, 2.0, 6.0);
        if (wanted != tau) {
            s.medium.extinction = wanted / depth;
            const double visibility = round_to_two_digits(3.912 / s.medium.extinction);
            s.medium.extinction = extinction_from_visibility(visibility);
            add("/medium/visibility", number(visibility),
                "optical depth " + number(round_to_two_digits(wanted)) + " through " +
                    number(round_to_two_digits(depth)) + " m of fog");
        }
    }
    if (open("/sun/direction", scene.sun.direction == SunSpec{}.direction)) {
        // Shadows where the slopes are: the sun about 2.5 times as steep as the mean slope.
        const double slope = t.mean_slope * e;
        const double elevation = std::clamp(std::atan(2.5 * slope), 12.0 * pi / 180.0, 30.0 * pi / 180.0);
        const double degrees = std::round(elevation * 180.0 / pi);
        const double el = degrees * pi / 180.0;
        s.sun.direction = glm::dvec3(std::cos(el) * sun_heading.x, std::cos(el) * sun_heading.y, std::sin(el));
        add("/sun/direction", vector_text(s.sun.direction),
            number(degrees) + " degrees high over a mean slope of " + number(std::round(std::atan(slope) * 180 / pi)) +
                " degrees");
    }
    if (open("/cameras", scene.cameras.empty())) {
        const Bounds3 b = terrain.bounds();
        const double aspect = double(s.image.width) / double(s.image.height);
        const glm::dvec3 centre(0.5 * (b.min.x + b.max.x), 0.5 * (b.min.y + b.max.y), t.median * e);
        const double down = 30.0 * pi / 180.0;
        const glm::dvec3 forward(std::cos(down) * view_heading.x, std::cos(down) * view_heading.y, -std::sin(down));
        s.cameras = {frame_box("overview", b.min, b.max, centre, forward, 45.0, aspect)};
        // The valley: its lowest block, seen from a fifth of the extent away at a low angle.
        const double reach = 0.2 * std::min(t.width, t.depth);
        const double floor_z = terrain.height(t.lowest.x, t.lowest.y);
        // The fog's top over the valley floor: a fill's top, a blanket's offset (world metres).
        double above = 0.0;
        if (s.fog && s.fog->placement && !s.fog->placement->regions.empty())
            above = s.fog->placement->regions[0].top * e - floor_z;
        else if (s.fog)
            above = s.fog->fit.offset * e;
        const double fog_top = floor_z + std::max(above, 0.0);
        const glm::dvec3 valley(t.lowest.x, t.lowest.y, floor_z);
        CameraSpec low;
        low.name = "valley";
        low.target = valley;
        low.position = valley - reach * glm::dvec3(view_heading, 0.0) +
            glm::dvec3(0.0, 0.0, std::max(fog_top - floor_z, 0.0) + 0.15 * reach + 0.3 * t.relief() * e);
        low.fov_y_deg = 50.0;
        s.cameras.push_back(low);
        // Inside: half way up the fog, looking along the valley.
        CameraSpec inside;
        inside.name = "inside";
        inside.position = glm::dvec3(t.lowest, floor_z + std::max(0.5 * above, 2.0));
        inside.target = inside.position + glm::dvec3(view_heading, 0.0) * reach + glm::dvec3(0.0, 0.0, -0.02 * reach);
        inside.fov_y_deg = 60.0;
        s.cameras.push_back(inside);
        const char* why[] = {"oblique, the terrain filling the frame", "low over the lowest valley",
                             "in the fog of that valley"};
        for (std::size_t k = 0; k < s.cameras.size(); ++k)
            add("/cameras/" + std::to_string(k),
                s.cameras[k].name + " " + vector_text(s.cameras[k].position) + " -> " +
                    vector_text(s.cameras[k].target),
                why[k]);
    }
    return s;
}

}  // namespace kiri::geometry
