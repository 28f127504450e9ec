// Growth animations: glTF organs keyed by their transforms and morph weights, USD frames keyed by
// visibility, each frame the scene as it stood at its day (the same plant as one built at that
// age), the same bytes every time, and one-line errors for bad frames.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <tuple>
#include <vector>

#include "cli_run.h"
#include "error_of.h"
#include "glb_reader.h"
#include "plantarch/Export.h"
#include "plantarch/ExportPlants.h"
#include "plantarch/PlantArchitecture.h"

using namespace plantarch;
namespace fs = std::filesystem;
using json = nlohmann::json;
using plantarch::testing::accessorValues;
using plantarch::testing::errorOf;
using plantarch::testing::Glb;
using plantarch::testing::OrganKey;
using plantarch::testing::organVertices;
using plantarch::testing::parseGlb;
using plantarch::testing::readAll;
using plantarch::testing::sameOrgans;
using plantarch::testing::shownAt;
using plantarch::testing::tempPath;

namespace {

// Each organ's vertices in the bean built directly at `age` (seed 7), in ID order.
std::map<OrganKey, std::vector<vec3>> builtAt(double age) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.setSeed(7);
    arch.loadPlantModelFromLibrary("bean");
    arch.buildPlantInstanceFromLibrary(vec3(0.0f), float(age));
    return organVertices(ctx);
}

}  // namespace

TEST(Animation, FrameDaysFromStartToEndByStep) {
    EXPECT_EQ(growthFrameDays({0, 60, 1}).size(), 61u);
    EXPECT_EQ(growthFrameDays({10, 30, 10}), (std::vector<double>{10, 20, 30}));
    const std::vector<double> thirds = growthFrameDays({0, 1, 0.3});
    ASSERT_EQ(thirds.size(), 4u);
    EXPECT_NEAR(thirds[3], 0.9, 1e-12);
    const std::vector<double> tenths = growthFrameDays({0, 1, 0.1});
    ASSERT_EQ(tenths.size(), 11u);
    EXPECT_EQ(tenths.back(), 1.0);  // the end itself, not 1.0000000000000002
    EXPECT_EQ(growthFrameDays({5, 5, 1}), (std::vector<double>{5}));
    EXPECT_EQ(growthFrameDays({0, 9999, 1}).size(), kMaxAnimationFrames);

    EXPECT_EQ(std::string(errorOf([] {
                              growthFrameDays({0, 60, 0}, "--frames");
                          }).what()),
              "--frames = 0: frame step must be positive (valid: more than 0 days)");
    EXPECT_EQ(std::string(errorOf([] {
                              growthFrameDays({20, 10, 1}, "--frames");
                          }).what()),
              "--frames = 10: last frame out of range (valid: 20 to 100000 days)");
    EXPECT_EQ(std::string(errorOf([] {
                              growthFrameDays({-1, 10, 1}, "--frames");
                          }).what()),
              "--frames = -1: first frame out of range (valid: 0 to 100000 days)");
    EXPECT_EQ(std::string(errorOf([] {
                              growthFrameDays({0, 100000, 1}, "--frames");
                          }).what()),
              "--frames = 1: too many frames (100001) (valid: a step giving at most 10000 frames)");
}

