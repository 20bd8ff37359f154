#include "kiri/geometry/reference/light_volume_bake.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>

#include "reference/parallel_rows.hpp"
#include "reference/path_tracer_core.hpp"

namespace kiri::geometry {
namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr int max_coefficients = light_volume_max_bands * light_volume_max_bands;
// Photons per task: a fixed partition, so that the sums do not depend on the thread count.
constexpr long long photons_per_task = 1024;
// Fixed point of the sums: a deposit of a full-weight photon over the longest step is 2^30 quanta.
constexpr double quanta = 1073741824.0;
constexpr long long max_cells = 1 << 23;

// The exit distance of o + t w (w unit) from the box, or -1 when the ray misses it.
double box_exit(const Bounds3& b, const glm::dvec3& o, const glm::dvec3& w)
{
    double t0 = 0.0, t1 = inf;
    if (!detail::clip_slab(o.x, w.x, b.min.x, b.max.x, t0, t1) ||
        !detail::clip_slab(o.y, w.y, b.min.y, b.max.y, t0, t1) ||
        !detail::clip_slab(o.z, w.z, b.min.z, b.max.z, t0, t1))
        return -1.0;
    return t1;
}

// A face of the box the sun shines on: corner + u a + v b, u, v in [0, 1], its projected area.
struct Face {
    glm::dvec3 corner, a, b;
    double projected = 0.0;
};

class Baker {
public:
    Baker(const detail::PathTracer& tracer, const Medium& medium, const glm::dvec3& sun, LightVolume& volume,
          const LightVolumeOptions& o)
        : tracer_(tracer), medium_(medium), sun_(sun), v_(volume), o_(o), nc_(volume.bands * volume.bands)
    {
        const Bounds3& b = medium.bounds();
        box_ = b;
        const glm::dvec3 e = b.max - b.min;
        // The faces towards the sun: x, y and the top (the sun is above the horizon).
        if (sun.x != 0.0)
            faces_.push_back({{sun.x > 0.0 ? b.max.x : b.min.x, b.min.y, b.min.z},
                              {0.0, e.y, 0.0},
                              {0.0, 0.0, e.z},
                              e.y * e.z * std::abs(sun.x)});
        if (sun.y != 0.0)
            faces_.push_back({{b.min.x, sun.y > 0.0 ? b.max.y : b.min.y, b.min.z},
                              {e.x, 0.0, 0.0},
                              {0.0, 0.0, e.z},
                              e.x * e.z * std::abs(sun.y)});
        faces_.push_back({{b.min.x, b.min.y, b.max.z}, {e.x, 0.0, 0.0}, {0.0, e.y, 0.0}, e.x * e.y * sun.z});
        for (const Face& f : faces_)
            projected_ += f.projected;
        step_ = 0.5 * std::min(v_.dx, v_.dy);
    }

    double projected_area() const { return projected_; }
    double quantum() const { return quantum_; }
    void set_photon_weight(double w)
    {
        weight0_ = w;
        quantum_ = w * std::max(step_, 1e-9) / quanta;
    }

