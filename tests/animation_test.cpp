// Growth animations: glTF frames keyed by scale, USD frames keyed by visibility, each frame the
// scene as it stood at its day (the same plant as one built at that age), the same bytes
// every time, and one-line errors for bad frames.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
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
using plantarch::testing::parseGlb;
using plantarch::testing::readAll;

namespace {

fs::path tempPath(const std::string& name) {
    return fs::temp_directory_path() /
           ("plantarch_animation_" + std::to_string(::getpid()) + "_" + name);
}

// Triangles under a node, through its children.
std::size_t trianglesUnder(const Glb& g, std::size_t node) {
    const json& n = g.doc["nodes"][node];
    std::size_t total = 0;
    if (n.contains("mesh"))
        for (const json& p : g.doc["meshes"][n["mesh"].get<std::size_t>()]["primitives"])
            total +=
                g.doc["accessors"][p["indices"].get<std::size_t>()]["count"].get<std::size_t>() / 3;
    if (n.contains("children"))
        for (const json& c : n["children"]) total += trianglesUnder(g, c.get<std::size_t>());
    return total;
}

// The scale a STEP sampler holds at time t: the last key at or before t (the first before it).
float scaleAt(const Glb& g, const json& sampler, float t) {
    const auto times = accessorValues<float>(g, sampler["input"]);
    const auto values = accessorValues<float>(g, sampler["output"]);
    std::size_t k = 0;
    while (k + 1 < times.size() && times[k + 1] <= t) ++k;
    return values[3 * k];
}

// A bean grown from germination, with the triangles of its scene at each of `ages` (each
// plant built at that age directly, in a fresh scene).
std::vector<std::size_t> trianglesBuiltAt(const std::vector<double>& ages) {
    std::vector<std::size_t> out;
    for (double age : ages) {
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.setSeed(7);
        arch.loadPlantModelFromLibrary("bean");
        arch.buildPlantInstanceFromLibrary(vec3(0.0f), float(age));
        out.push_back(ctx.triangleCount());
    }
    return out;
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

TEST(Animation, GlbShowsEachFrameAloneAndEachFrameIsThePlantAtItsDay) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.setSeed(7);
    arch.loadPlantModelFromLibrary("bean");
    const unsigned plant = arch.buildPlantInstanceFromLibrary(vec3(0.0f), 0.0f);
    const fs::path path = tempPath("growth.glb");
    writeGrowthAnimation(arch, {plant}, {10, 30, 10}, {path.string()}, {2.0});
    EXPECT_DOUBLE_EQ(arch.getPlantAge(plant), 30.0);  // left grown to the last frame
    const Glb g = parseGlb(readAll(path.string()));

    // The root holds the frames, in order, named by day.
    const json& nodes = g.doc["nodes"];
    const json& root = nodes[g.doc["scenes"][0]["nodes"][0].get<std::size_t>()];
    ASSERT_EQ(root["children"].size(), 3u);
    const std::vector<std::size_t> expected = trianglesBuiltAt({10, 20, 30});
    std::size_t total = 0;
    for (std::size_t f = 0; f < 3; ++f) {
        const std::size_t node = root["children"][f].get<std::size_t>();
        EXPECT_EQ(nodes[node]["name"], "day_" + std::to_string(10 * (f + 1)));
        EXPECT_EQ(nodes[node]["extras"]["day"].get<double>(), 10.0 * double(f + 1));
        // Still viewers show the last frame only.
        EXPECT_EQ(nodes[node].contains("scale"), f < 2) << f;
        // Grown from germination in 10-day steps, the plant is the one built at that age.
        EXPECT_EQ(trianglesUnder(g, node), expected[f]) << "frame " << f;
        total += expected[f];
        const json& plantNode = nodes[nodes[node]["children"][0].get<std::size_t>()];
        EXPECT_EQ(plantNode["name"], "bean_" + std::to_string(plant));
        EXPECT_DOUBLE_EQ(plantNode["extras"]["age"].get<double>(), 10.0 * double(f + 1));
    }
    EXPECT_LT(expected[0], expected[2]);  // the plant grows
    // Every frame's objects are rows of the one property table.
    const json& table = g.doc["extensions"]["EXT_structural_metadata"]["propertyTables"][0];
    EXPECT_GT(table["count"].get<std::size_t>(), 0u);

    // One channel per frame keys its scale; at frame i's time frame i alone is shown.
    const json& animation = g.doc["animations"][0];
    EXPECT_EQ(animation["name"], "growth");
    ASSERT_EQ(animation["channels"].size(), 3u);
    for (std::size_t f = 0; f < 3; ++f) {
        const json& channel = animation["channels"][f];
        EXPECT_EQ(channel["target"]["path"], "scale");
        EXPECT_EQ(channel["target"]["node"], root["children"][f]);
        EXPECT_EQ(animation["samplers"][channel["sampler"].get<std::size_t>()]["interpolation"],
                  "STEP");
    }
    for (int i = 0; i < 3; ++i)
        for (float t : {float(i) / 2.0f, (float(i) + 0.9f) / 2.0f})
            for (std::size_t f = 0; f < 3; ++f) {
                const json& channel = animation["channels"][f];
                EXPECT_EQ(
                    scaleAt(g, animation["samplers"][channel["sampler"].get<std::size_t>()], t),
                    std::size_t(i) == f ? 1.0f : 0.0f)
                    << "frame " << f << " at " << t << " s";
            }

    // Same frames, same bytes.
    Context ctx2;
    PlantArchitecture arch2(&ctx2);
    arch2.setSeed(7);
    arch2.loadPlantModelFromLibrary("bean");
    const unsigned plant2 = arch2.buildPlantInstanceFromLibrary(vec3(0.0f), 0.0f);
    const fs::path again = tempPath("again.glb");
    writeGrowthAnimation(arch2, {plant2}, {10, 30, 10}, {again.string()}, {2.0});
    EXPECT_EQ(readAll(path.string()), readAll(again.string()));
    fs::remove(path);
    fs::remove(again);
}

TEST(Animation, UsdFramesAreKeyedByVisibilityAtTheirTimeCodes) {
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
    const std::vector<std::size_t> expected = trianglesBuiltAt({10, 20, 30});
    const char* keys[3] = {"            0: \"inherited\",\n            1: \"invisible\",\n",
                           "            0: \"invisible\",\n            1: \"inherited\",\n"
                           "            2: \"invisible\",\n",
                           "            0: \"invisible\",\n            2: \"inherited\",\n"};
    for (std::size_t f = 0; f < 3; ++f) {
        const std::string name = "def Xform \"day_" + std::to_string(10 * (f + 1)) + "\"";
        const std::size_t at = text.find(name);
        ASSERT_NE(at, std::string::npos) << name;
        const std::size_t next = f < 2 ? text.find("def Xform \"day_", at + 1) : text.size();
        const std::string frame = text.substr(at, next - at);
        EXPECT_NE(
            frame.find("token visibility.timeSamples = {\n" + std::string(keys[f]) + "        }\n"),
            std::string::npos)
            << frame.substr(0, 400);
        // The frame's plant, nested one level deeper, and its triangles.
        EXPECT_NE(frame.find("\n        def Xform \"bean_" + std::to_string(plant) + "\""),
                  std::string::npos);
        std::size_t triangles = 0;
        const std::string key = "int[] faceVertexCounts = [";
        for (std::size_t k = frame.find(key); k != std::string::npos; k = frame.find(key, k + 1)) {
            const std::size_t open = k + key.size(), close = frame.find(']', open);
            if (close > open)
                triangles += std::size_t(std::count(frame.begin() + std::ptrdiff_t(open),
                                                    frame.begin() + std::ptrdiff_t(close), ',')) +
                             1;
        }
        EXPECT_EQ(triangles, expected[f]) << "frame " << f;
    }
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
              file + ": '.glb': writeUSDA writes USD text (valid: .usda)");
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
    EXPECT_EQ(g.doc["animations"][0]["channels"].size(), 5u);
    EXPECT_NE(readAll(usda).find("def Xform \"day_15\""), std::string::npos);

    // grow: frames count days from the file's state.
    const std::string xml = (dir / "bean.xml").string();
    ASSERT_EQ(cli::run("--seed 3 build bean --age 10 -o " + xml).status, 0);
    r = cli::run("--seed 3 grow " + xml + " --frames 0:10:5 --frame-rate 10 -o " + usda);
    ASSERT_EQ(r.status, 0) << r.out;
    const std::string text = readAll(usda);
    EXPECT_NE(text.find("timeCodesPerSecond = 10"), std::string::npos);
    EXPECT_NE(text.find("def Xform \"day_10\""), std::string::npos);
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
