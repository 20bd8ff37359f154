#include "kiri/geometry/reference/light_volume_bake.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <mutex>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>

#include "core/parallel_rows.hpp"
#include "reference/light_volume_grids.hpp"
#include "reference/path_tracer_core.hpp"

namespace kiri::geometry {
namespace {

using detail::inf;
constexpr int max_coefficients = light_volume_max_bands * light_volume_max_bands;
// Photons per task: a fixed partition, so that the sums do not depend on the thread count.
constexpr long long photons_per_task = 1024;
// Fixed point of the sums: a deposit of a full-weight photon over the longest step is 2^30 quanta.
constexpr double quanta = 1073741824.0;
constexpr long long max_cells = 1 << 23;
// The share of a sunlight ray's first scatterings drawn uniformly along it (the rest as its march
// of the fog's density says).
constexpr double uniform_share = 0.05;
// The most steps of that march.
constexpr int max_march_steps = 64;

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

// The radical inverse of k in base 2: the second coordinate of a Hammersley set ([Hammersley64]).
double radical_inverse(std::uint64_t k)
{
    k = (k << 32) | (k >> 32);
    k = ((k & 0x0000FFFF0000FFFFull) << 16) | ((k & 0xFFFF0000FFFF0000ull) >> 16);
    k = ((k & 0x00FF00FF00FF00FFull) << 8) | ((k & 0xFF00FF00FF00FF00ull) >> 8);
    k = ((k & 0x0F0F0F0F0F0F0F0Full) << 4) | ((k & 0xF0F0F0F0F0F0F0F0ull) >> 4);
    k = ((k & 0x3333333333333333ull) << 2) | ((k & 0xCCCCCCCCCCCCCCCCull) >> 2);
    k = ((k & 0x5555555555555555ull) << 1) | ((k & 0xAAAAAAAAAAAAAAAAull) >> 1);
    return double(k >> 11) * 0x1.0p-53;
}

// The radical inverse of k in an odd prime base: further coordinates ([Halton60]).
double radical_inverse(std::uint64_t k, int base)
{
    double inverse = 0.0, digit = 1.0 / base;
    for (; k > 0; k /= std::uint64_t(base), digit /= base)
        inverse += double(k % std::uint64_t(base)) * digit;
    return inverse;
}

// x + shift wrapped into [0, 1): one point of a low-discrepancy set, uniform after a random shift.
double shifted(double x, double shift)
{
    const double y = x + shift;
    return y - std::floor(y);
}

// A patch of a face of the box the sun shines on, where a group of photons enter:
// corner + a du + b dv, a and b in [0, 1).
struct EntryPatch {
    glm::dvec3 corner{0.0}, du{0.0}, dv{0.0};
    double projected = 0.0;  // its area seen from the sun
};

// Where the sun's light first scatters: the density of first collisions is pi sigma_t(p) T_sun(p)
// per unit volume (a sun of unit radiance, irradiance pi). Each photon starts at a first scattering
// drawn along a ray of sunlight: the ray enters the box through a patch of a face the sun shines on
// (an (x, y) cell of its top, or a strip of a side face beside the cells of the box's edge), at a
// point of a Hammersley set ([Hammersley64]) shifted at random per patch, and the collision is drawn
// along it in proportion to sigma_t e^(-tau) of a short deterministic march of the fog's density,
// mixed with a little of the uniform (so that no fog the march stepped over is left out). The
// photon carries pi sigma_t T_sun at its point, both exact (T_sun the path tracer's), over the
// density it was drawn from: unbiased, every photon scatters, and the sunlight entering through a
// lit wall is drawn there in proportion to what the wall takes in, where drawing in columns put
// a few photons of large weight into a wall's skin a mean free path deep.
struct FirstScattering {
    glm::dvec3 p{0.0};
    double u_cos = 0.0, u_phi = 0.0;  // the stratified uniforms of the first scattered direction
    double weight = 0.0;              // pi sigma_t T / (the density p was drawn from), per photon of the patch
};

class Baker {
public:
    Baker(const detail::PathTracer& tracer, const Medium& medium, const glm::dvec3& sun, LightVolume& volume,
          const LightVolumeOptions& o)
        : tracer_(tracer), medium_(medium), sun_(sun), v_(volume), o_(o), nc_(volume.bands * volume.bands),
          parts_(!volume.shadow_tops.empty())
    {
        box_ = medium.bounds();
        // The height fog above the Medium's highest top scatters light too: its photons are
        // followed, and its first scatterings drawn, up to its top.
        if (v_.haze_extinction > 0.0) {
            box_.max.z = std::max(box_.max.z, v_.haze_top);
            // And down to the ground where it lies under the Medium's floor.
            for (const double f : v_.floors)
                box_.min.z = std::min(box_.min.z, f);
        }
        step_ = 0.5 * std::min(v_.dx, v_.dy);
        columns_ = (long long)v_.nx * v_.ny;
        make_patches();
    }

