#pragma once
// What every pass of one frame reads: camera matrices and lighting, computed once per frame.
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "kiri/render/camera.hpp"
#include "kiri/render/renderer.hpp"
#include "kiri/render/tone_map.hpp"

namespace kiri::render::detail {

struct FrameContext {
    int width = 0, height = 0;
    glm::dmat4 view{1.0}, projection{1.0};
    glm::mat4 view_projection{1.0f};
    glm::mat4 inverse_view_projection{1.0f};
    //! The ray through NDC point (x, y) with unit view depth: ray_forward + x ray_right + y ray_up
    //! (the view's axes and the projection's focal lengths, whatever its near and far planes).
    glm::dvec3 ray_forward{0.0, 0.0, -1.0}, ray_right{1.0, 0.0, 0.0}, ray_up{0.0, 1.0, 0.0};
    glm::vec3 eye{0.0f};
    glm::vec3 sun_direction{0.0f, 0.0f, 1.0f};  // towards the sun, unit
    glm::vec3 sun_radiance{1.0f};
    glm::vec3 ambient{0.3f};
    glm::vec3 sky_zenith{0.3f}, sky_horizon{0.8f};
    bool sun_glow = true;                      // the sky draws the sun's glow (SunLight::sky)
    float ground_albedo = 1.0f;                // 0: a black ground (SunLight::black_ground)
    float exposure = float(display_exposure);  // tone_map.hpp
    float haze_density = 0.0f;                 // 1/m: the air's extinction (geometry::scene_air), towards sky_horizon
    //! A still picture (Renderer::render), not a frame of a moving view (Renderer::draw): the
    //! layers drawn at the frame's resolution take each sample's own ray (LayersPass).
    bool still = false;
    //! Combined mode: each fog renderer draws its share of the Medium (fog_partition.hpp).
    bool partitioned = false;
    glm::vec4 partition{0.0f};  //!< near_start, near_end, particle_share, particle_band
    //! The fog's thickness (metres) where the particles' share starts and where it is whole
    //! (geometry::particle_depth_share); (0, 0): every thickness.
    glm::vec2 partition_depth{0.0f};
};

//! The near and far planes of the frame's projection (x, y): what a depth-buffer value is turned
//! into a view depth with, 2 n f / (f + n - z (f - n)) for z = 2 depth - 1.
glm::vec2 depth_planes(const FrameContext& frame);

//! False when the box [lo, hi] lies wholly outside one plane of the frame's view frustum
//! (conservative: a box near a corner may pass).
bool box_in_view(const FrameContext& frame, const glm::dvec3& lo, const glm::dvec3& hi);

//! Sets fog_partition.glsl's uniforms of `program` from the frame.
template <class Program>
void set_partition_uniforms(const Program& program, const FrameContext& frame)
{
    program.set("u_partitioned", int(frame.partitioned));
    program.set("u_partition", frame.partition);
    program.set("u_partition_depth", frame.partition_depth);
}

//! Sets the frame's eye, sun, sky and air uniforms of `program` (the terrain's and the
//! particles' programs read them alike).
template <class Program>
void set_light_uniforms(const Program& program, const FrameContext& frame)
{
    program.set("u_eye", frame.eye);
    program.set("u_sun_direction", frame.sun_direction);
    program.set("u_sun_radiance", frame.sun_radiance);
    program.set("u_ambient", frame.ambient);
    program.set("u_sky_horizon", frame.sky_horizon);
    program.set("u_haze_density", frame.haze_density);
}

//! Builds the frame's context; near and far planes are fitted to the scene's bounds so that
//! depth precision is spent where the scene is (the camera's own planes are the fallback).
//! `scene_min`, `scene_max`: everything drawn (the clip planes); `terrain_across`: the diagonal
//! of the terrain's extent, which sets the air (geometry::scene_air).
FrameContext make_frame_context(const Camera& camera, const SunLight& sun, int width, int height,
                                const glm::dvec3& scene_min, const glm::dvec3& scene_max, double terrain_across);

}  // namespace kiri::render::detail
