// Fields built in tiles (plantarch/Field.h): the tile plan follows the project's layout, each
// plant built in its tile is the plant of the whole build (same ID, streams, state and
// geometry), the index is valid 3D Tiles whose boxes hold their tiles' geometry, and bad
// options are refused with one line.

#include "plantarch/Field.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "error_of.h"
#include "folder_test.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/PlantArchitecture.h"

using namespace plantarch;
using plantarch::testing::errorOf;

namespace {

class Field : public FolderTest {
protected:
    Field() : FolderTest("plantarch-field-") {}
};

// A grid with gaps (germination), a scatter and a single plant: 3 blocks, young beans.
const char* kField = R"({"plantarch_project": 1, "name": "field", "seed": 5, "blocks": [
  {"name": "grid", "species": "bean", "count": [4, 3], "spacing": [0.3, 0.3], "age": 12,
   "germination": 0.8},
  {"name": "scatter", "species": "bean", "layout": "scatter", "origin": [1.2, 0, 0],
   "area": [0.6, 0.8], "count": 4, "age": 10, "seed": 3},
  {"name": "one", "species": "bean", "layout": "single", "origin": [-1, 0.5, 0], "age": 14}]})";

Project field() {
    return readProjectString(kField, "field.json");
}

// A plant's geometry: every vertex of its objects in order, and its state as a plant file.
struct PlantPrint {
    std::vector<vec3> vertices;
    std::string xml;
};

PlantPrint printOf(const PlantArchitecture& arch, unsigned id) {
    PlantPrint p;
    for (ObjectID o : arch.getAllPlantObjectIDs(id))
        for (const vec3& v : arch.context().object(o).positions) p.vertices.push_back(v);
    p.xml = arch.getPlantStructureXML({id});
    return p;
}

std::string readText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace

TEST(FieldPlan, EveryPlantInOneTileWithItsWholeBuildIDAndBase) {
    const Project p = field();
    Context ctx;
    PlantArchitecture arch(&ctx);
    const BuiltProject built = buildProject(p, arch);
    const FieldPlan plan = fieldTiles(p, {.tileSize = 0.7f});
    EXPECT_EQ(plan.plants, built.plants().size());
    std::set<unsigned> seen;
    for (const FieldTile& t : plan.tiles) {
        EXPECT_FALSE(t.plants.empty()) << t.name;
        EXPECT_TRUE(t.halo.empty()) << "no halo without soft avoidance";
        EXPECT_EQ(t.name, "tile_" + std::to_string(t.ix) + "_" + std::to_string(t.iy));
        for (const FieldPlant& fp : t.plants) {
            EXPECT_TRUE(seen.insert(fp.id).second) << "plant " << fp.id << " in two tiles";
            ASSERT_EQ(built.blockPlants[fp.block].at(fp.index), fp.id);
            EXPECT_EQ(arch.getPlantBasePosition(fp.id), fp.base);
            EXPECT_EQ(arch.plantStream(fp.id), fp.index);
            EXPECT_GE(fp.base.x, t.min.x);
            EXPECT_LT(fp.base.x, t.max.x);
            EXPECT_GE(fp.base.y, t.min.y);
            EXPECT_LT(fp.base.y, t.max.y);
        }
    }
    EXPECT_EQ(seen.size(), plan.plants);
    EXPECT_GE(plan.tiles.size(), 4u);
    EXPECT_LE(plan.tiles.size(), std::size_t(plan.tilesX) * plan.tilesY);
    // One tile when the tile is larger than the field.
    EXPECT_EQ(fieldTiles(p, {.tileSize = 100.0f}).tiles.size(), 1u);
}

