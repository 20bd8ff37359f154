#include "author_outputs.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "kiri/geometry/core/error.hpp"

namespace kiri::cli {
namespace {

constexpr double mib = 1024.0 * 1024.0;
constexpr AuthorFormat all_formats[] = {AuthorFormat::glb,  AuthorFormat::vdb,     AuthorFormat::particles,
                                        AuthorFormat::maps, AuthorFormat::surface, AuthorFormat::obj,
                                        AuthorFormat::ply};

// Bytes per item of each file, measured on the Jacksboro scenes and rounded up. A tessellation
// vertex has about two triangles.
double file_bytes(AuthorFormat f, const geometry::AuthorEstimate& e, double cells, double particles)
{
    const double v = e.tessellation_vertices, t = 2.0 * v, layers = e.layer_vertices / std::max(v, 1.0);
    switch (f) {
    case AuthorFormat::glb:  // shared base (position, target, normal, uv, triangles), alpha per layer, terrain
        return v * 44.0 + t * 12.0 + layers * v * 8.0 + cells * 36.0;
    case AuthorFormat::vdb: return 8e6 * 4.5;  // at most VdbExportOptions::max_voxels floats
    case AuthorFormat::particles: return particles * 24.0 + 1024.0;
    case AuthorFormat::maps: return cells * 4.0 * 4.0 + cells;  // 4 float GeoTIFFs and a PNG
    case AuthorFormat::surface: return v * 130.0 + t * 55.0;    // OBJ and PLY
    case AuthorFormat::obj: return layers * (v * 40.0 + t * 50.0) + v * 60.0;
    case AuthorFormat::ply: return layers * (v * 36.0 + t * 13.0);
    }
    return 0.0;
}

// The key or flag that makes a format's file smaller.
const char* driver(AuthorFormat f)
{
    switch (f) {
    case AuthorFormat::glb: return "/fog/tessellation/level";
    case AuthorFormat::vdb: return "/medium/grid_spacing";
    case AuthorFormat::particles: return "/particles/count";
    case AuthorFormat::maps: return "/terrain/path";
    case AuthorFormat::surface: return "/fog/tessellation/level";
    case AuthorFormat::obj: return "--formats (leave out obj)";
    case AuthorFormat::ply: return "--formats (leave out ply)";
    }
    return "--formats";
}

}  // namespace

std::set<AuthorFormat> default_author_formats()
{
    return {AuthorFormat::glb, AuthorFormat::vdb, AuthorFormat::particles, AuthorFormat::maps};
}

const char* to_string(AuthorFormat f)
{
    switch (f) {
    case AuthorFormat::glb: return "glb";
    case AuthorFormat::vdb: return "vdb";
    case AuthorFormat::particles: return "particles";
    case AuthorFormat::maps: return "maps";
    case AuthorFormat::surface: return "surface";
    case AuthorFormat::obj: return "obj";
    case AuthorFormat::ply: return "ply";
    }
    return "?";
}

std::set<AuthorFormat> parse_author_formats(const std::string& list)
{
    std::set<AuthorFormat> out;
    std::stringstream in(list);
    std::string name;
    while (std::getline(in, name, ',')) {
        if (name == "all") {
            out.insert(std::begin(all_formats), std::end(all_formats));
            continue;
        }
        bool known = false;
        for (AuthorFormat f : all_formats)
            if (name == to_string(f)) {
                out.insert(f);
                known = true;
            }
        if (!known)
            throw InputError(
                "", "--formats",
                "unknown format \"" + name + "\" (expected glb, vdb, particles, maps, surface, obj, ply or all)");
    }
    if (out.empty())
        throw InputError("", "--formats", "names no format (e.g. glb,vdb)");
    return out;
}

double OutputEstimate::total_mib() const
{
    double sum = 0.0;
    for (const auto& [format, size] : mib)
        sum += size;
    return sum;
}

std::string OutputEstimate::summary() const
{
    std::string parts;
    char text[64];
    for (const auto& [format, size] : mib) {
        std::snprintf(text, sizeof text, "%s%s %.0f", parts.empty() ? "" : ", ", to_string(format), size);
        parts += text;
    }
    std::snprintf(text, sizeof text, "about %.0f MiB (", total_mib());
    return text + parts + ")";
}

OutputEstimate estimate_outputs(const geometry::AuthorEstimate& e, double cells, double particles,
                                const std::set<AuthorFormat>& formats)
{
    OutputEstimate out;
    for (AuthorFormat f : formats)
        out.mib.push_back({f, file_bytes(f, e, cells, particles) / mib});
    return out;
}

void check_output_estimate(const OutputEstimate& e, double limit_mib, const std::string& scene)
{
    if (e.total_mib() <= limit_mib)
        return;
    AuthorFormat largest = e.mib.front().first;
    double size = 0.0;
    for (const auto& [format, mib_of] : e.mib)
        if (mib_of > size) {
            largest = format;
            size = mib_of;
        }
    char limit[96];
    std::snprintf(limit, sizeof limit, "; the limit is %.0f MiB (--max-output)", limit_mib);
    throw LimitError(scene, driver(largest), std::string("the files would weigh ") + e.summary() + limit);
}

}  // namespace kiri::cli
