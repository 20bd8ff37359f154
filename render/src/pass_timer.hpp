#pragma once
// A GL_TIME_ELAPSED query around one pass; results are read after the frame's readback,
// when the GPU has finished anyway.
#include <chrono>
#include <string>

#include "gl_objects.hpp"
#include "kiri/render/renderer.hpp"

namespace kiri::render::detail {

class PassTimer {
public:
    explicit PassTimer(std::string name) : name_(std::move(name)), query_(make_query(GL_TIME_ELAPSED)) {}
    void begin()
    {
        ran_ = true;
        cpu_start_ = std::chrono::steady_clock::now();
        glBeginQuery(GL_TIME_ELAPSED, query_.get());
    }
    void end()
    {
        glEndQuery(GL_TIME_ELAPSED);
        cpu_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - cpu_start_).count();
    }
    //! Whether begin() was called since the last forget(): passes that may be skipped report
    //! only the timings of the ones that ran.
    bool ran() const { return ran_; }
    void forget() { ran_ = false; }
    PassTime result() const
    {
        GLuint64 ns = 0;
        glGetQueryObjectui64v(query_.get(), GL_QUERY_RESULT, &ns);
        return {name_, double(ns) * 1e-6, cpu_ms_};
    }

private:
    std::string name_;
    Query query_;
    std::chrono::steady_clock::time_point cpu_start_;
    double cpu_ms_ = 0.0;
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
