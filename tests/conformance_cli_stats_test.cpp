// `plantarch build --stats` and `plantarch canopy --stats` print what the library says of the
// same plants: every number of their JSON is compared with the library's queries for a plant
// or canopy built here with the same species, seed, age and build parameters. Counts must be
// equal; height and leaf area equal to the printed decimals (4 and 5).
//
// Flowers and fruit have no count query: they are counted here from the plant state (flowers
// of closed and open floral buds, flowers of fruiting buds) as those that have geometry (a
// fruit at the moment it sets has size 0 and none, and is not counted), and triangles from the
// Context objects whose plantID is the plant's.

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "cli_run.h"
#include "plantarch/LeafAngles.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/PlantSummary.h"

using namespace plantarch;

namespace {

std::string outputFile(const std::string& name) {
    const auto dir = std::filesystem::temp_directory_path() / "plantarch-conformance-stats";
    std::filesystem::create_directories(dir);
    return (dir / name).string();
}

// The JSON objects the command printed, one a line.
std::vector<nlohmann::json> statsLines(const std::string& args) {
    const cli::Result r = cli::run(args);
    EXPECT_EQ(r.status, 0) << r.out;
    std::vector<nlohmann::json> out;
    std::istringstream lines(r.out);
    std::string line;
    while (std::getline(lines, line))
        if (!line.empty() && line[0] == '{') out.push_back(nlohmann::json::parse(line));
    return out;
}

struct Organs {
    std::size_t flowers = 0, fruit = 0;
};

Organs countOrgans(const PlantInstance& p) {
    Organs c;
    auto add = [&](const FloralBud& fb) {
        std::size_t drawn = 0;
        for (const FlowerOrgan& fl : fb.flowers) drawn += fl.objects.empty() ? 0 : 1;
        if (fb.stage == FloralStage::FlowerClosed || fb.stage == FloralStage::FlowerOpen)
            c.flowers += drawn;
        if (fb.stage == FloralStage::Fruit) c.fruit += drawn;
    };
    for (const Shoot& s : p.shoots) {
        if (s.removed) continue;
        for (const Phytomer& ph : s.phytomers)
            for (const Petiole& pt : ph.petioles)
                for (const FloralBud& fb : pt.floralBuds) add(fb);
        for (const FloralBud& fb : s.terminalFloralBuds) add(fb);
    }
    return c;
}

std::size_t trianglesOf(const Context& ctx, unsigned plant) {
    std::size_t n = 0;
    ctx.forEachObject([&](const ObjectView& v) {
        if (ctx.objectDataInt(v.id, "plantID") == int(plant)) n += v.indices.size() / 3;
    });
    return n;
}

// One printed object against the library's numbers for that plant.
void expectStatsOf(const nlohmann::json& j, const PlantArchitecture& arch, const Context& ctx,
                   unsigned plant, const std::string& species, std::uint64_t seed) {
    SCOPED_TRACE(j.dump());
    const std::set<std::string> keys = {"species",
                                        "plant",
                                        "age",
                                        "seed",
                                        "height",
                                        "leaves",
                                        "leaf_area",
                                        "shoots",
                                        "flowers",
                                        "fruit",
                                        "triangles",
                                        "width_x",
                                        "width_y",
                                        "width_long",
                                        "width_short",
                                        "main_nodes",
                                        "shoots_by_rank",
                                        "phytomers_by_rank",
                                        "leaf_inclination",
                                        "leaf_inclination_mean"};
    std::set<std::string> printed;
    for (const auto& [k, v] : j.items()) printed.insert(k);
    EXPECT_EQ(printed, keys) << "a number printed that this test does not check, or one missing";
    EXPECT_EQ(j.at("species").get<std::string>(), species);
    EXPECT_EQ(j.at("plant").get<unsigned>(), plant);
    EXPECT_EQ(j.at("age").get<double>(), double(arch.getPlantAge(plant)));
    EXPECT_EQ(j.at("seed").get<std::uint64_t>(), seed);
    EXPECT_NEAR(j.at("height").get<double>(), arch.getPlantHeight(plant), 0.5e-4 + 1e-9);
    EXPECT_EQ(j.at("leaves").get<unsigned>(), arch.getPlantLeafCount(plant));
    EXPECT_NEAR(j.at("leaf_area").get<double>(), arch.getPlantLeafArea(plant), 0.5e-5 + 1e-9);
    EXPECT_EQ(j.at("shoots").get<unsigned>(), arch.getShootCount(plant));
    const Organs organs = countOrgans(arch.plant(plant));
    EXPECT_EQ(j.at("flowers").get<std::size_t>(), organs.flowers);
    EXPECT_EQ(j.at("fruit").get<std::size_t>(), organs.fruit);
    EXPECT_EQ(j.at("triangles").get<std::size_t>(), trianglesOf(ctx, plant));
    // The rest as summarizePlant gives them (tests/plant_summary_test.cpp checks it), to the
    // printed 4 decimals.
    const PlantSummary s = summarizePlant(arch, plant);
    EXPECT_NEAR(j.at("width_x").get<double>(), s.widthX, 0.5e-4 + 1e-9);
    EXPECT_NEAR(j.at("width_y").get<double>(), s.widthY, 0.5e-4 + 1e-9);
    EXPECT_NEAR(j.at("width_long").get<double>(), s.widthLong, 0.5e-4 + 1e-9);
    EXPECT_NEAR(j.at("width_short").get<double>(), s.widthShort, 0.5e-4 + 1e-9);
    EXPECT_EQ(j.at("main_nodes").get<unsigned>(), s.mainNodes);
    EXPECT_EQ(j.at("shoots_by_rank").get<std::vector<unsigned>>(), s.shootsByRank);
    EXPECT_EQ(j.at("phytomers_by_rank").get<std::vector<unsigned>>(), s.phytomersByRank);
    const auto inclination = j.at("leaf_inclination").get<std::vector<double>>();
    ASSERT_EQ(inclination.size(), s.leafInclination.size());
    for (std::size_t i = 0; i < inclination.size(); ++i)
        EXPECT_NEAR(inclination[i], s.leafInclination[i], 0.5e-4 + 1e-9);
    EXPECT_NEAR(j.at("leaf_inclination_mean").get<double>(), meanLeafInclination(arch, plant),
                0.5e-4 + 1e-9);
}

TEST(ConformanceCliStats, BuildPrintsTheLibrarysNumbers) {
    struct Case {
        std::string species;
        float age;
        std::uint64_t seed;
        std::map<std::string, float> defines;
    };
    // a bean with flowers and fruit, at a fractional age; a tree with a build parameter
    const std::vector<Case> cases = {{"bean", 70.5f, 7, {}},
                                     {"almond", 630.0f, 3, {{"num_scaffolds", 3.0f}}}};
    for (const Case& c : cases) {
        std::ostringstream args;
        args << "--seed " << c.seed << " build " << c.species << " --age " << c.age;
        for (const auto& [name, value] : c.defines) args << " -D " << name << "=" << value;
        args << " -o " << outputFile(c.species + ".txt") << " --stats";
        const std::vector<nlohmann::json> printed = statsLines(args.str());
        ASSERT_EQ(printed.size(), 1u) << args.str();

        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.setSeed(c.seed);
        arch.loadPlantModelFromLibrary(c.species);
        const unsigned p = arch.buildPlantInstanceFromLibrary(vec3(0.0f), c.age, c.defines);
        const Organs organs = countOrgans(arch.plant(p));
        if (c.species == "bean") {
            EXPECT_GT(organs.flowers * organs.fruit, 0u);
        }
        expectStatsOf(printed[0], arch, ctx, p, c.species, c.seed);
        EXPECT_EQ(printed[0].at("triangles").get<std::size_t>(), ctx.triangleCount());
    }
}

TEST(ConformanceCliStats, CanopyPrintsEachPlantsNumbers) {
    const std::uint64_t seed = 5;
    const std::vector<nlohmann::json> printed =
        statsLines("--seed 5 canopy tomato --count 3x2 --spacing 0.5x0.7 --age 60 -o " +
                   outputFile("canopy.txt") + " --stats");
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.setSeed(seed);
    arch.loadPlantModelFromLibrary("tomato");
    const std::vector<unsigned> plants =
        arch.buildPlantCanopyFromLibrary(vec3(0.0f), vec2(0.5f, 0.7f), glm::ivec2(3, 2), 60.0f);
    ASSERT_EQ(printed.size(), plants.size());
    for (std::size_t i = 0; i < plants.size(); ++i)
        expectStatsOf(printed[i], arch, ctx, plants[i], "tomato", seed);
}

}  // namespace