    long long columns() const { return columns_; }
    //! Sums a cell: its bands^2 moments and, with the terrain's shadow, its shadowed part's L_00.
    int stride() const { return nc_ + (parts_ ? 1 : 0); }
    long long photons() const { return first_.empty() ? 0 : first_.back(); }
    double quantum() const { return quantum_; }
    // The patches where photons enter: the top of each (x, y) cell, then the strips of the side
    // faces the sun shines on beside the edge's cells; and the share of the sunlight each one's
    // rays scatter, 1 - e^(-tau) along them (a raster of rays, each marched).
    void make_patches()
    {
        patches_.clear();
        const double z0 = box_.min.z, depth = box_.max.z - box_.min.z;
        for (long long cell = 0; cell < columns_; ++cell) {
            EntryPatch e;
            e.corner = {v_.x0 + double(cell % v_.nx) * v_.dx, v_.y0 + double(cell / v_.nx) * v_.dy, box_.max.z};
            e.du = {v_.dx, 0.0, 0.0};
            e.dv = {0.0, v_.dy, 0.0};
            e.projected = v_.dx * v_.dy * sun_.z;
            patches_.push_back(e);
        }
        if (depth > 0.0 && sun_.x != 0.0)
            for (int j = 0; j < v_.ny; ++j) {
                EntryPatch e;
                e.corner = {sun_.x < 0.0 ? box_.min.x : box_.max.x, v_.y0 + j * v_.dy, z0};
                e.du = {0.0, v_.dy, 0.0};
                e.dv = {0.0, 0.0, depth};
                e.projected = v_.dy * depth * std::abs(sun_.x);
                patches_.push_back(e);
            }
        if (depth > 0.0 && sun_.y != 0.0)
            for (int i = 0; i < v_.nx; ++i) {
                EntryPatch e;
                e.corner = {v_.x0 + i * v_.dx, sun_.y < 0.0 ? box_.min.y : box_.max.y, z0};
                e.du = {v_.dx, 0.0, 0.0};
                e.dv = {0.0, 0.0, depth};
                e.projected = v_.dx * depth * std::abs(sun_.y);
                patches_.push_back(e);
            }
        shares_.assign(patches_.size(), 0.0);
        constexpr int raster = 2;
        std::array<double, max_march_steps + 1> tau{};
        for (std::size_t g = 0; g < patches_.size(); ++g) {
            const EntryPatch& e = patches_[g];
            for (int b = 0; b < raster; ++b)
                for (int a = 0; a < raster; ++a) {
                    const glm::dvec3 entry = e.corner + e.du * ((a + 0.5) / raster) + e.dv * ((b + 0.5) / raster);
                    const int steps = march(entry, ray_length(entry), max_march_steps / 2, tau);
                    shares_[g] += -std::expm1(-tau[std::size_t(steps)]) / (raster * raster);
                }
        }
    }

