#pragma once
// KHR_debug routing: messages go to stderr (prefixed "kiri gl:"), errors are counted so that
// tests and the renderer can fail on them. GL calls back synchronously from inside the driver,
// so the callback never throws; callers check the count at safe points instead.
#include <string>

namespace kiri::render::detail {

void install_debug_callback(bool throw_on_error);
//! Throws kiri::Error naming where when GL reported an error since the last check and the
//! context asked for it (ContextOptions::throw_on_gl_error).
void check_gl_errors(const char* where);

}  // namespace kiri::render::detail
