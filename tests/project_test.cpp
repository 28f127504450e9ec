// Project files (plantarch/Project.h): strict reading with one-line errors naming the field,
// writing that reads back the same, and building: each block is the canopy it describes,
// growing on gives the plants of a fresh build, a stopped build leaves nothing.

#include "plantarch/Project.h"

#include <gtest/gtest.h>

#include <functional>
#include <stdexcept>

#include "error_of.h"
#include "folder_test.h"
#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"

using namespace plantarch;

namespace {

class ProjectFiles : public FolderTest {
protected:
    ProjectFiles() : FolderTest("plantarch-project-") {}
};

Project parse(const std::string& json) {
    return readProjectString(json, "p.json");
}

std::string errorOfProject(const std::string& json) {
    try {
        const Project p = parse(json);
        checkProject(p);
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

const char* kTwoBlocks = R"({"plantarch_project": 1, "name": "two", "seed": 9, "blocks": [
  {"name": "T", "species": "tomato", "count": [2, 1], "spacing": [0.4, 0.3], "age": 20, "seed": 7},
  {"name": "B", "species": "bean", "count": [2, 2], "spacing": [0.3, 0.3], "age": 25, "seed": 3,
   "origin": [5, 0, 0]}]})";

std::vector<std::string> plantStrings(const PlantArchitecture& arch,
                                      const std::vector<unsigned>& plants) {
    std::vector<std::string> out;
    for (unsigned id : plants) out.push_back(arch.getPlantString(id));
    return out;
}

}  // namespace

TEST(Project, EveryFieldReadsBackAfterWriting) {
    const Project p = parse(R"({"plantarch_project": 1, "name": "bean trial", "seed": 12,
      "mesh_detail": 0.5, "ground": {"size": [4, 3], "center": [1, 0]},
      "soft_collision": {"enabled": true, "cone": [70, 0.2, 128, 0.3]},
      "obstacles": {"files": ["wall.obj"], "avoid_distance": 0.25, "fruit_adjustment": true},
      "attraction": {"enabled": true, "points": [[0, 0, 1.2], [0.1, 0, 1.3]], "file": "p.csv",
                     "cone": [60, 0.15, 0.5]},
      "blocks": [
        {"name": "A", "species": "bean", "layout": "grid", "origin": [0, 0, 0], "count": [3, 2],
         "spacing": [0.3, 0.35], "germination": 0.8, "age": 40, "seed": 1,
         "parameters": {"x": 0.6}, "trellis": false},
        {"name": "B", "species": "tomato", "layout": "scatter", "origin": [2, 0, 0],
         "area": [1.5, 1.5], "count": 12, "age": 30},
        {"name": "C", "species": "my_bean.xml", "layout": "single", "origin": [0, 2, 0]}]})");
    EXPECT_EQ(p.blocks.size(), 3u);
    EXPECT_EQ(p.blocks[0].count, glm::ivec2(3, 2));
    EXPECT_FLOAT_EQ(p.blocks[0].germination, 0.8f);
    EXPECT_EQ(p.blocks[1].plants, 12u);
    EXPECT_FALSE(p.blocks[1].seed.has_value());
    EXPECT_FALSE(p.blocks[2].age.has_value());
    EXPECT_EQ(p.softCone.rays, 128u);
    EXPECT_EQ(p.attractionPoints.size(), 2u);
    const std::string text = writeProjectString(p);
    EXPECT_NE(text.find("\"spacing\": [\n        0.3,\n        0.35\n      ]"), std::string::npos)
        << text;  // shortest decimals, not 0.30000001192092896
    EXPECT_EQ(writeProjectString(parse(text)), text);
}

