#include <filesystem>

#include <unistd.h>

#include "commands.hpp"
#include "kiri/geometry/core/error.hpp"

namespace kiri::cli {

void check_output_file(const std::string& path)
{
    namespace fs = std::filesystem;
    const fs::path target(path);
    fs::path folder = target.parent_path();
    if (folder.empty())
        folder = ".";
    std::error_code ec;
    if (fs::is_directory(target, ec))
        throw IoError(path, "", "is a folder, expected a file name");
    if (!fs::is_directory(folder, ec))
        throw IoError(path, "", "the folder " + folder.string() + " does not exist");
    if (::access(folder.c_str(), W_OK) != 0)
        throw IoError(path, "", "the folder " + folder.string() + " is not writable");
}

void check_output_folder(const std::string& path)
{
    namespace fs = std::filesystem;
    const fs::path folder(path);
    std::error_code ec;
    if (fs::exists(folder, ec) && !fs::is_directory(folder, ec))
        throw IoError(path, "", "exists and is not a folder");
    // The nearest existing ancestor must be writable: author creates what is missing.
    fs::path existing = fs::absolute(folder, ec);
    while (!existing.empty() && !fs::exists(existing, ec))
        existing = existing.parent_path();
    if (existing.empty() || !fs::is_directory(existing, ec))
        throw IoError(path, "", "cannot be created (no existing parent folder)");
    if (::access(existing.c_str(), W_OK) != 0)
        throw IoError(path, "", "the folder " + existing.string() + " is not writable");
}

}  // namespace kiri::cli
