// The benches' judge (apps/kiri/bench/fog_judge.hpp) judges a frame only against the reference of
// the fog it draws: a configuration that changes the fog (its Medium, its height fog, its sun) is
// refused, one that changes only how a renderer draws it is judged.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "bench/fog_judge.hpp"
#include "cli/shipped_scene.hpp"
#include "kiri/geometry/core/error.hpp"

using kiri::bench::FogJudge;
using kiri::bench::SceneJson;
using kiri::render::FogMode;

TEST(FogJudge, RefusesAFrameOfAnotherFogThanItsReference)
{
    nlohmann::json json = kiri::test::shipped_scene("jacksboro");
    json["froxel"].erase("height_fog");
    const std::filesystem::path file = kiri::test::write_temp_scene(json, "fog_judge_test.json");
    const SceneJson source(file);
    FogJudge judge(source.parse(source.root), "", 32, 18);

    const auto message = [&] {
        try {
            judge.error();
        } catch (const kiri::Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    judge.prepare(source.parse(source.root), FogMode::froxel);
    EXPECT_EQ(message(), "");
    // How many layers draw the fog: the same fog (the Medium's noise is its own since 2026-12-07).
    nlohmann::json thirty = source.root;
    thirty["layers"]["count"] = 30;
    judge.prepare(source.parse(thirty), FogMode::layers);
    EXPECT_EQ(message(), "");
    // The fog itself: refused, naming what differs.
    nlohmann::json sheared = source.root;
    sheared["medium"]["detail_layers"] = 30;
    judge.prepare(source.parse(sheared), FogMode::froxel);
    EXPECT_NE(message().find("its Medium differs"), std::string::npos) << message();
    nlohmann::json hazy = source.root;
    hazy["froxel"]["height_fog"] = {{"visibility", 150}, {"base", 420}, {"scale_height", 25}};
    judge.prepare(source.parse(hazy), FogMode::froxel);
    EXPECT_NE(message().find("its height fog differs"), std::string::npos) << message();
    nlohmann::json dim = source.root;
    dim["sun"]["intensity"] = 1.0;
    judge.prepare(source.parse(dim), FogMode::froxel);
    EXPECT_NE(message().find("its sun differs"), std::string::npos) << message();
    // Back to the reference's own scene: judged again (the Medium made again, equal).
    judge.prepare(source.parse(source.root), FogMode::combined);
    EXPECT_EQ(message(), "");
    std::filesystem::remove(file);
}
