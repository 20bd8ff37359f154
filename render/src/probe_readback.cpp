#include "probe_readback.hpp"

#include <epoxy/gl.h>

#include "gl_objects.hpp"

namespace kiri::render::detail {

std::vector<float> run_point_probe(const ShaderProgram& program, const void* input, std::size_t bytes,
                                   std::size_t count)
{
    if (count == 0)
        return {};
    Buffer in_buffer = make_buffer(), out_buffer = make_buffer();
    glNamedBufferStorage(in_buffer.get(), GLsizeiptr(bytes), input, 0);
    glNamedBufferStorage(out_buffer.get(), GLsizeiptr(count * sizeof(float)), nullptr, GL_MAP_READ_BIT);
    program.set("u_count", int(count));
    program.use();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, in_buffer.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, out_buffer.get());
    glDispatchCompute(GLuint((count + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<float> out(count);
    glGetNamedBufferSubData(out_buffer.get(), 0, GLsizeiptr(out.size() * sizeof(float)), out.data());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, 0);
    return out;
}

}  // namespace kiri::render::detail
