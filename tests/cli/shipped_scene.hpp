#pragma once
// A shipped scene's JSON to edit in a test and write beside the temporary files, where its
// terrain's relative path would not reach the DEM.
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "temp_path.hpp"

namespace kiri::test {

//! data/scenes/<name>.json, its terrain's path made absolute.
inline nlohmann::json shipped_scene(const std::string& name)
{
    const std::filesystem::path scenes = std::filesystem::path(KIRI_DATA_DIR) / "scenes";
    std::ifstream in(scenes / (name + ".json"));
    nlohmann::json scene = nlohmann::json::parse(in);
    const std::filesystem::path terrain = scenes / scene["terrain"]["path"].get<std::string>();
    scene["terrain"]["path"] = std::filesystem::absolute(terrain).lexically_normal().string();
    return scene;
}

//! `scene` written to the temporary file `file_name`; its path.
inline std::filesystem::path write_temp_scene(const nlohmann::json& scene, const std::string& file_name)
{
    const std::filesystem::path file = temp_path(file_name);
    std::ofstream(file) << scene.dump(1);
    return file;
}

}  // namespace kiri::test