    // Photons per patch: `per_column` for each (x, y) cell's top and as many per area seen from
    // the sun on the sides, or, with `by_share`, that times the share of the sunlight the patch's
    // rays scatter, at least a quarter of it (a sixteenth where its rays met no fog): a thin fog's
    // photons cost as much as a thick one's, and it scatters less light, so it needs fewer for the
    // same noise. The weights divide by each patch's own count, so the allocation changes the
    // noise, not the mean.
    void allocate(long long per_column, bool by_share)
    {
        per_column = std::max<long long>(per_column, 1);
        const double top_area = v_.dx * v_.dy * sun_.z;
        counts_.assign(patches_.size(), 1);
        for (std::size_t g = 0; g < patches_.size(); ++g) {
            const double full = double(per_column) * patches_[g].projected / top_area;
            const double share = by_share ? std::max(shares_[g], shares_[g] > 0.0 ? 0.25 : 0.0625) : 1.0;
            counts_[g] = std::max<long long>(1, std::llround(full * share));
        }
        first_.assign(counts_.size() + 1, 0);
        for (std::size_t g = 0; g < counts_.size(); ++g)
            first_[g + 1] = first_[g] + counts_[g];
        // A deposit of 2^30 quanta over the longest step: a photon of the fullest cell drawn
        // uniformly over the box's height.
        const double sigma = medium_.max_extinction() + (tracer_.has_haze() ? tracer_.haze().extinction : 0.0);
        const double reference =
            std::numbers::pi * sigma * v_.dx * v_.dy * std::max(box_.max.z - box_.min.z, 1e-9) / double(per_column);
        quantum_ = reference * std::max(step_, 1e-9) / quanta;
    }

