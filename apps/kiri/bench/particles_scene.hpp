#pragma once
// The cloud of the particle benchmarks: Shimada's Table 1 used cumulus clouds of 9,382 to 60,134
// particles. Here a cumulus is a Medium (the same type every kiri renderer reads): a dome 3 km
// wide and 1.5 km tall over the middle of Jacksboro (base 1800 m), with the layers' density profile, at the
// extinction of a fog of 1 km visibility and the layers' noise at 500 m, lit by the default scene's low
// western sun.
#include <cstddef>
#include <filesystem>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "kiri/geometry/medium/medium.hpp"
#include "kiri/geometry/particles/particles.hpp"
#include "kiri/geometry/scene/scene.hpp"
#include "kiri/render/attenuation.hpp"
#include "kiri/render/gl_context.hpp"

namespace kiri::bench {

//! Shimada's particle counts (Table 1).
constexpr std::size_t shimada_counts[3] = {9382, 32914, 60134};

struct ParticleBenchScene {
    geometry::Scene scene;  //!< the default scene (sun, cameras, terrain path)
    glm::dvec3 sun;         //!< towards the sun, unit
    std::unique_ptr<render::GlContext> context;

    explicit ParticleBenchScene(const std::filesystem::path& data_dir);
    //! The cumulus: a dome of radius 1500 m and height 1500 m based at 1800 m, extinction sigma.
    static geometry::Medium cumulus(double extinction = 0.004);
    //! Exactly `count` particles sampled in a medium (seed 1).
    static geometry::ParticleCloud sample(const geometry::Medium& medium, std::size_t count);
};

//! Relative error |Gamma - exact| / exact over the particles.
struct GammaError {
    double mean = 0.0, max = 0.0;
};
GammaError relative_error(const std::vector<float>& gamma, const std::vector<double>& exact);

//! One resolution's builds: best and median wall time of `repeats` (after a warm-up), the
//! error of the buffer, its memory and where the best build's time went.
struct BufferBuild {
    double best_s = 0.0, median_s = 0.0;
    GammaError error;
    std::size_t bytes = 0;
    render::AttenuationBuildTimes times;
};
BufferBuild time_buffer(render::AttenuationBuffer& buffer, const glm::dvec3& sun,
                        const render::AttenuationOptions& options, int repeats, const std::vector<double>& exact);

}  // namespace kiri::bench