TEST(Animation, GlbPlaysEachFrameAsThePlantBuiltAtItsDay) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.setSeed(7);
    arch.loadPlantModelFromLibrary("bean");
    const unsigned plant = arch.buildPlantInstanceFromLibrary(vec3(0.0f), 0.0f);
    const fs::path path = tempPath("growth.glb");
    const std::vector<double> days = {6, 12, 18, 24, 30};
    writeGrowthAnimation(arch, {plant}, {6, 30, 6}, {path.string()}, {2.0});
    EXPECT_DOUBLE_EQ(arch.getPlantAge(plant), 30.0);  // left grown to the last frame
    const Glb g = parseGlb(readAll(path.string()));

    // The plant's node holds a node per shoot, and each a node per organ with its labels.
    const json& nodes = g.doc["nodes"];
    const json& root = nodes[g.doc["scenes"][0]["nodes"][0].get<std::size_t>()];
    ASSERT_EQ(root["children"].size(), 1u);
    const json& plantNode = nodes[root["children"][0].get<std::size_t>()];
    EXPECT_EQ(plantNode["name"], "bean_" + std::to_string(plant));
    EXPECT_DOUBLE_EQ(plantNode["extras"]["age"].get<double>(), 30.0);
    const json& shoot = nodes[plantNode["children"][0].get<std::size_t>()];
    EXPECT_EQ(shoot["name"].get<std::string>().rfind("shoot_", 0), 0u);
    const json& organ = nodes[shoot["children"][0].get<std::size_t>()];
    for (const char* key : {"plantID", "objectID", "organ", "shoot", "node", "leaf", "age"})
        EXPECT_TRUE(organ["extras"].contains(key)) << key;
    const json& animation = g.doc["animations"][0];
    EXPECT_EQ(animation["name"], "growth");
    EXPECT_EQ(animation["extras"]["days"], json(days));

    // At frame i's time every organ stands where it stands in the plant built at that day, to
    // within the writer's tolerance, and nothing else is shown.
    std::size_t morphs = 0;
    for (const json& m : g.doc["meshes"]) morphs += m["primitives"][0].contains("targets");
    EXPECT_GT(morphs, 0u);  // internodes that lengthen change shape: morph targets
    for (std::size_t f = 0; f < days.size(); ++f) {
        const std::map<OrganKey, std::vector<vec3>> shown = shownAt(g, f);
        const std::map<OrganKey, std::vector<vec3>> built = builtAt(days[f]);
        EXPECT_TRUE(sameOrgans(shown, built)) << "frame " << f;
    }

    // Same frames, same bytes.
    Context ctx2;
    PlantArchitecture arch2(&ctx2);
    arch2.setSeed(7);
    arch2.loadPlantModelFromLibrary("bean");
    const unsigned plant2 = arch2.buildPlantInstanceFromLibrary(vec3(0.0f), 0.0f);
    const fs::path again = tempPath("again.glb");
    writeGrowthAnimation(arch2, {plant2}, {6, 30, 6}, {again.string()}, {2.0});
    EXPECT_EQ(readAll(path.string()), readAll(again.string()));
    fs::remove(path);
    fs::remove(again);
}

// Where each organ stands at each frame is checked against the plant built at that day by
// python/tests/test_usda.py, which parses the file; here its layout.
TEST(Animation, UsdOrgansAreKeyedAtTheFramesTimeCodes) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.setSeed(7);
    arch.loadPlantModelFromLibrary("bean");
    const unsigned plant = arch.buildPlantInstanceFromLibrary(vec3(0.0f), 0.0f);
    const fs::path path = tempPath("growth.usda");
    writeGrowthAnimation(arch, {plant}, {10, 30, 10}, {path.string()}, {12.0});
    const std::string text = readAll(path.string());
    fs::remove(path);
    EXPECT_NE(text.find("startTimeCode = 0\n    endTimeCode = 2\n    timeCodesPerSecond = 12\n"),
              std::string::npos);
    EXPECT_NE(text.find("upAxis = \"Z\""), std::string::npos);
    EXPECT_NE(text.find("def Xform \"plantarch\" (\n    customData = {\n        double[] days = "
                        "[10, 20, 30]\n"),
              std::string::npos);
    // The plant, a shoot, and organs placed per frame; an organ that appears after the first
    // frame is hidden until then.
    EXPECT_NE(text.find("\n    def Xform \"bean_" + std::to_string(plant) + "\""),
              std::string::npos);
    EXPECT_NE(text.find("\n        def Xform \"shoot_1\""), std::string::npos);
    EXPECT_NE(text.find("float3 xformOp:translate.timeSamples = {\n"), std::string::npos);
    EXPECT_NE(text.find("float3 xformOp:scale.timeSamples = {\n"), std::string::npos);
    EXPECT_NE(text.find("token visibility.timeSamples = {\n"
                        "                    0: \"invisible\",\n"),
              std::string::npos);
    EXPECT_NE(text.find("def Mesh \"leaf_s1_n0_l2\""), std::string::npos);
    // No frame repeats the whole scene.
    EXPECT_EQ(text.find("def Xform \"day_"), std::string::npos);
}

