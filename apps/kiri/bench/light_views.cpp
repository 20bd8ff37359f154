#include "bench/light_views.hpp"

#include <cmath>
#include <fstream>
#include <numbers>
#include <utility>

#include <nlohmann/json.hpp>

namespace kiri::bench {

namespace fs = std::filesystem;
using nlohmann::json;

std::vector<LightView> light_views(bool quick)
{
    std::vector<LightView> v;
    for (const char* e : {"30", "10", "60"})
        for (const char* c : {"above", "side", "inside"})
            v.push_back({std::string("slab") + e + "_" + c, std::string("slab") + e, c, true});
    v.push_back({"slab30_across", "slab30", "across", true});
    v.push_back({"thin30_above", "thin30", "above", true});
    v.push_back({"thin30_across", "thin30", "across", true});
    v.push_back({"thin10_inside", "thin10", "inside", true});
    v.push_back({"thin60_above", "thin60", "above", true});
    const std::vector<std::pair<std::string, std::vector<std::string>>> shipped = {
        {"jacksboro", {"default", "ridge", "top"}},
        {"jacksboro_lake", {"default", "ridge", "sun", "top"}},
        {"jacksboro_fill", {"default", "valley", "top"}},
        {"jacksboro_wind", {"default", "wide"}},
        {"jacksboro_descent", {"descent_1_far_above", "descent_2_just_above", "descent_3_inside", "descent_4_below"}}};
    // Four of the shipped views are fitted on too (the default scene's thin blanket, from its
    // camera and from inside; the lake and the fill from theirs); the others are held out.
    const auto fitted_on = [](const std::string& name) {
        return name == "jacksboro_default" || name == "jacksboro_lake_default" || name == "jacksboro_fill_default" ||
            name == "jacksboro_descent_descent_3_inside";
    };
    for (const auto& [scene, cameras] : shipped)
        for (const std::string& c : cameras)
            if (!quick || c == cameras.front())
                v.push_back({scene + "_" + c, scene, c, fitted_on(scene + "_" + c)});
    return v;
}

fs::path write_slab_scene(const fs::path& dir, const std::string& name)
{
    const fs::path file = dir / (name + ".json");
    if (!fs::exists(dir / "flat.asc")) {
        std::ofstream f(dir / "flat.asc");
        f << "ncols 201\nnrows 201\nxllcorner 0\nyllcorner 0\ncellsize 50\nNODATA_value -9999\n";
        for (int r = 0; r < 201; ++r) {
            for (int c = 0; c < 201; ++c)
                f << (c ? " 0" : "0");
            f << "\n";
        }
    }
    const bool thin = name.rfind("thin", 0) == 0;
    const double top = thin ? 15.0 : 100.0, elevation = std::stod(name.substr(thin ? 4 : 4)) * std::numbers::pi / 180;
    const double h = std::cos(elevation) / std::sqrt(2.0);
    const json sun = {-h, h, std::sin(elevation)};
    const double mid = top / 2;
    json cameras = json::array();
    cameras.push_back({{"name", "above"}, {"position", {0, -400, 600}}, {"target", {0, 0, 50}}, {"fov", 40}});
    cameras.push_back(
        {{"name", "side"}, {"position", {-5250, -150, thin ? 25 : 70}}, {"target", {-4950, 0, mid}}, {"fov", 40}});
    cameras.push_back({{"name", "inside"},
                       {"position", {0, 0, mid}},
                       {"target", {-1000 * h, 1000 * h, mid + 1000 * std::sin(elevation)}},
                       {"fov", 60}});
    cameras.push_back({{"name", "across"}, {"position", {0, 0, mid}}, {"target", {1000, 1000, mid}}, {"fov", 60}});
    const json scene = {
        {"terrain", {{"path", "flat.asc"}}},
        {"cameras", cameras},
        {"sun", {{"direction", sun}, {"color", {1, 1, 1}}, {"intensity", 3.0}, {"ambient", {0, 0, 0}}}},
        {"fog", {{"fill", {{"seeds", "all"}, {"top", top}}}}},
        {"medium", {{"extinction", 0.02}, {"albedo", 0.99}, {"anisotropy", 0.8}, {"top_density", 1}, {"detail", 0}}}};
    std::ofstream(file) << scene.dump(1);
    return file;
}

}  // namespace kiri::bench
