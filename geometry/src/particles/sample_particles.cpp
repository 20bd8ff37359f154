#include <algorithm>
#include <cmath>
#include <atomic>
#include <cstdint>
#include <functional>
#include <limits>
#include <numbers>
#include <random>
#include <thread>
#include <vector>

#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/medium/fog_lighting.hpp"
#include "kiri/geometry/particles/particle_footprint.hpp"
#include "kiri/geometry/particles/particles.hpp"
#include "particles/for_slices.hpp"
#include "particles/relax_particles.hpp"
#include "particles/sample_elimination.hpp"
#include "particles/shell_envelope.hpp"

namespace kiri::geometry {
namespace {

using detail::uniform;

constexpr double max_particles = 2e6, max_candidates = 2e7;
// Below 1/64 of the full density the local spacing stops growing (4x the spacing at full
// density): the thin rims of the fog get a few large particles, not a handful of huge ones.
constexpr double min_relative_density = 1.0 / 64.0;

// The rejection sampler's trials in chunks of `trials_per_chunk`, chunk c drawn with its own
// generator seeded by (seed, c) and evaluated a batch of chunks at a time on every core; the
// accepted points handed out in chunk order, so they do not depend on the number of threads.
class RejectionChunks {
public:
    using Target = std::function<double(const glm::dvec3&)>;
    RejectionChunks(const detail::ShellEnvelope& envelope, Target target, std::uint64_t seed)
        : envelope_(envelope), target_(std::move(target)), seed_(seed)
    {}
    //! Appends up to `wanted` accepted points (and their q) in order, counting the trials and
    //! hits up to the last one taken (the whole chunk when it runs out).
    void take(std::size_t wanted, std::vector<glm::dvec3>& points, std::vector<double>& q, std::size_t& trials,
              std::size_t& hits)
    {
        if (next_ >= done_.size())
            run_batch();
        const Chunk& c = done_[next_];
        const std::size_t n = std::min(wanted, c.points.size() - used_);
        points.insert(points.end(), c.points.begin() + std::ptrdiff_t(used_),
                      c.points.begin() + std::ptrdiff_t(used_ + n));
        q.insert(q.end(), c.q.begin() + std::ptrdiff_t(used_), c.q.begin() + std::ptrdiff_t(used_ + n));
        hits += n;
        const std::size_t trials_before = trials_taken_;
        used_ += n;
        if (used_ == c.points.size()) {
            trials_taken_ = std::size_t(next_ + 1) * trials_per_chunk;
            ++next_;
            used_ = 0;
        } else {
            trials_taken_ = std::size_t(next_) * trials_per_chunk + c.trial_of[used_ - 1] + 1;
        }
        trials += trials_taken_ - trials_before;
    }

private:
    static constexpr std::size_t trials_per_chunk = 16384;
    struct Chunk {
        std::vector<glm::dvec3> points;
        std::vector<double> q;
        std::vector<std::uint32_t> trial_of;  // each point's trial within the chunk
    };
    void run_batch()
    {
        const int threads = std::max(1, int(std::thread::hardware_concurrency()));
        const std::size_t first = done_.size(), count = std::size_t(2 * threads);
        done_.resize(first + count);
        std::atomic<std::size_t> next{first};
        const auto work = [&] {
            for (std::size_t k = next++; k < first + count; k = next++) {
                // splitmix64 of (seed, chunk): independent streams for neighbouring chunks.
                std::uint64_t z = seed_ + 0x9e3779b97f4a7c15ull * (k + 1);
                z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
                z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
                std::mt19937_64 rng(z ^ (z >> 31));
                Chunk& c = done_[k];
                for (std::uint32_t t = 0; t < trials_per_chunk; ++t) {
                    const detail::ShellEnvelope::Proposal proposal = envelope_.draw(rng);
                    const double value = target_(proposal.position);
                    if (uniform(rng) * proposal.bound < value) {
                        c.points.push_back(proposal.position);
                        c.q.push_back(value);
                        c.trial_of.push_back(t);
                    }
                }
            }
        };
        std::vector<std::thread> pool;
        for (int t = 1; t < threads; ++t)
            pool.emplace_back(work);
        work();
        for (std::thread& t : pool)
            t.join();
    }
    const detail::ShellEnvelope& envelope_;
    Target target_;
    std::uint64_t seed_;
    std::vector<Chunk> done_;
    std::size_t next_ = 0, used_ = 0, trials_taken_ = 0;
};

// The radius of the particles at full density were they drawn from `target` (the share's
// depth is counted in it): radius_min, or radius_scale times the spacing at full density, given
// or from a pilot of 4096 points drawn by the sampler (about 1.5 % in the integral, 0.5 % in the
// radius). 0 when the pilot finds no fog.
double share_radius(const detail::ShellEnvelope& envelope, RejectionChunks::Target target,
                    const ParticleOptions& options)
{
    if (options.radius_min > 0.0)
        return options.radius_min;
    if (options.spacing > 0.0)
        return options.radius_scale * options.spacing;
    RejectionChunks pilot(envelope, std::move(target), options.seed ^ 0x9e3779b97f4a7c15ull);
    std::vector<glm::dvec3> points;
    std::vector<double> q;
    std::size_t trials = 0, hits = 0;
    constexpr std::size_t wanted = 4096, give_up = 8000000;
    while (points.size() < wanted && trials < give_up)
        pilot.take(wanted - points.size(), points, q, trials, hits);
    if (hits == 0 || options.count <= 0)
        return 0.0;
    const double integral = envelope.volume() * double(hits) / double(trials);
    return options.radius_scale * std::cbrt(integral / double(options.count));
}

}  // namespace

void validate_particle_options(const ParticleOptions& o, const std::string& label)
{
    check_fields(o, label, "/particles");
    if (o.radius_min > 0.0 && o.radius_max > 0.0 && o.radius_min > o.radius_max)
        throw InputError(label, "/particles/" + std::string(field_of(o, o.radius_min).key),
                         "the minimum is above the maximum");
}

ParticleCloud sample_particles(const Medium& medium, const ParticleOptions& options, const std::string& label,
                               const HeightShare& share)
{
    validate_particle_options(options, label);
    const double share_max = share.share ? std::clamp(share.max, 0.0, 1.0) : 1.0;
    const double from = share.share ? share.from : 0.0;
    const detail::ShellEnvelope band_envelope(medium, from, share_max);
    const auto no_particles = [&] {
        ParticleCloud empty;  // no fog to sample: no particles, the other renderers draw nothing either
        empty.anisotropy = medium.options().anisotropy;
        empty.scattering_octaves = shader_octaves(medium.options());
        return empty;
    };
    if (band_envelope.empty())
        return no_particles();

    // The density the particles stand for: d(p), or d(p) share(h) above `from`, and with a depth
    // times the share by the fog's thickness there (under an envelope that knows it: where most
    // of the band lies in thin fog, most trials would fall there).
    const auto banded = [&](const glm::dvec3& p) {
        const double d = medium.density(p);
        if (!share.share || !(d > 0.0))
            return d;
        const double h = medium.height_fraction(p);
        return h > from ? d * std::clamp(share.share(h), 0.0, share_max) : 0.0;
    };
    FogPartition depth_rule;
    depth_rule.particle_depth = share.share ? std::max(share.depth, 0.0) : 0.0;
    if (depth_rule.particle_depth > 0.0)
        depth_rule.particle_radius = share_radius(band_envelope, banded, options);
    const bool by_depth = depth_rule.particle_radius > 0.0;
    const auto depth_share = [&](double thickness) { return particle_depth_share(depth_rule, thickness); };
    const detail::ShellEnvelope envelope =
        by_depth ? detail::ShellEnvelope(medium, from, share_max, depth_share) : band_envelope;
    if (envelope.empty())
        return no_particles();
    const auto target = [&](const glm::dvec3& p) {
        const double q = banded(p);
        if (!(q > 0.0) || !by_depth)
            return q;
        const MediumColumn c = medium.column(p.x, p.y);
        return q * depth_share(c.top - c.floor);
    };
    // Rejection: uniform under the envelope, kept with probability q(p) / bound, in chunks of
    // trials that run side by side on every core, each chunk with its own generator (seeded by
    // the seed and its index), taken in order: the same candidates on any number of threads.
    RejectionChunks chunks(envelope, target, options.seed);
    std::vector<glm::dvec3> candidates;
    std::vector<double> density;
    std::size_t trials = 0, hits = 0;
    // A fog too thin for the wanted candidates (a thin top band) stops at `give_up` trials, or
    // earlier once that is plainly out of reach, and keeps what it found: a thin fog gets few
    // particles, or none, not an error.
    const auto draw = [&](std::size_t wanted) {
        const std::size_t give_up = std::max<std::size_t>(wanted, 1000) * 2000;
        while (candidates.size() < wanted) {
            if (trials > give_up ||
                (trials >= 1000000 && double(wanted) * double(trials) > 4.0 * double(give_up) * double(hits + 1)))
                return;
            chunks.take(wanted - candidates.size(), candidates, density, trials, hits);
        }
    };
    // The count: given, or from the spacing at full density and a first estimate of the density
    // integral (a pilot run of the same sampler).
    std::size_t count = std::size_t(options.count);
    if (options.spacing > 0.0) {
        draw(20000);
        const double integral = envelope.volume() * double(hits) / double(trials);
        const double n = std::round(integral / std::pow(options.spacing, 3.0));
        if (n > max_particles)
            throw LimitError(label, "/particles/spacing",
                             "gives " + std::to_string(std::llround(n)) + " particles, above the limit of 2000000");
        count = std::size_t(std::max(n, 1.0));
    }
    const double wanted = std::ceil(double(count) * options.candidates);
    if (wanted > max_candidates)
        throw LimitError(label, "/particles/candidates", "count * candidates is above the limit of 2e7 points");
    draw(std::size_t(wanted));
    ParticleCloud cloud;
    cloud.anisotropy = medium.options().anisotropy;
    cloud.scattering_octaves = shader_octaves(medium.options());
    cloud.forward_scattering = options.forward_scattering;
    cloud.share_radius = depth_rule.particle_radius;
    const MediumGrid& grid = medium.grid();
    cloud.fog_xy_min = {grid.x0, grid.y0};
    cloud.fog_xy_max = {grid.x0 + (grid.nx - 1) * grid.dx, grid.y0 + (grid.ny - 1) * grid.dy};
    cloud.candidate_count = candidates.size();
    cloud.trial_count = trials;
    if (candidates.empty())
        return cloud;  // no particle found any fog: the other renderers draw it
    // Fewer candidates than wanted (a thin fog): fewer particles, in the same proportion.
    if (double(candidates.size()) < wanted)
        count = std::max<std::size_t>(1, std::min(count, std::size_t(double(candidates.size()) / options.candidates)));
    const double integral = envelope.volume() * double(hits) / double(trials);

    // Local spacing where each candidate lies: the distance between particles at that density.
    const double spacing_full = std::cbrt(integral / double(count));
    const auto spacing_at_density = [&](double d) {
        return std::cbrt(integral / (double(count) * std::max(d, min_relative_density)));
    };
    std::vector<double> spacing(candidates.size());
    for (std::size_t i = 0; i < candidates.size(); ++i)
        spacing[i] = spacing_at_density(density[i]);
    const std::vector<std::size_t> kept = detail::eliminate_samples(candidates, spacing, spacing_full, count);

    std::vector<glm::dvec3> placed(kept.size());
    for (std::size_t k = 0; k < kept.size(); ++k)
        placed[k] = candidates[kept[k]];
    // Two points keep 1.6 spacings apart: from the default camera over its blanket (one particle
    // deep) the particles' error 3.99 -> 3.37 %; in trials (the fog's edge found at each sweep)
    // 1.3: 3.63 %, 1.6: 3.28 %, 2.0: 3.72 % with 30 sweeps, 3.45 % with 60 at 1.6.
    constexpr double relax_reach = 1.6;
    detail::relax_points(placed,
                         {[&](const glm::dvec3& p) { return spacing_at_density(target(p)); }, target,
                          [&](double x, double y) { return medium.column(x, y); }},
                         options.relax, relax_reach);

    cloud.density_integral = integral;
    cloud.spacing = spacing_full;
    const double albedo = options.albedo >= 0.0 ? options.albedo : medium.options().albedo;
    const double extinction = options.extinction > 0.0 ? options.extinction : medium.options().extinction;
    const double r_min = options.radius_min > 0.0 ? options.radius_min : options.radius_scale * spacing_full;
    const double r_max = options.radius_max > 0.0 ? options.radius_max : 2.0 * options.radius_scale * spacing_full;
    // Every particle carries the same share of the extinction integral (the candidates were
    // drawn in proportion to the density): tau r^2 footprint_area = extinction * integral / count.
    const double carried = extinction * integral / double(kept.size());
    cloud.extinction = extinction;
    cloud.albedo = albedo;
    cloud.particles.reserve(kept.size());
    for (std::size_t k = 0; k < kept.size(); ++k) {
        const std::size_t i = kept[k];
        Particle p;
        p.position = placed[k];
        p.radius = std::clamp(options.radius_scale * spacing[i], r_min, std::max(r_min, r_max));
        p.optical_depth = carried / (footprint_area() * p.radius * p.radius);
        p.albedo = albedo;
        cloud.particles.push_back(p);
    }
    return cloud;
}

namespace {

// A plane through the Medium's floor (or its top) over a particle's disc: fitted by least squares
// to the floors (tops) of the fog's columns at its centre and two rings of 16 (level with fewer
// than 8 of them). A blanket's bottom slopes within a disc 300 m across: a level plane under its
// lowest point left slivers of the balls under the bottom, which level rays from under the
// blanket crossed by the hundred (the frame bench's valley view, the particles 31.7 % off the
// reference; 3.7 % so). Lowered under every sample, the fitted plane kept most of them (13 %;
// lowered by half, 4.5 %). The plane's height at the centre (+inf over no fog) and its slope.
std::pair<double, glm::dvec2> fitted_plane(const Medium& medium, const Particle& p, double MediumColumn::*surface)
{
    std::vector<glm::dvec3> at;  // offsets from the centre, and the floor (top) there
    at.reserve(33);
    const auto take = [&](double dx, double dy) {
        const MediumColumn c = medium.column(p.position.x + dx, p.position.y + dy);
        if (c.coverage > 0.0)
            at.emplace_back(dx, dy, c.*surface);
    };
    take(0.0, 0.0);
    for (int a = 0; a < 16; ++a) {
        const double phi = 2.0 * std::numbers::pi * a / 16.0;
        for (double x : {0.5, 1.0})
            take(x * p.radius * std::cos(phi), x * p.radius * std::sin(phi));
    }
    if (at.empty())
        return {std::numeric_limits<double>::infinity(), glm::dvec2(0.0)};
    glm::dvec2 slope(0.0);
    double mean = 0.0;
    for (const glm::dvec3& q : at)
        mean += q.z;
    mean /= double(at.size());
    if (at.size() >= 8) {  // z = mean + slope . (d - dm): the normal equations of the slope
        glm::dvec2 dm(0.0);
        for (const glm::dvec3& q : at)
            dm += glm::dvec2(q);
        dm /= double(at.size());
        double sxx = 0.0, sxy = 0.0, syy = 0.0, sxz = 0.0, syz = 0.0;
        for (const glm::dvec3& q : at) {
            const glm::dvec2 d = glm::dvec2(q) - dm;
            sxx += d.x * d.x;
            sxy += d.x * d.y;
            syy += d.y * d.y;
            sxz += d.x * (q.z - mean);
            syz += d.y * (q.z - mean);
        }
        const double det = sxx * syy - sxy * sxy;
        if (det > 1e-9 * (sxx * syy + 1e-30))
            slope = {(sxz * syy - syz * sxy) / det, (syz * sxx - sxz * sxy) / det};
        mean -= glm::dot(slope, dm);  // the plane's height at the centre
    }
    return {mean, slope};
}

}  // namespace

void set_above_ground(ParticleCloud& cloud, const Medium& medium, const std::function<double(double, double)>& ground)
{
    // 96 columns a particle (about 0.1 s for 20,000 on one core): a slice of the particles on
    // every core; each particle's share depends on it alone.
    const auto run = [&](std::size_t first, std::size_t end) {
        for (std::size_t k = first; k < end; ++k) {
            Particle& p = cloud.particles[k];
            // A floor a fifth of the radius or more over the ground is the fog's own (a blanket's
            // bottom): the billboard cuts the ball at its plane, as the terrain cuts it where the
            // fog lies on the ground (there the floor is the ground's grid, a little off the
            // terrain between its samples, and a plane through it would cut the slopes).
            const auto [floor, slope] = fitted_plane(medium, p, &MediumColumn::floor);
            const bool floats = std::isfinite(floor) && floor > ground(p.position.x, p.position.y) + 0.2 * p.radius;
            p.floor = floats ? floor : -std::numeric_limits<double>::infinity();
            p.floor_slope = floats ? slope : glm::dvec2(0.0);
            // The fog's top cuts every ball that stands out of it: a ball near a fog lake's flat
            // top, seen level from its shore, veiled the far shore over the top (the fill's
            // valley view: the particles' p99 error 124 -> 46 %).
            const auto [top, top_slope] = fitted_plane(medium, p, &MediumColumn::top);
            p.top = top;
            p.top_slope = std::isfinite(top) ? top_slope : glm::dvec2(0.0);
            const auto plane_at = [&](double z, const glm::dvec2& dz, double x, double y) {
                return z + glm::dot(dz, glm::dvec2(x, y) - glm::dvec2(p.position));
            };
            const double none = std::numeric_limits<double>::quiet_NaN();
            p.above_ground = footprint_share_between(p.position, p.radius, [&](double x, double y) {
                // What the billboard cuts over the fog's columns: the floor's plane, and the
                // terrain where the fog is as thick as the particle's radius; the top's plane.
                const MediumColumn c = medium.column(x, y);
                if (!(c.coverage > 0.0))
                    return std::pair{none, none};
                const double cut = std::max(c.top - c.floor >= p.radius ? ground(x, y) : -HUGE_VAL,
                                            plane_at(p.floor, p.floor_slope, x, y));
                const double ceiling = plane_at(p.top, p.top_slope, x, y);
                return std::pair{std::isfinite(cut) ? cut : none, std::isfinite(ceiling) ? ceiling : none};
            });
        }
    };
    detail::for_slices(cloud.particles.size(), run);
}

HeightShare particle_height_share(const FogPartition& partition)
{
    // The band by height; the depth by the fog's thickness, in the radius the sampler finds.
    return {[partition](double h) { return particle_share(partition, h, std::numeric_limits<double>::infinity()); },
            1.0 - partition.particle_band, partition.particle_share, partition.particle_depth};
}

}  // namespace kiri::geometry