    // Traces photon `index`, adding its deposits to `sums` (fixed point); returns the deposits.
    long long trace(long long index, std::vector<std::int64_t>& sums) const
    {
        detail::Random rng(o_.seed, std::uint64_t(index));
        // The entry point, on a face picked by its projected area.
        double pick = rng.uniform() * projected_;
        const Face* face = &faces_.back();
        for (const Face& f : faces_) {
            if (pick < f.projected) {
                face = &f;
                break;
            }
            pick -= f.projected;
        }
        const double u = rng.uniform(), v = rng.uniform();
        glm::dvec3 o = face->corner + face->a * u + face->b * v;
        const detail::HeightfieldRay* ground = tracer_.terrain();
        if (ground && ground->first_hit(o, sun_, 1e-6, inf))
            return 0;  // the terrain hides this point from the sun
        glm::dvec3 w = -sun_;
        double weight = weight0_;
        long long deposits = 0;
        for (int scatterings = 0;;) {
            const double t_exit = box_exit(box_, o, w);
            if (!(t_exit > 0.0))
                break;
            double t = tracer_.medium() ? tracer_.medium_collision(o, w, t_exit, rng) : inf;
            bool in_haze = false;
            if (tracer_.has_haze()) {
                const double th = tracer_.haze_collision(o, w, std::min(t, t_exit), rng);
                if (th < t) {
                    t = th;
                    in_haze = true;
                }
            }
            double t_stop = std::min(t, t_exit);
            bool absorbed = false;
            if (ground)
                if (const auto hit = ground->first_hit(o, w, 0.0, t_stop)) {
                    t_stop = *hit;
                    absorbed = true;
                }
            if (scatterings > 0)
                deposits += deposit(o, w, t_stop, weight, rng, sums);
            if (absorbed || !(t < t_exit) || scatterings >= o_.max_bounces)
                break;
            ++scatterings;
            weight *= in_haze ? tracer_.albedo_haze() : tracer_.albedo_medium();
            o += w * t;
            w = detail::sample_phase(w, in_haze ? tracer_.g_haze() : tracer_.g_medium(), rng);
            if (scatterings >= o_.roulette_after) {
                const double survive = std::min(1.0, weight / weight0_);
                if (!(survive > 0.0) || rng.uniform() >= survive)
                    break;
                weight /= survive;
            }
        }
        return deposits;
    }

private:
    const detail::PathTracer& tracer_;
    const Medium& medium_;
    glm::dvec3 sun_;
    LightVolume& v_;
    const LightVolumeOptions& o_;
    int nc_;
    Bounds3 box_;
    std::vector<Face> faces_;
    double projected_ = 0.0, step_ = 1.0, weight0_ = 1.0, quantum_ = 1.0;

    // The track-length estimator of the segment o + t w, t in [0, length]: points a jittered
    // step apart, each adding weight x step x Y_lm(w) to its cell's sum (divided by the cell's
    // volume at the end). Steps resolve the cells: half a cell across, half a level up.
    long long deposit(const glm::dvec3& o, const glm::dvec3& w, double length, double weight, detail::Random& rng,
                      std::vector<std::int64_t>& sums) const
    {
        if (!(length > 0.0))
            return 0;
        std::array<double, max_coefficients> y{};
        real_spherical_harmonics(w, v_.bands, y.data());
        const double across = std::hypot(w.x, w.y);
        const double max_step = across > 0.0 ? step_ / across : inf;
        long long count = 0;
        for (double t = 0.0; t < length;) {
            const glm::dvec3 here = o + w * t;
            const MediumColumn c = medium_.column(here.x, here.y);
            const double level = (c.top - c.floor) / v_.nz;
            double dt = std::min(max_step, 2.0 * step_);
            if (level > 0.0 && w.z != 0.0)
                dt = std::min(dt, 0.5 * level / std::abs(w.z));
            dt = std::max(dt, 1e-3 * step_);
            const double seg = std::min(dt, length - t);
            const glm::dvec3 p = o + w * (t + rng.uniform() * seg);
            t += seg;
            const double h = shell_height(medium_.column(p.x, p.y), p.z);
            if (h < 0.0)
                continue;
            const int i = int(std::floor((p.x - v_.x0) / v_.dx)), j = int(std::floor((p.y - v_.y0) / v_.dy));
            if (i < 0 || j < 0 || i >= v_.nx || j >= v_.ny)
                continue;
            const int k = std::min(int(h * v_.nz), v_.nz - 1);
            std::int64_t* cell = &sums[((std::size_t(k) * v_.ny + j) * v_.nx + i) * nc_];
            const double scale = weight * seg / quantum_;
            for (int q = 0; q < nc_; ++q) {  // rounded half away from zero, as llround, without its call
                const double x = scale * y[q];
                cell[q] += std::int64_t(x >= 0.0 ? x + 0.5 : x - 0.5);
            }
            ++count;
        }
        return count;
    }
};

}  // namespace

