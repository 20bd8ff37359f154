#pragma once
// Runs the kiri executable as a user would and captures its exit code, stdout and stderr.
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

#include "temp_path.hpp"

namespace kiri::test {

struct RunResult {
    int exit_code = -1;
    std::string out, err;
    int error_lines() const
    {
        int n = 0;
        for (char c : err)
            n += c == '\n';
        return n;
    }
};

inline std::string read_all(const std::filesystem::path& p)
{
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

inline std::string shell_quote(const std::string& s)
{
    std::string out = "'";
    for (char c : s)
        out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

inline RunResult run_kiri(const std::string& args)
{
    const std::filesystem::path out = temp_path("cli_stdout"), err = temp_path("cli_stderr");
    const std::string command = shell_quote(KIRI_EXE) + " " + args + " >" + out.string() + " 2>" + err.string();
    const int status = std::system(command.c_str());
    RunResult r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = read_all(out);
    r.err = read_all(err);
    std::filesystem::remove(out);
    std::filesystem::remove(err);
    return r;
}

}  // namespace kiri::test
