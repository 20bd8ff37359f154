#include "kiri/geometry/scene/dem_scene.hpp"

#include <algorithm>
#include <cctype>
#include <system_error>

#include <nlohmann/json.hpp>

#include "kiri/geometry/core/error.hpp"

namespace kiri::geometry {

bool is_scene_path(const std::filesystem::path& path)
{
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext == ".json";
}

Scene dem_scene(const std::filesystem::path& dem)
{
    std::error_code ec;
    if (!std::filesystem::exists(dem, ec))
        throw InputError(dem.string(), "", "no such file");
    const std::filesystem::path absolute = std::filesystem::absolute(dem, ec);
    const nlohmann::json root = {{"terrain", {{"path", (ec ? dem : absolute).string()}}},
                                 {"fog", {{"fill", {{"seeds", "all"}}}}}};
    Scene scene = parse_scene(root.dump(), dem.string(), dem.parent_path());
    scene.file = dem;
    return scene;
}

Scene load_scene_or_dem(const std::filesystem::path& path)
{
    return is_scene_path(path) ? load_scene(path) : dem_scene(path);
}

std::string starter_scene_json(const Scene& scene, const std::filesystem::path& out)
{
    Scene s = scene;
    std::error_code ec;
    const std::filesystem::path folder = std::filesystem::absolute(out, ec).parent_path();
    if (!ec) {
        const std::filesystem::path relative = std::filesystem::absolute(s.terrain.path, ec).lexically_relative(folder);
        if (!ec && !relative.empty())
            s.terrain.path = relative;
    }
    return scene_to_json(s);
}

}  // namespace kiri::geometry