TEST(Project, APhysiologySectionReadsBackAfterWriting) {
    const Project p = parse(R"({"plantarch_project": 1, "blocks": [{"species": "bean"}],
      "physiology": {"carbon": true, "nitrogen": true, "location": [38.54, -121.74],
                     "start": "2026-06-01", "clearness": 0.6, "light_every": 3, "days": 12,
                     "fertilise": [[20, 0.5], [35, 0.25]]}})");
    ASSERT_TRUE(p.physiology.has_value());
    const PhysiologySeason& s = p.physiology->season;
    EXPECT_TRUE(s.carbon && s.nitrogen);
    EXPECT_EQ(s.location.latitude, 38.54);
    EXPECT_EQ(s.start.month, 6);
    EXPECT_EQ(s.lightEvery, 3u);
    EXPECT_EQ(p.physiology->days, 12u);
    ASSERT_EQ(s.fertilise.size(), 2u);
    EXPECT_EQ(s.fertilise[1].grams, 0.25);
    const std::string text = writeProjectString(p);
    EXPECT_NE(text.find("\"start\": \"2026-06-01\""), std::string::npos) << text;
    EXPECT_EQ(writeProjectString(parse(text)), text);
    // A project without the section is written without it, as before.
    EXPECT_EQ(writeProjectString(parse(R"({"plantarch_project": 1})")).find("physiology"),
              std::string::npos);
    const Project w = parse(R"({"plantarch_project": 1, "physiology": {"nitrogen": true,
      "location": [0, 0], "weather": "w.csv"}})");
    EXPECT_EQ(w.physiology->weatherFile, "w.csv");
    EXPECT_EQ(writeProjectString(parse(writeProjectString(w))), writeProjectString(w));
}

TEST(Project, APhysiologySeasonIsRebuiltNotGrownOn) {
    const char* json = R"({"plantarch_project": 1, "seed": 2,
      "blocks": [{"species": "bean", "count": [1, 1], "age": 22}],
      "physiology": {"carbon": true, "location": [38.54, -121.74], "start": "2026-06-01",
                     "light_every": 6, "days": 2}})";
    const Project p = parse(json);
    Context ctx;
    PlantArchitecture arch(&ctx);
    const BuiltProject built = buildProject(p, arch);
    ASSERT_EQ(built.physiology.size(), 2u);
    EXPECT_EQ(built.physiology.back().age, 22.0);
    EXPECT_GT(built.physiology.back().input, 0.0);
    EXPECT_TRUE(arch.hasCarbohydrateModel(built.plants().front()));
    // The plant built to 20 days and grown two with its budget differs from one built to 22.
    Project plain = p;
    plain.physiology.reset();
    Context ctx2;
    PlantArchitecture arch2(&ctx2);
    const BuiltProject built2 = buildProject(plain, arch2);
    EXPECT_EQ(arch.getPlantAge(built.plants().front()), arch2.getPlantAge(built2.plants().front()));
    EXPECT_FALSE(arch2.hasCarbohydrateModel(built2.plants().front()));
    Project later = p;
    later.blocks[0].age = 25.0f;
    EXPECT_NE(std::string(plantarch::testing::errorOf([&] { projectGrowth(p, later); }).what())
                  .find("p.json: physiology: a project with a physiology season is built again"),
              std::string::npos);
}

TEST(Project, DefaultsFillWhatIsLeftOut) {
    const Project p = parse(R"({"plantarch_project": 1, "blocks": [{"species": "bean"}]})");
    EXPECT_EQ(p.seed, 1u);
    EXPECT_EQ(p.blocks[0].name, "block 1");
    EXPECT_EQ(p.blocks[0].layout, ProjectBlock::Layout::Grid);
    EXPECT_FALSE(p.ground.has_value());
    EXPECT_FALSE(p.softCollision);
}

