#include "staged_read.hpp"

#include "gl_objects.hpp"

namespace kiri::render::detail {

void read_buffer_staged(GLuint source, GLintptr offset, GLsizeiptr bytes, void* out)
{
    Buffer staging = make_buffer();
    glNamedBufferStorage(staging.get(), bytes, nullptr, GL_MAP_READ_BIT);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);  // after the shaders' writes to it
    glCopyNamedBufferSubData(source, staging.get(), offset, 0, bytes);
    glGetNamedBufferSubData(staging.get(), 0, bytes, out);
}

}  // namespace kiri::render::detail
