#pragma once
// Reading a few bytes of a buffer the GPU works in (a list's counts, a tally) without the
// buffer itself being read back: a driver that sees a buffer read by the CPU may move it to host
// memory for good, and the shaders' atomics on it then cross the bus. NVIDIA's did so with the
// froxel apply's lists: the apply went from 0.26 to 26 ms a frame at 1920x1080 (docs/speed.md,
// "On a GPU"). The bytes are copied into a small staging buffer on the GPU and read from there.
#include <epoxy/gl.h>

#include <span>

#include "gl_objects.hpp"

namespace kiri::render::detail {

//! A staging buffer kept for reads made every frame: created at the first read (and again when
//! one needs more bytes), not once a read.
class StagingBuffer {
public:
    //! The first `bytes` of each of `sources`, one after another into `out`, through one staging
    //! copy (one wait for the GPU).
    void read(std::span<const GLuint> sources, GLsizeiptr bytes, void* out);

private:
    Buffer buffer_;
    GLsizeiptr size_ = 0;
};

//! The same through a staging buffer of its own, for a read made once (per sun, per fog).
void read_buffers_staged(std::span<const GLuint> sources, GLsizeiptr bytes, void* out);

}  // namespace kiri::render::detail