TEST(Project, EachBadValueIsOneLineNamingTheFieldTheValueAndTheRange) {
    const std::vector<std::pair<std::string, std::string>> cases = {
        {R"({"plantarch_project": 1, "blocks": [{"species": "bean"}, {"species": "bean", "count": [3, 0]}]})",
         "p.json: blocks/1/count/1 = 0: out of range (valid: whole numbers 1 to 1000000)"},
        {R"({"plantarch_project": 1, "blocks": [{"species": "bean", "spacng": [1, 1]}]})",
         "p.json: blocks/0/spacng: unknown field, did you mean 'spacing'?"},
        {R"({"plantarch_project": 1, "blocks": [{"species": "bean", "layout": "single", "count": 3}]})",
         "p.json: blocks/0/count: does not apply to a single block (valid: with layout grid or "
         "scatter)"},
        {R"({"plantarch_project": 1, "blocks": [{"species": "bean", "layout": "grd"}]})",
         "p.json: blocks/0/layout = \"grd\": unknown layout, did you mean 'grid'? (valid: grid, "
         "scatter, single, skeleton)"},
        {R"({"plantarch_project": 1, "blocks": [{"species": "beam"}]})",
         "p.json: blocks/0/species = beam: unknown species, did you mean 'bean'?"},
        {R"({"plantarch_project": 1, "blocks": [{"species": "apple", "parameters": {"trunk_height": 9}}]})",
         "p.json: blocks/0/parameters/trunk_height = 9: build parameter out of range (valid: 0.1 "
         "to 3 m)"},
        {R"({"plantarch_project": 1, "blocks": [{"species": "bean", "age": -1}]})",
         "p.json: blocks/0/age = -1: out of range (valid: 0 to 100000 days)"},
        {R"({"plantarch_project": 1, "blocks": [{"species": "bean", "germination": 1.5}]})",
         "p.json: blocks/0/germination = 1.5: out of range (valid: 0 to 1)"},
        {R"({"plantarch_project": 1, "blocks": [{"species": "bean", "name": "A"}, {"species": "bean", "name": "A"}]})",
         "p.json: blocks/1/name = \"A\": another block has this name (blocks/0)"},
        {R"({"plantarch_project": 1, "seed": 1.5})", "p.json: seed = 1.5: expected a seed"},
        {R"({"plantarch_project": 1, "ground": {"size": [0, 2]}})",
         "p.json: ground/size/0 = 0: out of range (valid: > 0 to 10000 m)"},
        {R"({"plantarch_project": 1, "soft_collision": {"cone": [180, 0.1, 256, 0.4]}})",
         "p.json: soft_collision/cone/0 = 180: out of range"},
        {R"({"plantarch_project": 1, "attraction": {"points": [[0, 0]]}})",
         "p.json: attraction/points/0 = [0,0]: expected 3 numbers [x, y, z]"},
        {R"({"plantarch_project": 1, "attraction": {"enabled": "yes"}})",
         "p.json: attraction/enabled = \"yes\": expected true or false"},
        {R"({"plantarch_project": 1, "obstacles": {"files": ["missing.obj"]}})",
         "p.json: obstacles/files/0 = missing.obj: cannot open obstacle file: No such file or "
         "directory"},
        {R"({"plantarch_project": 1, "nmae": "x"})",
         "p.json: nmae: unknown field, did you mean 'name'?"},
        {R"({"plantarch_project": 3})",
         "p.json: plantarch_project = 3: unsupported project version"},
        {R"({"name": "x"})", "p.json: plantarch_project: not a plantarch project"},
        {R"({"plantarch_project": 1, "seed": 1, "seed": 2})",
         "p.json:1: seed: a field given twice (valid: each field once per object)"},
        {"{\"plantarch_project\": 1,\n \"name\": }", "p.json:2: not a JSON document: "},
        {"[1, 2]", "p.json: '[1,2]': expected an object {...}"},
        {R"({"plantarch_project": 1, "physiology": {"location": [0, 0], "start": "2026-01-01"}})",
         "p.json: physiology: neither carbon nor nitrogen is on"},
        {R"({"plantarch_project": 1, "physiology": {"carbon": true, "start": "2026-01-01"}})",
         "p.json: physiology/location: missing (valid: [latitude, longitude] in degrees)"},
        {R"({"plantarch_project": 1, "physiology": {"carbon": true, "location": [91, 0], "start": "2026-01-01"}})",
         "p.json: physiology/location/0 = 91: out of range (valid: latitude -90 to 90 degrees)"},
        {R"({"plantarch_project": 1, "physiology": {"carbon": true, "location": [0, 0]}})",
         "p.json: physiology/start: missing (valid: a start date \"YYYY-MM-DD\" (clear days) or "
         "a weather file, not both)"},
        {R"({"plantarch_project": 1, "physiology": {"carbon": true, "location": [0, 0], "start": "2026-02-30"}})",
         "p.json: physiology/start = \"2026-02-30\": "},
        {R"({"plantarch_project": 1, "physiology": {"carbon": true, "location": [0, 0], "start": "2026-01-01", "days": 0}})",
         "p.json: physiology/days = 0: out of range (valid: whole days 1 to 100000)"},
        {R"({"plantarch_project": 1, "physiology": {"carbon": true, "location": [0, 0], "start": "2026-01-01", "light_every": 2.5}})",
         "p.json: physiology/light_every = 2.5: expected a whole number"},
        {R"({"plantarch_project": 1, "physiology": {"carbon": true, "location": [0, 0], "start": "2026-01-01", "fertilise": [[1, 2]]}})",
         "p.json: physiology/fertilise: fertilisation adds nitrogen (valid: with \"nitrogen\": "
         "true)"},
        {R"({"plantarch_project": 1, "physiology": {"nitrogen": true, "location": [0, 0], "start": "2026-01-01", "fertilise": [[1, 0]]}})",
         "p.json: physiology/fertilise/0/1 = 0: out of range (valid: > 0 to 1000000 g N)"},
        {R"({"plantarch_project": 1, "physiology": {"carbon": true, "location": [0, 0], "weather": "none.csv"}})",
         "p.json: physiology/weather"},
        {R"({"plantarch_project": 1, "blocks": [{"species": "bean", "age": 5}], "physiology": {"carbon": true, "location": [0, 0], "start": "2026-01-01", "days": 10}})",
         "p.json: blocks/0/age = 5: younger than the physiology's days (valid: >= physiology/days "
         "(10 days))"},
        {R"({"plantarch_project": 1, "physiology": {"carbon": true, "location": [0, 0], "start": "2026-01-01", "dyas": 3}})",
         "p.json: physiology/dyas: unknown field, did you mean 'days'?"},
    };
    for (const auto& [json, expected] : cases) {
        const std::string message = errorOfProject(json);
        EXPECT_NE(message.find(expected), std::string::npos) << json << "\n  gave: " << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

TEST(Project, EachBlockIsTheCanopyItDescribesBuiltAlone) {
    const Project p = parse(kTwoBlocks);
    Context ctx;
    PlantArchitecture arch(&ctx);
    const BuiltProject built = buildProject(p, arch);
    ASSERT_EQ(built.blockPlants.size(), 2u);
    ASSERT_EQ(built.blockPlants[0].size(), 2u);
    ASSERT_EQ(built.blockPlants[1].size(), 4u);
    struct Alone {
        const char* species;
        std::uint64_t seed;
        vec3 center;
        vec2 spacing;
        glm::ivec2 count;
        float age;
    };
    const Alone alone[] = {{"tomato", 7, vec3(0.0f), vec2(0.4f, 0.3f), {2, 1}, 20.0f},
                           {"bean", 3, vec3(5, 0, 0), vec2(0.3f), {2, 2}, 25.0f}};
    for (std::size_t b = 0; b < 2; ++b) {
        Context c;
        PlantArchitecture a(&c);
        a.setSeed(alone[b].seed);
        a.loadPlantModelFromLibrary(alone[b].species);
        const auto plants = a.buildPlantCanopyFromLibrary(alone[b].center, alone[b].spacing,
                                                          alone[b].count, alone[b].age);
        EXPECT_EQ(plantStrings(a, plants), plantStrings(arch, built.blockPlants[b]))
            << "block " << b;
        std::size_t triangles = 0;
        for (unsigned id : built.blockPlants[b])
            for (ObjectID o : arch.getAllPlantObjectIDs(id))
                triangles += ctx.object(o).triangleCount();
        EXPECT_EQ(triangles, c.triangleCount()) << "block " << b;
    }
    // The first block is also what the canopy command builds with the block's seed.
    const ProjectStats s = projectStats(arch, built);
    EXPECT_EQ(s.plants, 6u);
    EXPECT_EQ(s.triangles, ctx.triangleCount());
    EXPECT_GT(s.leafArea, 0.0);
}

TEST(Project, EditingOneBlockLeavesTheOthersPlantsAlone) {
    Project p = parse(kTwoBlocks);
    Context c1, c2;
    PlantArchitecture a1(&c1), a2(&c2);
    const BuiltProject b1 = buildProject(p, a1);
    p.blocks[0].count = {3, 2};
    const BuiltProject b2 = buildProject(p, a2);
    EXPECT_EQ(plantStrings(a1, b1.blockPlants[1]), plantStrings(a2, b2.blockPlants[1]));
}

TEST(Project, GrowingOnGivesThePlantsOfAFreshBuildAtTheLaterAge) {
    const Project earlier = parse(kTwoBlocks);
    Project later = earlier;
    later.blocks[0].age = 26.0f;
    later.blocks[1].age = 31.0f;
    Context c1, c2;
    PlantArchitecture grown(&c1), fresh(&c2);
    const BuiltProject g = buildProject(earlier, grown);
    growProject(earlier, later, grown, g);
    const BuiltProject f = buildProject(later, fresh);
    EXPECT_EQ(plantStrings(grown, g.plants()), plantStrings(fresh, f.plants()));
    EXPECT_EQ(c1.triangleCount(), c2.triangleCount());

    Project changed = later;
    changed.blocks[1].count = {1, 1};
    EXPECT_NE(std::string(plantarch::testing::errorOf([&] {
                              growProject(later, changed, grown, g);
                          }).what())
                  .find("blocks/1"),
              std::string::npos);
    Project younger = later;
    younger.blocks[0].age = 10.0f;
    EXPECT_NE(std::string(plantarch::testing::errorOf([&] {
                              growProject(later, younger, grown, g);
                          }).what())
                  .find("blocks/0/age"),
              std::string::npos);
}

TEST(Project, AStoppedBuildLeavesNothing) {
    const Project p = parse(R"({"plantarch_project": 1, "ground": {"size": [2, 2]}, "blocks": [
      {"species": "bean", "count": [4, 4], "age": 30}]})");
    // Stopped at the first report, half way (plants copied in already) and at the last.
    const std::vector<std::function<bool(double)>> stops = {[](double) { return true; },
                                                            [](double f) { return f >= 0.5; },
                                                            [](double f) { return f == 1.0; }};
    for (const auto& stopHere : stops) {
        Context ctx;
        PlantArchitecture arch(&ctx);
        ProjectBuildOptions o;
        o.progress = [&](std::string_view, double f) {
            if (stopHere(f)) throw std::runtime_error("stop");
        };
        EXPECT_THROW(buildProject(p, arch, o), std::runtime_error);
        EXPECT_EQ(ctx.objectCount(), 0u);
        EXPECT_TRUE(arch.getAllPlantIDs().empty());
        // The same objects build again in it afterwards.
        const BuiltProject b = buildProject(p, arch);
        EXPECT_EQ(b.plants().size(), 16u);
    }
}

