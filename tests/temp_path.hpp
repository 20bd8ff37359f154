#pragma once
// Temporary paths unique to this test process: several builds (CI, developers' worktrees)
// may run the same tests at the same time on one machine, sharing /tmp.
#include <unistd.h>

#include <filesystem>
#include <string>

namespace kiri::test {

inline std::filesystem::path temp_path(const std::string& name)
{
    return std::filesystem::temp_directory_path() / ("kiri_" + std::to_string(::getpid()) + "_" + name);
}

}  // namespace kiri::test