LightVolume bake_light_volume(const FogVolume& fog, const Heightfield* terrain, const glm::dvec3& sun_direction,
                              const LightVolumeOptions& options)
{
    const auto start = std::chrono::steady_clock::now();
    LightVolume v;
    const Medium* medium = fog.medium;
    const double len = glm::length(sun_direction);
    if (!medium || !(medium->max_extinction() > 0.0) || !std::isfinite(medium->max_extinction()) || !(len > 0.0) ||
        !std::isfinite(len))
        return v;
    const glm::dvec3 sun = sun_direction / len;
    if (!(sun.z > 0.0))
        return v;
    const MediumGrid& g = medium->grid();
    const double width = (g.nx - 1) * g.dx, height = (g.ny - 1) * g.dy;
    if (!(width > 0.0) || !(height > 0.0))
        return v;
    double cell = options.cell_size > 0.0 && std::isfinite(options.cell_size)
        ? options.cell_size
        : std::max({g.dx, g.dy, 1.0 / medium->options().extinction});
    v.nz = std::clamp(options.levels, 1, 64);
    v.bands = std::clamp(options.bands, 1, light_volume_max_bands);
    // At most max_cells sums per thread (64 MiB of fixed point): the side shrinks to fit.
    const double columns = double(max_cells) / (double(v.nz) * v.bands * v.bands);
    const int side = std::clamp(std::min(options.max_side, int(std::sqrt(columns))), 1, 1024);
    cell = std::max({cell, width / side, height / side});
    v.nx = std::clamp(int(std::ceil(width / cell - 1e-9)), 1, side);
    v.ny = std::clamp(int(std::ceil(height / cell - 1e-9)), 1, side);
    v.x0 = g.x0;
    v.y0 = g.y0;
    v.dx = width / v.nx;
    v.dy = height / v.ny;
    const int nc = v.bands * v.bands;
    const std::size_t cells = std::size_t(v.nx) * v.ny * v.nz;

    FogLighting light;
    light.sun_direction = sun;
    PathTracerOptions po;
    po.surround = options.surround;
    const detail::PathTracer tracer(fog, terrain, light, po);
    Baker baker(tracer, *medium, sun, v, options);
    const long long photons = options.photons > 0
        ? options.photons
        : std::max<long long>(1, (long long)std::max(options.photons_per_column, 1) * v.nx * v.ny);
    // Each photon carries 1 / photons of the power pi x (projected area) that enters the box.
    const double weight = std::numbers::pi * baker.projected_area() / double(photons);
    baker.set_photon_weight(weight);

    const long long tasks = (photons + photons_per_task - 1) / photons_per_task;
    std::vector<std::int64_t> total(cells * nc, 0);
    std::mutex merge;
    std::atomic<long long> deposits{0};
    detail::for_rows_in_parallel(options.threads, int(std::min<long long>(tasks, 1 << 30)), [&](auto next_task) {
        std::vector<std::int64_t> sums(cells * nc, 0);
        long long mine = 0;
        for (long long t = next_task(); t < tasks; t = next_task()) {
            const long long end = std::min(photons, (t + 1) * photons_per_task);
            for (long long p = t * photons_per_task; p < end; ++p)
                mine += baker.trace(p, sums);
        }
        // Integer sums: the same in any order.
        const std::lock_guard lock(merge);
        for (std::size_t k = 0; k < total.size(); ++k)
            total[k] += sums[k];
        deposits += mine;
    });

    // Each cell's volume: its footprint's shell thickness / levels, integrated on a 4 x 4 raster.
    constexpr int raster = 4;
    std::vector<double> column_volume(std::size_t(v.nx) * v.ny, 0.0);
    for (int j = 0; j < v.ny; ++j)
        for (int i = 0; i < v.nx; ++i) {
            double sum = 0.0;
            for (int b = 0; b < raster; ++b)
                for (int a = 0; a < raster; ++a) {
                    const MediumColumn c =
                        medium->column(v.x0 + (i + (a + 0.5) / raster) * v.dx, v.y0 + (j + (b + 0.5) / raster) * v.dy);
                    sum += std::max(c.top - c.floor, 0.0);
                }
            column_volume[std::size_t(j) * v.nx + i] = sum / (raster * raster) * v.dx * v.dy / v.nz;
        }
    const double quantum = baker.quantum();
    v.moments.assign(cells * nc, 0.0);
    for (std::size_t k = 0; k < cells; ++k) {
        const double volume = column_volume[k % (std::size_t(v.nx) * v.ny)];
        if (!(volume > 0.0))
            continue;
        for (int q = 0; q < nc; ++q)
            v.moments[k * nc + q] = double(total[k * nc + q]) * quantum / volume;
    }
    v.photons = photons;
    v.deposits = deposits;
    v.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return v;
}

}  // namespace kiri::geometry