TEST(FieldPlan, WithSoftAvoidanceATileHasTheNeighboursWithinItsHalo) {
    Project p = field();
    p.softCollision = true;
    const FieldPlan plan = fieldTiles(p, {.tileSize = 0.7f, .halo = 0.35f});
    std::size_t halos = 0;
    for (const FieldTile& t : plan.tiles)
        for (const FieldPlant& h : t.halo) {
            ++halos;
            EXPECT_FALSE(h.base.x >= t.min.x && h.base.x < t.max.x && h.base.y >= t.min.y &&
                         h.base.y < t.max.y);
            const float dx = std::max({t.min.x - h.base.x, 0.0f, h.base.x - t.max.x});
            const float dy = std::max({t.min.y - h.base.y, 0.0f, h.base.y - t.max.y});
            EXPECT_LE(std::hypot(dx, dy), 0.35f);
        }
    EXPECT_GT(halos, 0u);
    EXPECT_EQ(fieldTiles(p, {.tileSize = 0.7f, .halo = 0.0f}).tiles[0].halo.size(), 0u);
}

TEST(FieldBuild, EachPlantBuiltInPartIsThePlantOfTheWholeBuild) {
    const Project p = field();
    Context whole;
    PlantArchitecture arch(&whole);
    buildProject(p, arch);
    const FieldPlan plan = fieldTiles(p, {.tileSize = 0.7f});
    for (const FieldTile& t : plan.tiles) {
        std::vector<std::vector<unsigned>> only(p.blocks.size());
        for (const FieldPlant& fp : t.plants) only[fp.block].push_back(fp.index);
        Context c;
        PlantArchitecture a(&c);
        const BuiltProject part = buildProject(p, a, {.only = only});
        ASSERT_EQ(part.plants().size(), t.plants.size()) << t.name;
        for (const FieldPlant& fp : t.plants) {
            const PlantPrint mine = printOf(a, fp.id), theirs = printOf(arch, fp.id);
            EXPECT_EQ(mine.xml, theirs.xml) << t.name << " plant " << fp.id;
            EXPECT_EQ(mine.vertices, theirs.vertices) << t.name << " plant " << fp.id;
        }
    }
}

