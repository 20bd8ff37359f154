#include "sky_pass.hpp"

#include "terrain_pass.hpp"

namespace kiri::render::detail {

SkyPass::SkyPass() : program_({"fullscreen.vert", "ground.glsl", "sky.frag"}), empty_vao_(make_vertex_array()) {}

void SkyPass::draw(const FrameContext& frame, const TerrainPass& terrain) const
{
    program_.set("u_inverse_view_projection", frame.inverse_view_projection);
    program_.set("u_eye", frame.eye);
    program_.set("u_sun_direction", frame.sun_direction);
    program_.set("u_sun_radiance", frame.sun_glow ? frame.sun_radiance : glm::vec3(0.0f));
    program_.set("u_sun_light", frame.sun_radiance);
    program_.set("u_ambient", frame.ambient);
    program_.set("u_sky_zenith", frame.sky_zenith);
    program_.set("u_sky_horizon", frame.sky_horizon);
    program_.set("u_haze_density", frame.haze_density);
    terrain.set_ground_uniforms(program_, frame);
    program_.use();
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glBindVertexArray(empty_vao_.get());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDepthMask(GL_TRUE);
}

}  // namespace kiri::render::detail