TEST(Project, ATriangleBudgetRefusesTheBuild) {
    const Project p = parse(R"({"plantarch_project": 1, "blocks": [
      {"species": "bean", "count": [4, 4], "age": 40}]})");
    Context ctx;
    PlantArchitecture arch(&ctx);
    EXPECT_THROW(buildProject(p, arch, {.maxTriangles = 20000}), TriangleBudgetError);
    EXPECT_EQ(ctx.objectCount(), 0u);
}

TEST(Project, GroundObstaclesAndPointsAreInTheScene) {
    const Project p = parse(R"({"plantarch_project": 1, "ground": {"size": [2, 1]},
      "attraction": {"enabled": true, "points": [[0, 0, 0.3]]},
      "blocks": [{"species": "bean", "layout": "single", "age": 10}]})");
    Context ctx;
    PlantArchitecture arch(&ctx);
    const BuiltProject b = buildProject(p, arch);
    ASSERT_EQ(b.ground.size(), 1u);
    EXPECT_EQ(ctx.objectDataString(b.ground[0], "organ"), "ground");
    EXPECT_NEAR(ctx.objectArea(b.ground[0]), 2.0, 1e-6);
    EXPECT_EQ(arch.getAttractionPoints(b.plants()[0]).size(), 1u);
}

TEST_F(ProjectFiles, RelativePathsAreTakenFromTheProjectFilesFolder) {
    std::filesystem::create_directories(dir_ / "sub");
    put(at("sub/wall.obj"), "v 1 -1 0\nv 1 1 0\nv 1 1 1\nv 1 -1 1\nf 1 2 3 4\n");
    put(at("sub/p.json"), R"({"plantarch_project": 1, "obstacles": {"files": ["wall.obj"]},
      "blocks": [{"species": "bean", "layout": "single", "age": 5}]})");
    const Project p = readProjectFile(at("sub/p.json"));
    EXPECT_EQ(projectPath(p, "wall.obj"), (dir_ / "sub" / "wall.obj").string());
    Context ctx;
    PlantArchitecture arch(&ctx);
    const BuiltProject b = buildProject(p, arch);
    EXPECT_EQ(b.obstacles.size(), 1u);
    EXPECT_EQ(ctx.objectDataString(b.obstacles[0], "organ"), "obstacle");
    writeProjectFile(p, at("copy.json"));
    EXPECT_EQ(writeProjectString(readProjectFile(at("copy.json"))), writeProjectString(p));
}
