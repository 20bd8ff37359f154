#include "staged_read.hpp"

#include <cstddef>

#include "gl_objects.hpp"

namespace kiri::render::detail {

void read_buffers_staged(std::span<const GLuint> sources, GLsizeiptr bytes, void* out)
{
    if (sources.empty())
        return;
    const auto total = GLsizeiptr(sources.size()) * bytes;
    Buffer staging = make_buffer();
    // Read by the CPU alone: in host memory from the start (a driver moves a buffer the CPU reads
    // there at its first read, and NVIDIA's debug output says so at every new one).
    glNamedBufferStorage(staging.get(), total, nullptr, GL_MAP_READ_BIT | GL_CLIENT_STORAGE_BIT);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);  // after the shaders' writes to them
    for (std::size_t k = 0; k < sources.size(); ++k)
        glCopyNamedBufferSubData(sources[k], staging.get(), 0, GLintptr(k) * bytes, bytes);
    glGetNamedBufferSubData(staging.get(), 0, total, out);
}

}  // namespace kiri::render::detail
