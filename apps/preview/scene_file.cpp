#include "scene_file.hpp"

#include <fstream>
#include <system_error>

#include "kiri/geometry/core/error.hpp"

namespace kiri::preview {
namespace fs = std::filesystem;

void save_scene(const geometry::Scene& scene, const fs::path& out)
{
    const fs::path target = fs::absolute(out);
    geometry::Scene copy = scene;
    const fs::path terrain = fs::absolute(scene.terrain.path).lexically_normal();
    const fs::path relative = terrain.lexically_relative(target.parent_path());
    copy.terrain.path = relative.empty() ? terrain : relative;
    const std::string text = geometry::scene_to_json(copy);
    geometry::parse_scene(text, target.string(), target.parent_path());  // loads back, or throws
    const fs::path tmp = target.string() + ".tmp";
    {
        std::ofstream file(tmp, std::ios::binary);
        file << text;
        file.close();
        if (!file) {
            std::error_code ec;
            fs::remove(tmp, ec);
            throw IoError(target.string(), "", "cannot write");
        }
    }
    std::error_code ec;
    fs::rename(tmp, target, ec);
    if (ec) {
        fs::remove(tmp, ec);
        throw IoError(target.string(), "", "cannot move into place: " + ec.message());
    }
}

fs::path next_screenshot_path(const fs::path& folder, const std::string& stem)
{
    for (int n = 1;; ++n) {
        fs::path p = folder / (stem + "-preview-" + std::to_string(n) + ".png");
        if (!fs::exists(p))
            return p;
    }
}

}  // namespace kiri::preview
