#pragma once
// The device time of one pass of a frame. On a GPU: a GL_TIME_ELAPSED query around the pass,
// read after the frame has finished. On a software rasteriser (Mesa's llvmpipe, softpipe) the
// queries do not time passes: compute dispatches run outside the binned scenes the queries
// are kept in (they read 0), and draws are binned and run per tile when the scene is flushed, so
// a query spans whatever else shares its scene (or, begun in one scene and ended in another,
// reads a raw clock: millions of ms). There the device is the CPU, and the pass's device time is
// the wall time from an idle device, through the pass, to an idle device again (glFinish on
// both sides).
#include <chrono>
#include <string>

#include "gl_objects.hpp"
#include "kiri/render/renderer.hpp"

namespace kiri::render::detail {

//! Whether the current context's GL_TIME_ELAPSED queries time passes (a GPU), or the device is
//! the CPU itself (llvmpipe, softpipe, SwiftShader): read once per process.
bool timer_queries_time_passes();

class PassTimer {
public:
    explicit PassTimer(std::string name);
    void begin();
    void end();
    //! Whether begin() was called since the last forget(): passes that may be skipped report
    //! only the timings of the ones that ran.
    bool ran() const { return ran_; }
    void forget() { ran_ = false; }
    //! gpu_ms: the device's time of the pass; cpu_ms: the time its commands took to issue.
    PassTime result() const;

private:
    std::string name_;
    bool queries_;  // timer_queries_time_passes()
    Query query_;
    std::chrono::steady_clock::time_point cpu_start_;
    double cpu_ms_ = 0.0, device_ms_ = 0.0;
    bool ran_ = false;
};

//! Times the enclosing scope: begin() now, end() when it closes. GL_TIME_ELAPSED queries do
//! not nest, so neither may two of these.
class ScopedPassTimer {
public:
    explicit ScopedPassTimer(PassTimer& timer) : timer_(timer) { timer_.begin(); }
    ~ScopedPassTimer() { timer_.end(); }
    ScopedPassTimer(const ScopedPassTimer&) = delete;
    ScopedPassTimer& operator=(const ScopedPassTimer&) = delete;

private:
    PassTimer& timer_;
};

}  // namespace kiri::render::detail