    // Traces photon `index`, adding its deposits to `sums` (fixed point); returns the deposits.
    long long trace(long long index, std::vector<std::int64_t>& sums) const
    {
        detail::Random rng(o_.seed, std::uint64_t(index));
        const FirstScattering first = first_scattering(index, rng);
        if (!(first.weight > 0.0) || !std::isfinite(first.weight))
            return 0;
        glm::dvec3 o = first.p;
        const double sigma_m = tracer_.medium() ? medium_.extinction(o) : 0.0;
        const double sigma_h = tracer_.has_haze() ? tracer_.haze().sigma(o) : 0.0;
        const bool haze_first = rng.uniform() * (sigma_m + sigma_h) >= sigma_m;
        double weight = first.weight * (haze_first ? tracer_.albedo_haze() : tracer_.albedo_medium());
        if (!(weight > 0.0))
            return 0;
        glm::dvec3 w =
            detail::sample_phase(-sun_, haze_first ? tracer_.g_haze() : tracer_.g_medium(), first.u_cos, first.u_phi);
        const double weight1 = weight;
        const detail::HeightfieldRay* ground = tracer_.terrain();
        long long deposits = 0;
        for (int scatterings = 1;;) {
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
            deposits += deposit(o, w, t_stop, weight, rng, sums);
            if (absorbed || !(t < t_exit) || scatterings >= o_.max_bounces)
                break;
            ++scatterings;
            weight *= in_haze ? tracer_.albedo_haze() : tracer_.albedo_medium();
            o += w * t;
            w = detail::sample_phase(w, in_haze ? tracer_.g_haze() : tracer_.g_medium(), rng);
            if (scatterings >= o_.roulette_after) {
                const double survive = std::min(1.0, weight / weight1);
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
    bool parts_;  // the cells' shadowed parts summed apart (LightVolume::class_means)
    Bounds3 box_;
    long long columns_ = 1;
    std::vector<EntryPatch> patches_;
    std::vector<double> shares_;             // of the sunlight each patch's rays scatter
    std::vector<long long> counts_, first_;  // photons per patch, and the first photon of each
    double step_ = 1.0, quantum_ = 1.0;

    // The length of the sunlight ray entry - t sun in the box, up to the ground.
    double ray_length(const glm::dvec3& entry) const
    {
        const glm::dvec3 d = -sun_;
        double length = box_exit(box_, entry, d);
        if (const detail::HeightfieldRay* ground = tracer_.terrain(); ground && length > 0.0)
            if (const auto hit = ground->first_hit(entry, d, 0.0, length))
                length = *hit;
        return length > 0.0 && std::isfinite(length) ? length : 0.0;
    }

    // The optical depth along that ray at the ends of equal steps (each step's extinction at its
    // middle, one and a half steps a mean free path of the densest fog, at most max_steps) into tau;
    // returns the steps.
    int march(const glm::dvec3& entry, double length, int max_steps, std::array<double, max_march_steps + 1>& tau) const
    {
        const double sigma_max = medium_.max_extinction() + (tracer_.has_haze() ? tracer_.haze().extinction : 0.0);
        const int steps = std::clamp(int(std::ceil(length * sigma_max * 1.5)), 1, max_steps);
        const double dt = length / steps;
        tau[0] = 0.0;
        for (int i = 0; i < steps; ++i)
            tau[std::size_t(i) + 1] = tau[std::size_t(i)] + extinction(entry - sun_ * ((i + 0.5) * dt)) * dt;
        return steps;
    }

    // The fog's extinction at p, both media.
    double extinction(const glm::dvec3& p) const
    {
        return (tracer_.medium() ? medium_.extinction(p) : 0.0) + (tracer_.has_haze() ? tracer_.haze().sigma(p) : 0.0);
    }

    FirstScattering first_scattering(long long index, detail::Random& rng) const
    {
        FirstScattering f;
        const long long group = std::upper_bound(first_.begin(), first_.end(), index) - first_.begin() - 1;
        const long long k = index - first_[std::size_t(group)], n = counts_[std::size_t(group)];
        const EntryPatch& patch = patches_[std::size_t(group)];
        detail::Random shift(o_.seed ^ 0xA5A5A5A5A5A5A5A5ull, std::uint64_t(group));
        const double sx = shift.uniform(), sy = shift.uniform(), sz = shift.uniform(), sc = shift.uniform(),
                     sp = shift.uniform();
        // The distance along the ray and the first scattered direction stratified too (bases 3, 5,
        // 7: [Halton60]).
        const double ut = shifted(radical_inverse(std::uint64_t(k), 3), sz);
        f.u_cos = shifted(radical_inverse(std::uint64_t(k), 5), sc);
        f.u_phi = shifted(radical_inverse(std::uint64_t(k), 7), sp);
        const double a = (double(k) + 0.5) / double(n) + sx, b = radical_inverse(std::uint64_t(k)) + sy;
        const glm::dvec3 entry = patch.corner + patch.du * (a - std::floor(a)) + patch.dv * (b - std::floor(b));
        const glm::dvec3 d = -sun_;
        const double length = ray_length(entry);
        if (!(length > 0.0))
            return f;
        std::array<double, max_march_steps + 1> tau;
        const int steps = march(entry, length, max_march_steps, tau);
        const double dt = length / steps;
        const double total = tau[std::size_t(steps)];
        const double absorbed = -std::expm1(-total);  // 1 - e^(-total)
        const double share = absorbed > 1e-12 ? uniform_share : 1.0;
        double t = 0.0;
        if (ut < share)
            t = ut / share * length;
        else {
            const double target = -std::log1p(-(ut - share) / (1.0 - share) * absorbed);
            const int i = int(std::upper_bound(tau.begin(), tau.begin() + steps + 1, target) - tau.begin()) - 1;
            const int s = std::clamp(i, 0, steps - 1);
            const double rate = (tau[std::size_t(s) + 1] - tau[std::size_t(s)]) / dt;
            t = std::clamp(s * dt + (rate > 0.0 ? (target - tau[std::size_t(s)]) / rate : 0.0), 0.0, length);
        }
        // The mixture's density at t along the ray, then per unit volume (the entry uniform over
        // the patch, each ray carrying its area seen from the sun).
        double along = share / length;
        if (share < 1.0) {
            const int s = std::clamp(int(t / dt), 0, steps - 1);
            const double rate = (tau[std::size_t(s) + 1] - tau[std::size_t(s)]) / dt;
            const double tau_t = tau[std::size_t(s)] + rate * (t - s * dt);
            along += (1.0 - share) * rate * std::exp(-tau_t) / absorbed;
        }
        const double density = along / patch.projected;
        f.p = entry + d * t;
        const double sigma = extinction(f.p);
        if (!(sigma > 0.0) || !(density > 0.0))
            return f;
        const double transmittance = tracer_.sun_transmittance(f.p, rng);
        f.weight = std::numbers::pi * sigma * transmittance / (density * double(n));
        return f;
    }

    // cell[q] += scale y[q] rounded to the nearest integer. Adding 1.5 x 2^52 rounds a double of
    // magnitude under 2^51 to an integer in its low mantissa bits, which then subtract as int64:
    // plain arithmetic the compiler vectorises, where a conversion per coefficient did not
    // (a deposit is 2^30 quanta at most for a full-weight photon; larger ones take the slow path).
    void add_rounded(std::int64_t* cell, double scale, const double* y) const { add_rounded(cell, scale, y, nc_); }
    void add_rounded(std::int64_t* cell, double scale, const double* y, int nc) const
    {
        constexpr double magic = 0x1.8p52;
        constexpr double largest = 0x1.0p50;
        if (!(std::abs(scale) < largest)) {
            for (int q = 0; q < nc; ++q)
                cell[q] += std::llround(std::clamp(scale * y[q], -0x1.0p62, 0x1.0p62));
            return;
        }
        std::array<double, max_coefficients> shifted_values;
        for (int q = 0; q < nc; ++q)
            shifted_values[std::size_t(q)] = scale * y[q] + magic;
        std::array<std::int64_t, max_coefficients> bits;
        std::memcpy(bits.data(), shifted_values.data(), sizeof(double) * std::size_t(nc));
        const std::int64_t magic_bits = std::bit_cast<std::int64_t>(magic);
        for (int q = 0; q < nc; ++q)
            cell[q] += bits[std::size_t(q)] - magic_bits;
    }

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
        // The step's level height from the last point's column (the shell's thickness changes
        // little over a step): one column lookup per point.
        MediumColumn c = v_.shell(medium_.column(o.x, o.y), o.x, o.y);
        for (double t = 0.0; t < length;) {
            const double level = (c.top - c.floor) / v_.nz;
            double dt = std::min(max_step, 2.0 * step_);
            if (level > 0.0 && w.z != 0.0)
                dt = std::min(dt, 0.5 * level / std::abs(w.z));
            dt = std::max(dt, 1e-3 * step_);
            const double seg = std::min(dt, length - t);
            const glm::dvec3 p = o + w * (t + rng.uniform() * seg);
            t += seg;
            c = v_.shell(medium_.column(p.x, p.y), p.x, p.y);
            const double h = shell_height(c, p.z);
            if (h < 0.0)
                continue;
            const int i = int(std::floor((p.x - v_.x0) / v_.dx)), j = int(std::floor((p.y - v_.y0) / v_.dy));
            if (i < 0 || j < 0 || i >= v_.nx || j >= v_.ny)
                continue;
            const int k = std::min(int(h * v_.nz), v_.nz - 1);
            std::int64_t* cell = &sums[((std::size_t(k) * v_.ny + j) * v_.nx + i) * std::size_t(stride())];
            add_rounded(cell, weight * seg / quantum_, y.data());
            if (parts_ && p.z < v_.shadow_top_at(p.x, p.y))
                add_rounded(cell + nc_, weight * seg / quantum_, y.data(), 1);
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
    if (fog.height_fog.enabled()) {  // its extent covers the terrain, under which the Medium lies
        v.haze_extinction = fog.height_fog.extinction;
        v.haze_base = fog.height_fog.base;
        v.haze_scale_height = fog.height_fog.scale_height;
        v.haze_top = fog.height_fog.top();
        if (terrain)
            detail::lower_floors_to_the_ground(v, *medium, *terrain);
    }
    if (terrain)
        detail::mark_the_terrains_shadow(v, *terrain, sun, options.threads);
    const int nc = v.bands * v.bands;
    const std::size_t cells = std::size_t(v.nx) * v.ny * v.nz;

    FogLighting light;
    light.sun_direction = sun;
    PathTracerOptions po;
    po.surround = options.surround;
    const detail::PathTracer tracer(fog, terrain, light, po);
    Baker baker(tracer, *medium, sun, v, options);
    // Whole columns of photons: every (x, y) cell draws its first scatterings itself.
    if (options.photons > 0)
        baker.allocate((options.photons + baker.columns() - 1) / baker.columns(), false);
    else {
        const long long per_column = std::max(options.photons_per_column, 1);
        baker.allocate(per_column, true);
        const long long first = baker.photons();
        // Each count is rounded, so the factor that reaches the floor may fall a few short of it.
        for (long long k = first > 0 ? (options.min_photons + first - 1) / first : 1;
             first > 0 && baker.photons() < options.min_photons; ++k)
            baker.allocate(per_column * k, true);
    }
    const long long photons = baker.photons();

    const long long tasks = (photons + photons_per_task - 1) / photons_per_task;
    const std::size_t stride = std::size_t(baker.stride());
    std::vector<std::int64_t> total(cells * stride, 0);
    std::mutex merge;
    std::atomic<long long> deposits{0};
    detail::for_rows_in_parallel(options.threads, int(std::min<long long>(tasks, 1 << 30)), [&](auto next_task) {
        std::vector<std::int64_t> sums(cells * stride, 0);
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

    // Each cell's volume: its footprint's shell thickness / levels, integrated on a raster; with
    // the column normalisation, the volume-weighted mean of column_scale over it too; and the
    // volume of each level's part under the terrain's shadow's top.
    if (options.column_normalised)
        v.column_extinction = medium->options().extinction * 0.5 * (1.0 + medium->options().top_density);
    const bool parts = stride > std::size_t(nc);
    constexpr int raster = 8;
    std::vector<double> column_volume(std::size_t(v.nx) * v.ny, 0.0), column_mean(column_volume.size(), 1.0);
    std::vector<double> shadowed(parts ? cells : 0, 0.0);  // each cell's share in the shadow
    for (int j = 0; j < v.ny; ++j)
        for (int i = 0; i < v.nx; ++i) {
            double sum = 0.0, scaled = 0.0;
            for (int b = 0; b < raster; ++b)
                for (int a = 0; a < raster; ++a) {
                    const double x = v.x0 + (i + (a + 0.5) / raster) * v.dx, y = v.y0 + (j + (b + 0.5) / raster) * v.dy;
                    const MediumColumn c = medium->column(x, y);
                    const MediumColumn cells = v.shell(c, x, y);
                    const double thick = std::max(cells.top - cells.floor, 0.0);
                    sum += thick;
                    scaled += thick * v.column_scale(c);
                    if (parts && thick > 0.0) {
                        const double level = thick / v.nz, top = v.shadow_top_at(x, y);
                        for (int k = 0; k < v.nz; ++k)
                            shadowed[(std::size_t(k) * v.ny + j) * v.nx + i] +=
                                std::clamp(top - (cells.floor + k * level), 0.0, level);
                    }
                }
            column_volume[std::size_t(j) * v.nx + i] = sum / (raster * raster) * v.dx * v.dy / v.nz;
            if (sum > 0.0) {
                column_mean[std::size_t(j) * v.nx + i] = std::max(scaled / sum, 1e-6);
                if (parts)
                    for (int k = 0; k < v.nz; ++k)
                        shadowed[(std::size_t(k) * v.ny + j) * v.nx + i] /= sum / v.nz;
            }
        }
    const double quantum = baker.quantum();
    v.moments.assign(cells * nc, 0.0);
    std::vector<std::uint8_t> known(parts ? cells * 2 : 0, 0);
    if (parts)
        v.class_means.assign(cells * 2, 0.0);
    for (std::size_t k = 0; k < cells; ++k) {
        const std::size_t column = k % (std::size_t(v.nx) * v.ny);
        const double volume = column_volume[column] * column_mean[column];
        if (!(volume > 0.0))
            continue;
        for (int q = 0; q < nc; ++q)
            v.moments[k * nc + q] = double(total[k * stride + q]) * quantum / volume;
        if (!parts)
            continue;
        // L_00 of each part over its own volume, in the moments' units.
        const double share = std::clamp(shadowed[k], 0.0, 1.0);
        const double in_shadow = double(total[k * stride + std::size_t(nc)]) * quantum;
        const double in_sun = double(total[k * stride]) * quantum - in_shadow;
        if (1.0 - share >= detail::least_sunlit_part) {
            v.class_means[k * 2] = std::max(in_sun, 0.0) / (volume * (1.0 - share));
            known[k * 2] = 1;
        }
        if (share >= detail::least_shadowed_part) {
            v.class_means[k * 2 + 1] = std::max(in_shadow, 0.0) / (volume * share);
            known[k * 2 + 1] = 1;
        }
    }
    if (parts)
        detail::fill_unknown_parts(v, known);
    v.photons = photons;
    v.deposits = deposits;
    v.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return v;
}

}  // namespace kiri::geometry
