#pragma once
// A fullscreen triangle that writes only depth (gl_FragDepth of the bound program) into the bound
// framebuffer: every texel, whatever is there (the depth resolve, the layers' low-resolution
// terrain depth).
#include <epoxy/gl.h>

namespace kiri::render::detail {

inline void draw_fullscreen_depth(GLuint empty_vertex_array)
{
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_ALWAYS);
    glDepthMask(GL_TRUE);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glBindVertexArray(empty_vertex_array);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthFunc(GL_LESS);
}

}  // namespace kiri::render::detail
