#include "pass_timer.hpp"

#include <array>
#include <cstring>

namespace kiri::render::detail {
namespace {

double ms_since(std::chrono::steady_clock::time_point start)
{
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

bool timer_queries_time_passes()
{
    static const bool gpu = [] {
        const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
        if (!renderer)
            return true;
        for (const char* cpu : {"llvmpipe", "softpipe", "SwiftShader"})
            if (std::strstr(renderer, cpu))
                return false;
        return true;
    }();
    return gpu;
}

PassTimer::PassTimer(std::string name) : name_(std::move(name)), queries_(timer_queries_time_passes())
{
    if (queries_)
        query_ = make_query(GL_TIME_ELAPSED);
}

void PassTimer::begin()
{
    ran_ = true;
    if (queries_) {
        cpu_start_ = std::chrono::steady_clock::now();
        glBeginQuery(GL_TIME_ELAPSED, query_.get());
        return;
    }
    glFinish();  // what came before is not this pass's
    cpu_start_ = std::chrono::steady_clock::now();
}

void PassTimer::end()
{
    if (queries_) {
        glEndQuery(GL_TIME_ELAPSED);
        cpu_ms_ = ms_since(cpu_start_);
        return;
    }
    cpu_ms_ = ms_since(cpu_start_);
    glFinish();
    device_ms_ = ms_since(cpu_start_);
}

PassTime PassTimer::result() const
{
    if (!queries_)
        return {name_, device_ms_, cpu_ms_};
    GLuint64 ns = 0;
    glGetQueryObjectui64v(query_.get(), GL_QUERY_RESULT, &ns);
    return {name_, double(ns) * 1e-6, cpu_ms_};
}

}  // namespace kiri::render::detail
