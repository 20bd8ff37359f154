#include "camera_path.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include <glm/geometric.hpp>

#include "kiri/geometry/core/error.hpp"

namespace kiri::preview {

std::vector<render::Camera> load_camera_path(const std::filesystem::path& file)
{
    std::ifstream in(file);
    if (!in)
        throw InputError(file.string(), "", "cannot read the camera path");
    std::vector<render::Camera> keys;
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '#')
            continue;
        std::istringstream s(line);
        double v[7] = {0, 0, 0, 0, 0, 0, 45.0};
        int n = 0;
        while (n < 7 && s >> v[n])
            ++n;
        std::string rest;
        const std::string where = "line " + std::to_string(number);
        if (n < 6 || (s.clear(), s >> rest))
            throw InputError(file.string(), where, "expected px py pz tx ty tz [fov]");
        if (!std::all_of(v, v + 7, [](double x) { return std::isfinite(x); }))
            throw InputError(file.string(), where, "numbers must be finite");
        if (!(v[6] > 0.0 && v[6] < 180.0))
            throw InputError(file.string(), where, "fov must be in (0, 180)");
        render::Camera c;
        c.position = {v[0], v[1], v[2]};
        c.target = {v[3], v[4], v[5]};
        c.fov_y_deg = v[6];
        if (glm::length(c.target - c.position) <= 0.0)
            throw InputError(file.string(), where, "the target equals the position");
        keys.push_back(c);
    }
    if (keys.empty())
        throw InputError(file.string(), "", "no camera in the path");
    return keys;
}

render::Camera camera_on_path(const std::vector<render::Camera>& keys, double t)
{
    if (keys.size() == 1)
        return keys.front();
    const double x = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0) * double(keys.size() - 1);
    const std::size_t i = std::min(std::size_t(x), keys.size() - 2);
    const double f = x - double(i);
    render::Camera c = keys[i];
    c.position = glm::mix(keys[i].position, keys[i + 1].position, f);
    c.target = glm::mix(keys[i].target, keys[i + 1].target, f);
    c.fov_y_deg = keys[i].fov_y_deg + f * (keys[i + 1].fov_y_deg - keys[i].fov_y_deg);
    return c;
}

}  // namespace kiri::preview
