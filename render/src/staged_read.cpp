#include "staged_read.hpp"

#include <cstddef>

namespace kiri::render::detail {

void StagingBuffer::read(std::span<const GLuint> sources, GLsizeiptr bytes, void* out)
{
    if (sources.empty())
        return;
    const auto total = GLsizeiptr(sources.size()) * bytes;
    if (!buffer_ || size_ < total) {
        buffer_ = make_buffer();
        // Read by the CPU alone: in host memory from the start (a driver moves a buffer the CPU
        // reads there at its first read).
        glNamedBufferStorage(buffer_.get(), total, nullptr, GL_MAP_READ_BIT | GL_CLIENT_STORAGE_BIT);
        size_ = total;
    }
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);  // after the shaders' writes to them
    for (std::size_t k = 0; k < sources.size(); ++k)
        glCopyNamedBufferSubData(sources[k], buffer_.get(), 0, GLintptr(k) * bytes, bytes);
    glGetNamedBufferSubData(buffer_.get(), 0, total, out);
}

void read_buffers_staged(std::span<const GLuint> sources, GLsizeiptr bytes, void* out)
{
    StagingBuffer().read(sources, bytes, out);
}

}  // namespace kiri::render::detail