TEST(Animation, BadFramesAndPathsAreOneLineErrors) {
    Context a, b;
    const std::string file = tempPath("bad.glb").string();
    EXPECT_EQ(std::string(errorOf([&] { writeGLTF(std::vector<AnimationFrame>{}, file); }).what()),
              file + ": an animation needs at least one frame");
    EXPECT_EQ(std::string(errorOf([&] {
                              writeGLTF({{&a, 5.0, {}}, {&b, 5.0, {}}}, file);
                          }).what()),
              file +
                  ": frame 1 day = 5: animation frame days must be finite and increasing "
                  "(valid: more than 5)");
    const std::string usda = tempPath("bad.usda").string();
    EXPECT_EQ(std::string(errorOf([&] {
                              writeUSDA({{&a, 0.0, {}}}, usda, {}, {0.0});
                          }).what()),
              usda + ": framesPerSecond = 0: frame rate out of range (valid: 0.001 to 1000)");
    // A name of another format is refused before anything else is looked at.
    EXPECT_EQ(std::string(errorOf([&] {
                              writeUSDA({{&a, 0.0, {}}}, file, {}, {0.0});
                          }).what()),
              file + ": '.glb': writeUSDA writes USD text or a USDZ package (valid: .usda, .usdz)");
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    const unsigned plant = arch.buildPlantInstanceFromLibrary(vec3(0.0f), 5.0f);
    const std::string obj = tempPath("growth.obj").string();
    EXPECT_EQ(std::string(errorOf([&] {
                              writeGrowthAnimation(arch, {plant}, {0, 10, 1}, {obj});
                          }).what()),
              obj +
                  ": '.obj': an animation is written as .glb, .gltf or .usda (valid: .glb, .gltf, "
                  ".usda)");
    EXPECT_DOUBLE_EQ(arch.getPlantAge(plant), 5.0);  // checked before any growth
    EXPECT_FALSE(fs::exists(file));
    EXPECT_FALSE(fs::exists(obj));
}

TEST(Animation, CommandLineWritesGrowthFromBuildAndGrow) {
    const fs::path dir = tempPath("cli");
    fs::remove_all(dir);
    const std::string glb = (dir / "growth.glb").string(), usda = (dir / "growth.usda").string();
    cli::Result r = cli::run("--seed 3 build bean --frames 0:20:5 -o " + glb + " -o " + usda);
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("bean at 20 days (seed 3)"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("; its growth in 5 frames from 0 days written to " + glb),
              std::string::npos)
        << r.out;
    const Glb g = parseGlb(readAll(glb));
    EXPECT_EQ(g.doc["animations"][0]["extras"]["days"], json({0, 5, 10, 15, 20}));
    EXPECT_NE(readAll(usda).find("double[] days = [0, 5, 10, 15, 20]"), std::string::npos);

    // grow: frames count days from the file's state.
    const std::string xml = (dir / "bean.xml").string();
    ASSERT_EQ(cli::run("--seed 3 build bean --age 10 -o " + xml).status, 0);
    r = cli::run("--seed 3 grow " + xml + " --frames 0:10:5 --frame-rate 10 -o " + usda);
    ASSERT_EQ(r.status, 0) << r.out;
    const std::string text = readAll(usda);
    EXPECT_NE(text.find("timeCodesPerSecond = 10"), std::string::npos);
    EXPECT_NE(text.find("double[] days = [0, 5, 10]"), std::string::npos);
    EXPECT_NE(text.find("double age = 20"), std::string::npos);

    // Bad uses: one line, status 2, nothing written.
    const std::string out = (dir / "bad.glb").string();
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"build bean --frames 0:60:0 -o " + out,
         "--frames = 0: frame step must be positive (valid: more than 0 days)"},
        {"build bean --frames 0:x -o " + out,
         "--frames = 0:x: expected START:END or START:END:STEP, in days (valid: e.g. 0:60:1)"},
        {"build bean --age 30 --frames 0:60 -o " + out,
         "--age and --frames both given: --frames gives the ages of the frames"},
        {"build bean -o " + out, "--age is required (or --frames for a growth animation)"},
        {"build bean --frames 0:60 -o " + (dir / "bad.obj").string(),
         (dir / "bad.obj").string() +
             ": '.obj': --frames writes an animation (valid: .glb, .gltf, .usda)"},
        {"canopy bean --frames 0:10 --separate -o " + out,
         "--separate: --separate writes still files, one per plant: not with --frames (valid: "
         "without --frames)"},
        {"grow " + xml + " -o " + out, "--days is required (or --frames for a growth animation)"},
        {"build bean --frames 0:10 --frame-rate 0 -o " + out,
         "--frame-rate = 0: not a frame rate (valid: 0.001 to 1000)"},
    };
    for (const auto& [args, message] : cases) {
        const cli::Result bad = cli::run(args);
        EXPECT_EQ(bad.status, 2) << args;
        EXPECT_EQ(bad.out, "plantarch: " + message + "\n") << args;
    }
    EXPECT_FALSE(fs::exists(out));
    EXPECT_FALSE(fs::exists(dir / "bad.obj"));
    fs::remove_all(dir);
}