TEST_F(Field, TilesAndIndexHoldTheWholeFieldsPlants) {
    const Project p = field();
    Context whole;
    PlantArchitecture arch(&whole);
    buildProject(p, arch);
    const FieldOptions o{.tileSize = 0.7f};
    const FieldPlan plan = fieldTiles(p, o);
    const std::string out = at("out");
    std::map<unsigned, FieldPlantRow> rows;
    for (std::size_t i = 0; i < plan.tiles.size(); ++i)
        for (const FieldPlantRow& r : buildFieldTile(p, o, i, out)) rows[r.id] = r;
    writeFieldIndex(p, o, out);
    ASSERT_EQ(rows.size(), plan.plants);
    for (const auto& [id, r] : rows) {
        std::size_t triangles = 0;
        for (ObjectID obj : arch.getAllPlantObjectIDs(id))
            triangles += whole.object(obj).triangleCount();
        EXPECT_EQ(r.triangles, triangles) << id;
        EXPECT_EQ(r.height, arch.getPlantHeight(id)) << id;
        EXPECT_EQ(float(r.leafArea), arch.getPlantLeafArea(id)) << id;
        EXPECT_EQ(r.base, arch.getPlantBasePosition(id)) << id;
        EXPECT_EQ(r.stream, arch.plantStream(id)) << id;
    }

    // tileset.json: 3D Tiles 1.1, a root with one child per tile whose box holds the geometry
    // of its GLB (read back: y up turned to z up, as a 3D Tiles viewer does).
    const nlohmann::json tileset = nlohmann::json::parse(readText(out + "/tileset.json"));
    EXPECT_EQ(tileset["asset"]["version"], "1.1");
    EXPECT_GT(tileset["geometricError"].get<double>(), 0.0);
    const auto& children = tileset["root"]["children"];
    ASSERT_EQ(children.size(), plan.tiles.size());
    std::size_t triangles = 0;
    for (std::size_t i = 0; i < plan.tiles.size(); ++i) {
        const auto& child = children[i];
        EXPECT_EQ(child["content"]["uri"], plan.tiles[i].name + ".glb");
        EXPECT_EQ(child["geometricError"].get<double>(), 0.0);
        const std::vector<double> box = child["boundingVolume"]["box"];
        ASSERT_EQ(box.size(), 12u);
        // Inside the root's box (3D Tiles: a child's volume lies within its parent's).
        const std::vector<double> root = tileset["root"]["boundingVolume"]["box"];
        for (int a = 0; a < 3; ++a)
            EXPECT_LE(std::abs(box[a] - root[a]) + box[3 + 4 * a], root[3 + 4 * a] + 1e-4)
                << plan.tiles[i].name << " axis " << a;
        Context c;
        const std::vector<ObjectID> objects = readGLTF(c, out + "/" + plan.tiles[i].name + ".glb");
        triangles += c.triangleCount();
        std::set<int> plants;
        for (ObjectID obj : objects) {
            plants.insert(*c.objectDataInt(obj, "plantID"));
            for (const vec3& v : c.object(obj).positions) {
                EXPECT_LE(std::abs(v.x - box[0]), box[3]) << plan.tiles[i].name;
                EXPECT_LE(std::abs(v.y - box[1]), box[7]) << plan.tiles[i].name;
                EXPECT_LE(std::abs(v.z - box[2]), box[11]) << plan.tiles[i].name;
            }
        }
        std::set<int> expected;
        for (const FieldPlant& fp : plan.tiles[i].plants) expected.insert(int(fp.id));
        EXPECT_EQ(plants, expected) << plan.tiles[i].name;
    }
    EXPECT_EQ(triangles, whole.triangleCount());

    // plants.csv: the header and one row per plant, in tile order.
    std::istringstream csv(readText(out + "/plants.csv"));
    std::string line;
    std::getline(csv, line);
    EXPECT_EQ(line, fieldPlantsHeader());
    std::size_t n = 0;
    while (std::getline(csv, line)) ++n;
    EXPECT_EQ(n, plan.plants);
    // Built again, a tile's files are the same bytes.
    const std::string glb = readText(out + "/" + plan.tiles[1].name + ".glb");
    buildFieldTile(p, o, 1, at("again"));
    EXPECT_EQ(readText(at("again") + "/" + plan.tiles[1].name + ".glb"), glb);
}

TEST_F(Field, WithSoftAvoidanceATileWritesOnlyItsOwnPlants) {
    Project p = readProjectString(R"({"plantarch_project": 1, "seed": 2,
      "soft_collision": {"enabled": true}, "blocks": [
      {"name": "g", "species": "bean", "count": [3, 1], "spacing": [0.2, 0.2], "age": 8}]})",
                                  "soft.json");
    const FieldOptions o{.tileSize = 0.3f, .halo = 0.25f};
    const FieldPlan plan = fieldTiles(p, o);
    ASSERT_EQ(plan.tiles.size(), 2u);
    ASSERT_FALSE(plan.tiles[0].halo.empty());
    const auto rows = buildFieldTile(p, o, 0, at("soft"));
    ASSERT_EQ(rows.size(), plan.tiles[0].plants.size());
    Context c;
    std::set<int> plants;
    for (ObjectID obj : readGLTF(c, at("soft") + "/" + plan.tiles[0].name + ".glb"))
        plants.insert(*c.objectDataInt(obj, "plantID"));
    EXPECT_EQ(plants.size(), plan.tiles[0].plants.size());
    EXPECT_EQ(plants.count(int(plan.tiles[0].halo[0].id)), 0u);
}

