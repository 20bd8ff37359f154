#include <bit>
#include <cmath>
#include <limits>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/particles/particles.hpp"

namespace kiri::geometry {
namespace {

template <typename T>
void put(std::ofstream& out, T value)
{
    static_assert(std::endian::native == std::endian::little, "the PLY writer assumes a little-endian host");
    out.write(reinterpret_cast<const char*>(&value), sizeof value);
}

}  // namespace

void write_particles_ply(const std::string& path, const ParticleCloud& cloud)
{
    const std::string tmp = path + ".tmp";
    {
        std::ofstream out(tmp, std::ios::binary);
        if (!out)
            throw IoError(path, "", "cannot be created");
        std::ostringstream header;
        header.precision(17);
        header << "ply\nformat binary_little_endian 1.0\n"
               << "comment kiri particles: Gaussian footprints (docs/particles.md)\n"
               << "comment forward_scattering " << cloud.forward_scattering << "\n"
               << "comment anisotropy " << cloud.anisotropy << "\n"
               << "element vertex " << cloud.particles.size() << "\n"
               << "property float x\nproperty float y\nproperty float z\n"
               << "comment above_ground: the share of the ball's mass above the ground (or the floor) and "
                  "under the top (the rest is in the ground or outside the fog: a renderer that hides the "
                  "ground and cuts the ball at both planes draws optical_depth / above_ground within)\n"
               << "comment floor: where a blanket of fog floats over the ground under the particle, the "
                  "height at the centre of its floor's plane, fitted over the particle's disc, or the "
                  "lowest float where none; floor_dzdx, floor_dzdy: that plane's slope\n"
               << "comment top: the height at the centre of the plane of the fog's top, fitted over the "
                  "particle's disc, or the largest float where none; top_dzdx, top_dzdy: its slope\n"
               << "property float radius\nproperty float optical_depth\nproperty float albedo\n"
               << "property float above_ground\nproperty float floor\nproperty float floor_dzdx\n"
               << "property float floor_dzdy\nproperty float top\nproperty float top_dzdx\n"
               << "property float top_dzdy\n"
               << "end_header\n";
        out << header.str();
        for (const Particle& p : cloud.particles) {
            put(out, float(p.position.x));
            put(out, float(p.position.y));
            put(out, float(p.position.z));
            put(out, float(p.radius));
            put(out, float(p.optical_depth));
            put(out, float(p.albedo));
            put(out, float(p.above_ground));
            put(out, std::isfinite(p.floor) ? float(p.floor) : std::numeric_limits<float>::lowest());
            put(out, float(p.floor_slope.x));
            put(out, float(p.floor_slope.y));
            put(out, std::isfinite(p.top) ? float(p.top) : std::numeric_limits<float>::max());
            put(out, float(p.top_slope.x));
            put(out, float(p.top_slope.y));
        }
        out.close();
        if (!out) {
            std::remove(tmp.c_str());
            throw IoError(path, "", "cannot write");
        }
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::remove(tmp.c_str());
        throw IoError(path, "", "cannot move into place: " + ec.message());
    }
}

}  // namespace kiri::geometry
