#include "tonemap_pass.hpp"

namespace kiri::render::detail {

ToneMapPass::ToneMapPass() : program_({"fullscreen.vert", "tonemap.frag"}), empty_vao_(make_vertex_array()) {}

void ToneMapPass::draw(const FrameContext& frame, unsigned hdr_color) const
{
    program_.set("u_hdr", 0);
    program_.set("u_exposure", frame.exposure);
    program_.use();
    glBindTextureUnit(0, hdr_color);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDepthMask(GL_FALSE);
    glBindVertexArray(empty_vao_.get());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDepthMask(GL_TRUE);
}

}  // namespace kiri::render::detail