// With soft avoidance a halo that reaches every plant makes each tile the whole field, so its
// plants are exactly the whole build's; without a halo, plants by the border differ.
TEST(FieldBuild, WithSoftAvoidanceAWideHaloGivesTheWholeFieldsPlants) {
    const Project p = readProjectString(R"({"plantarch_project": 1, "seed": 3,
      "soft_collision": {"enabled": true}, "blocks": [
      {"name": "g", "species": "bean", "count": [4, 2], "spacing": [0.25, 0.25], "age": 40}]})",
                                        "soft.json");
    Context whole;
    PlantArchitecture arch(&whole);
    buildProject(p, arch);
    std::size_t differ[2] = {0, 0};
    for (int wide = 0; wide < 2; ++wide) {
        const FieldPlan plan = fieldTiles(p, {.tileSize = 0.5f, .halo = wide ? 1.0f : 0.0f});
        ASSERT_EQ(plan.tiles.size(), 2u);
        for (const FieldTile& t : plan.tiles) {
            std::vector<std::vector<unsigned>> only(1);
            for (const FieldPlant& fp : t.plants) only[0].push_back(fp.index);
            for (const FieldPlant& fp : t.halo) only[0].push_back(fp.index);
            std::sort(only[0].begin(), only[0].end());
            Context c;
            PlantArchitecture a(&c);
            buildProject(p, a, {.only = only});
            for (const FieldPlant& fp : t.plants)
                differ[wide] += printOf(a, fp.id).vertices != printOf(arch, fp.id).vertices;
        }
    }
    EXPECT_GT(differ[0], 0u) << "the plants by the border see no neighbour without a halo";
    EXPECT_EQ(differ[1], 0u);
}

TEST_F(Field, BadOptionsAreOneLineErrors) {
    const Project p = field();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    for (float size : {0.0f, -1.0f, nan, inf})
        EXPECT_NE(std::string(errorOf([&] { fieldTiles(p, {.tileSize = size}); }).what())
                      .find("tile_size"),
                  std::string::npos)
            << size;
    EXPECT_NE(std::string(errorOf([&] { fieldTiles(p, {.tileSize = 1e-6f}); }).what())
                  .find("at most 1000000 tiles"),
              std::string::npos);
    for (float halo : {-1.0f, nan, 2000.0f})
        EXPECT_NE(std::string(errorOf([&] { fieldTiles(p, {.tileSize = 1, .halo = halo}); }).what())
                      .find("halo"),
                  std::string::npos)
            << halo;
    const FieldOptions o{.tileSize = 0.7f};
    EXPECT_NE(std::string(errorOf([&] { buildFieldTile(p, o, 1000, at("x")); }).what())
                  .find("no such tile"),
              std::string::npos);
    std::ofstream(at("file")) << "x";
    EXPECT_NE(std::string(errorOf([&] { buildFieldTile(p, o, 0, at("file")); }).what())
                  .find("not a folder"),
              std::string::npos);
    // The index needs every tile.
    buildFieldTile(p, o, 0, at("part"));
    const std::string missing = errorOf([&] { writeFieldIndex(p, o, at("part")); }).what();
    EXPECT_NE(missing.find("tile missing"), std::string::npos) << missing;
    EXPECT_FALSE(std::filesystem::exists(at("part/tileset.json")));
    EXPECT_FALSE(std::filesystem::exists(at("part/plants.csv")));
    // A tile's table that is not the tile's.
    std::filesystem::create_directories(at("bad"));
    const FieldPlan plan = fieldTiles(p, o);
    for (const FieldTile& t : plan.tiles) {
        std::ofstream(at("bad/" + t.name + ".glb")) << "glb";
        std::ofstream(at("bad/" + t.name + ".csv")) << fieldPlantsHeader() << "\n1,2\n";
    }
    EXPECT_NE(std::string(errorOf([&] { writeFieldIndex(p, o, at("bad")); }).what())
                  .find("is not the tile's plant"),
              std::string::npos);
    // Layouts only, and no physiology.
    Project measured = p;
    measured.blocks[0].layout = ProjectBlock::Layout::Skeleton;
    EXPECT_NE(std::string(errorOf([&] { fieldTiles(measured, o); }).what()).find("blocks/0/layout"),
              std::string::npos);
    Project season = p;
    season.physiology = ProjectPhysiology{};
    EXPECT_NE(std::string(errorOf([&] { fieldTiles(season, o); }).what()).find("physiology"),
              std::string::npos);
}
