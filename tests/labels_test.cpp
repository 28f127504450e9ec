// Labels that survive (docs/formats.md, "Labels"): OBJ label comments and names, their reading
// back, PLY face labels and colours (binary and ASCII), labels through `convert` between OBJ,
// PLY and glTF, and the object table that leads from a mesh object to its plant file element.

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <pugixml.hpp>
#include <set>
#include <sstream>

#include "cli_run.h"
#include "glb_reader.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/PlantStructureWrite.h"
#include "ply_reader.h"

using namespace plantarch;
using plantarch::testing::readAll;
using plantarch::testing::readPlyFile;

namespace {

namespace fs = std::filesystem;

fs::path folder(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("plantarch_labels_" + name);
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

Mesh quad() {
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    m.indices = {0, 1, 2, 0, 2, 3};
    return m;
}

// Every label an exporter reads, as one comparable text per object.
std::string labelsText(const Context& c, ObjectID id) {
    std::ostringstream s;
    for (const char* label : {"plantID", "shootID", "rank", "node", "leafID"}) {
        const auto v = c.objectDataInt(id, label);
        s << label << '=' << (v ? std::to_string(*v) : "-") << ' ';
    }
    const auto age = c.objectDataFloat(id, "age");
    s << "age=" << (age ? std::to_string(*age) : "-") << ' ';
    for (const char* label : {"organ", "plant_name"})
        s << label << '=' << c.objectDataString(id, label).value_or("-") << ' ';
    return s.str();
}

// A canopy of two beans built through the library.
struct TwoBeans {
    Context ctx;
    PlantArchitecture arch{&ctx};
    std::vector<unsigned> plants;
    TwoBeans() {
        arch.loadPlantModelFromLibrary("bean");
        plants = arch.buildPlantCanopyFromLibrary(vec3(0.0f), vec2(0.3f), glm::ivec2(2, 1), 20.0f);
    }
};

}  // namespace

TEST(Labels, ObjCommentAndNamesOfOneObject) {
    const fs::path d = folder("comment");
    Context c;
    c.addObject(quad());  // object 0: no labels
    const ObjectID id = c.addObject(quad());
    c.setObjectData(id, "plantID", 3);
    c.setObjectData(id, "plant_name", std::string("my bean"));
    c.setObjectData(id, "organ", std::string("leaf"));
    c.setObjectData(id, "shootID", 1);
    c.setObjectData(id, "rank", 1);
    c.setObjectData(id, "node", 4);
    c.setObjectData(id, "leafID", 7);
    c.setObjectData(id, "age", 12.5f);
    writeOBJ(c, (d / "q.obj").string(), {.normals = false, .materials = false});
    EXPECT_EQ(readAll((d / "q.obj").string()),
              "# plantarch OBJ: 2 objects, 4 triangles\n"
              "o obj0\ng obj0\n# plantarch labels object=0\n"
              "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n"
              "o obj1_plant3_leaf\ng obj1_plant3_leaf\n"
              "# plantarch labels object=1 plant=3 plant_name=my%20bean organ=leaf shoot=1 rank=1 "
              "node=4 leaf=7 age=12.5\n"
              "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 5 6 7\nf 5 7 8\n");
    Context back;
    const std::vector<ObjectID> ids = readOBJ(back, (d / "q.obj").string());
    EXPECT_EQ(ids, (std::vector<ObjectID>{0, 1}));
    EXPECT_EQ(labelsText(back, 1), labelsText(c, 1));
    EXPECT_EQ(labelsText(back, 0), labelsText(c, 0));
    fs::remove_all(d);
}

TEST(Labels, ObjReadBackKeepsEveryLabelAndObjectID) {
    TwoBeans b;
    const fs::path d = folder("canopy_obj");
    const std::string path = (d / "c.obj").string();
    writeOBJ(b.ctx, path);
    Context back;
    const std::vector<ObjectID> ids = readOBJ(back, path);
    EXPECT_EQ(ids, b.ctx.objectIDs()) << "a fresh Context gets the recorded IDs";
    std::set<int> plants;
    for (ObjectID id : b.ctx.objectIDs()) {
        ASSERT_TRUE(back.doesObjectExist(id));
        EXPECT_EQ(labelsText(back, id), labelsText(b.ctx, id)) << "object " << id;
        EXPECT_EQ(back.object(id).triangleCount(), b.ctx.object(id).triangleCount());
        plants.insert(back.objectDataInt(id, "plantID").value_or(-1));
    }
    EXPECT_EQ(plants, (std::set<int>{0, 1}));

    // Into a Context whose IDs are taken: new IDs in file order, the same labels.
    Context busy;
    busy.addObject(quad());
    const std::vector<ObjectID> again = readOBJ(busy, path);
    const std::vector<ObjectID> original = b.ctx.objectIDs();
    ASSERT_EQ(again.size(), original.size());
    EXPECT_NE(again, original);
    for (std::size_t i = 0; i < again.size(); ++i)
        EXPECT_EQ(labelsText(busy, again[i]), labelsText(b.ctx, original[i]));

    // Asked not to, readOBJ leaves the labels alone.
    Context plain;
    const std::vector<ObjectID> bare = readOBJ(plain, path, {.labels = false});
    EXPECT_FALSE(plain.objectDataInt(bare.front(), "plantID").has_value());
    fs::remove_all(d);
}

// The names an OBJ gave its objects (the `name` label readOBJ stores) survive a write and a
// read, though the writer names objects obj<ID>_...: the label comment carries them.
TEST(Labels, ObjShapeNamesSurviveAWriteAndARead) {
    const fs::path d = folder("names");
    const std::string in = (d / "in.obj").string(), out = (d / "out.obj").string();
    std::ofstream(in) << "o wall\nv -1 0 0\nv 1 0 0\nv 1 0 2\nv -1 0 2\nf 1 2 3 4\n"
                         "g my ground\nv -5 -5 0\nv 5 -5 0\nv 0 5 0\nf -3 -2 -1\n";
    Context a;
    const std::vector<ObjectID> first = readOBJ(a, in);
    ASSERT_EQ(first.size(), 2u);
    EXPECT_EQ(a.objectDataString(first[0], "name"), "wall");
    EXPECT_EQ(a.objectDataString(first[1], "name"), "my ground");
    writeOBJ(a, out);
    Context b;
    const std::vector<ObjectID> second = readOBJ(b, out);
    ASSERT_EQ(second.size(), 2u);
    EXPECT_EQ(b.objectDataString(second[0], "name"), "wall");
    EXPECT_EQ(b.objectDataString(second[1], "name"), "my ground");
    fs::remove_all(d);
}

// Found by fuzz_obj: a recorded ID far above the Context's issued a dummy object for every
// ID below it (a million under AddressSanitizer took 13 s). The IDs are now skipped at once.
TEST(Labels, ObjRecordedHighObjectIDIsKept) {
    const fs::path d = folder("high");
    const std::string path = (d / "high.obj").string();
    std::ofstream(path) << "o a\n# plantarch labels object=900000 plant=2\n"
                           "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    Context c;
    const std::vector<ObjectID> ids = readOBJ(c, path);
    EXPECT_EQ(ids, std::vector<ObjectID>{900000});
    EXPECT_EQ(c.objectCount(), 1u);
    EXPECT_EQ(c.objectIDs(), std::vector<ObjectID>{900000});
    EXPECT_EQ(c.objectDataInt(900000, "plantID"), 2);

    // Past the limit of unused IDs the objects are numbered afresh, labels kept.
    ObjReadOptions few;
    few.maxSkippedObjectIDs = 899999;
    Context fresh;
    EXPECT_EQ(readOBJ(fresh, path, few), std::vector<ObjectID>{0});
    EXPECT_EQ(fresh.objectDataInt(0, "plantID"), 2);
    few.maxSkippedObjectIDs = 900000;
    Context kept;
    EXPECT_EQ(readOBJ(kept, path, few), std::vector<ObjectID>{900000});
    fs::remove_all(d);
}

TEST(Labels, ObjBadLabelValueNamesFileLineAndKey) {
    const fs::path d = folder("bad");
    const std::string path = (d / "bad.obj").string();
    std::ofstream(path) << "o a\n# plantarch labels object=0 plant=3 later_key=x\n"
                           "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"
                           "o b\n# plantarch labels object=1 plant=three\n"
                           "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 4 5 6\n";
    Context c;
    try {
        readOBJ(c, path);
        FAIL() << "a bad label value was accepted";
    } catch (const Error& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find(path + ":8"), std::string::npos) << m;
        EXPECT_NE(m.find("plant"), std::string::npos) << m;
        EXPECT_NE(m.find("three"), std::string::npos) << m;
    }
    EXPECT_EQ(c.objectCount(), 0u) << "nothing added on error";

    // A key this version does not know is skipped; a bad encoding is an error.
    std::ofstream(path) << "o a\n# plantarch labels object=0 plant=3 later_key=x\n"
                           "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    const std::vector<ObjectID> ids = readOBJ(c, path);
    ASSERT_EQ(ids.size(), 1u);
    EXPECT_EQ(c.objectDataInt(ids[0], "plantID"), 3);
    std::ofstream(path) << "o a\n# plantarch labels organ=le%4\n"
                           "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    EXPECT_THROW(readOBJ(c, path), Error);
    fs::remove_all(d);
}

TEST(Labels, PlyAsciiAndBinaryHoldTheSameLabelsAndColours) {
    TwoBeans b;
    const fs::path d = folder("ply");
    writePLY(b.ctx, (d / "b.ply").string(), {.color = PlyColor::Organ});
    writePLY(b.ctx, (d / "a.ply").string(), {.format = PlyFormat::Ascii, .color = PlyColor::Organ});
    const auto bin = readPlyFile((d / "b.ply").string());
    const auto asc = readPlyFile((d / "a.ply").string());
    EXPECT_TRUE(bin.binary);
    EXPECT_FALSE(asc.binary);
    for (const char* name :
         {"plant_id", "object_id", "organ", "leaf_id", "shoot_id", "rank", "node", "age"}) {
        ASSERT_TRUE(bin.face.count(name)) << name;
        EXPECT_EQ(bin.face.at(name), asc.face.at(name)) << name;
    }
    EXPECT_EQ(bin.faces, asc.faces);
    EXPECT_EQ(bin.vertex.at("red"), asc.vertex.at("red"));
    // Each face's labels are its object's; its vertices have its organ's colour.
    const std::size_t faces = bin.faces.size();
    ASSERT_EQ(faces, b.ctx.triangleCount());
    std::set<int> plants;
    for (std::size_t f = 0; f < faces; ++f) {
        const ObjectID id = ObjectID(bin.face.at("object_id")[f]);
        EXPECT_EQ(bin.face.at("plant_id")[f], b.ctx.objectDataInt(id, "plantID").value_or(-1));
        EXPECT_EQ(bin.face.at("node")[f], b.ctx.objectDataInt(id, "node").value_or(-1));
        EXPECT_EQ(bin.face.at("leaf_id")[f], b.ctx.objectDataInt(id, "leafID").value_or(-1));
        EXPECT_EQ(float(bin.face.at("age")[f]), b.ctx.objectDataFloat(id, "age").value_or(-1));
        const std::string organ = b.ctx.objectDataString(id, "organ").value_or("");
        EXPECT_EQ(kOrganLabels[std::size_t(bin.face.at("organ")[f])], organ);
        const auto rgb = organLabelColor(organ);
        const int v = bin.faces[f][0];
        EXPECT_EQ(bin.vertex.at("red")[std::size_t(v)], rgb[0]);
        EXPECT_EQ(bin.vertex.at("green")[std::size_t(v)], rgb[1]);
        EXPECT_EQ(bin.vertex.at("blue")[std::size_t(v)], rgb[2]);
        plants.insert(int(bin.face.at("plant_id")[f]));
    }
    EXPECT_EQ(plants, (std::set<int>{0, 1}));
    // Plant colours tell the plants apart.
    writePLY(b.ctx, (d / "p.ply").string(), {.color = PlyColor::Plant});
    const auto byPlant = readPlyFile((d / "p.ply").string());
    std::map<int, std::set<double>> reds;
    for (std::size_t f = 0; f < faces; ++f)
        reds[int(byPlant.face.at("plant_id")[f])].insert(
            byPlant.vertex.at("red")[std::size_t(byPlant.faces[f][0])]);
    ASSERT_EQ(reds.size(), 2u);
    EXPECT_EQ(reds[0].size(), 1u);
    EXPECT_EQ(reds[1].size(), 1u);
    EXPECT_NE(*reds[0].begin(), *reds[1].begin());
    fs::remove_all(d);
}

namespace {

// The property table of a .glb, column by column.
std::map<std::string, std::string> propertyTable(const std::string& path) {
    const auto g = plantarch::testing::parseGlb(readAll(path));
    const auto& table = g.doc["extensions"]["EXT_structural_metadata"]["propertyTables"][0];
    std::map<std::string, std::string> columns;
    for (const auto& [name, p] : table["properties"].items()) {
        const auto& view = g.doc["bufferViews"][p["values"].get<int>()];
        columns[name] = g.bin.substr(view["byteOffset"].get<std::size_t>(),
                                     view["byteLength"].get<std::size_t>());
    }
    return columns;
}

// The face labels of a PLY file, column by column.
std::map<std::string, std::vector<double>> faceLabels(const std::string& path) {
    return readPlyFile(path).face;
}

}  // namespace

// The example of docs/formats.md ("Labels"): a canopy of two plants, its OBJ converted.
TEST(Labels, ConvertKeepsLabelsBetweenFormats) {
    const fs::path d = folder("convert");
    const std::string f = (d / "field").string();
    auto r = cli::run("canopy bean --count 2x1 --age 20 -o " + f + ".obj -o " + f + ".ply -o " + f +
                      ".glb");
    ASSERT_EQ(r.status, 0) << r.out;
    r = cli::run("convert " + f + ".obj " + f + "_from_obj.ply --ply-format ascii");
    ASSERT_EQ(r.status, 0) << r.out;
    r = cli::run("convert " + f + ".obj " + f + "_from_obj.glb");
    ASSERT_EQ(r.status, 0) << r.out;
    r = cli::run("convert " + f + ".obj " + f + "_from_obj.obj");
    ASSERT_EQ(r.status, 0) << r.out;

    // OBJ -> PLY (ASCII from binary): per face the same plant, object, organ, leaf, shoot, rank,
    // node and age.
    const auto original = faceLabels(f + ".ply");
    const auto converted = faceLabels(f + "_from_obj.ply");
    ASSERT_EQ(original.size(), 8u);
    EXPECT_EQ(converted, original);
    const auto& plant = original.at("plant_id");
    EXPECT_EQ(std::set<double>(plant.begin(), plant.end()), (std::set<double>{0, 1}));
    // OBJ -> GLB: the same property table (object IDs and all their labels).
    EXPECT_EQ(propertyTable(f + "_from_obj.glb"), propertyTable(f + ".glb"));
    // OBJ -> OBJ: the same names and label comments.
    auto heads = [](const std::string& path) {
        std::istringstream in(readAll(path));
        std::string out;
        for (std::string line; std::getline(in, line);)
            if (line.rfind("o ", 0) == 0 || line.rfind("# plantarch labels", 0) == 0)
                out += line + "\n";
        return out;
    };
    EXPECT_EQ(heads(f + "_from_obj.obj"), heads(f + ".obj"));
    EXPECT_GT(heads(f + ".obj").size(), 1000u);
    fs::remove_all(d);
}

TEST(Labels, ObjectTableLeadsFromEachMeshObjectToItsPlantFileElement) {
    const fs::path d = folder("table");
    const std::string f = (d / "field").string();
    // Strawberries at 60 days have flowers, fruit and peduncles as well as leaves.
    auto r = cli::run("canopy strawberry --count 2x1 --age 60 --object-ids -o " + f + ".obj -o " +
                      f + ".xml");
    ASSERT_EQ(r.status, 0) << r.out;
    ASSERT_TRUE(fs::exists(f + ".objects.json"));
    const auto table = nlohmann::json::parse(readAll(f + ".objects.json"));
    EXPECT_EQ(table["format"], "plantarch object table 1");
    EXPECT_EQ(table["plants"].size(), 2u);
    pugi::xml_document xml;
    ASSERT_TRUE(xml.load_file((f + ".xml").c_str()));

    // Every object of the OBJ is in the table, with the labels of its comment.
    std::map<ObjectID, std::string> organOf;
    {
        Context c;
        for (ObjectID id : readOBJ(c, f + ".obj"))
            organOf[id] = c.objectDataString(id, "organ").value_or("");
    }
    ASSERT_EQ(table["objects"].size(), organOf.size());
    std::map<std::string, int> elements;
    for (const auto& o : table["objects"]) {
        const ObjectID id = o["object_id"];
        ASSERT_TRUE(organOf.count(id)) << id;
        EXPECT_EQ(o["organ"], organOf[id]);
        if (!o.contains("structure")) continue;
        // The XPath names the element that holds the ID in the plant file.
        const auto& s = o["structure"];
        const pugi::xpath_node node = xml.select_node(s["xpath"].get<std::string>().c_str());
        ASSERT_TRUE(node) << s["xpath"];
        const std::string element = s["element"];
        EXPECT_EQ(node.node().name(), element == "flower" ? std::string("flower") : element);
        const char* child = element == "leaf" || element == "flower" ? "object_IDs"
                            : element == "peduncle"                  ? "peduncle_object_ID"
                                                                     : "object_ID";
        std::istringstream recorded(node.node().child_value(child));
        std::vector<ObjectID> ids;
        for (ObjectID v; recorded >> v;) ids.push_back(v);
        const std::size_t part = s.value("part", 0);
        ASSERT_LT(part, ids.size()) << s["xpath"];
        EXPECT_EQ(ids[part], id) << s["xpath"];
        EXPECT_EQ(o["plant_id"], s["plant_instance"]);
        ++elements[element];
    }
    for (const char* e : {"internode", "petiole", "leaf", "peduncle", "flower"})
        EXPECT_GT(elements[e], 0) << e;

    // From an OBJ, the table lists the labels (no plant file is known).
    r = cli::run("convert " + f + ".obj " + f + "_copy.ply --object-ids");
    ASSERT_EQ(r.status, 0) << r.out;
    const auto copy = nlohmann::json::parse(readAll(f + "_copy.objects.json"));
    ASSERT_EQ(copy["objects"].size(), table["objects"].size());
    for (std::size_t i = 0; i < copy["objects"].size(); ++i) {
        nlohmann::json expected = table["objects"][i];
        expected.erase("structure");
        EXPECT_EQ(copy["objects"][i], expected);
    }
    fs::remove_all(d);
}

TEST(Labels, BadPlyOptionsAreRejected) {
    auto r = cli::run("build bean --age 5 -o /tmp/plantarch_labels_x.ply --ply-color leafy");
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.out.find("--ply-color"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("none, organ, plant, material"), std::string::npos) << r.out;
    r = cli::run("build bean --age 5 -o /tmp/plantarch_labels_x.ply --ply-format text");
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.out.find("binary, ascii"), std::string::npos) << r.out;
    EXPECT_FALSE(fs::exists("/tmp/plantarch_labels_x.ply"));
}

TEST(Labels, ObstacleFromAPlantExportIsNoPlant) {
    // A plant's OBJ used as an obstacle: its labels are not read, so its faces belong to no
    // plant and the plant grown beside it is the only plant 0.
    const fs::path d = folder("obstacle");
    const std::string wall = (d / "old.obj").string(), out = (d / "scene.ply").string();
    auto r = cli::run("build bean --age 10 -o " + wall);
    ASSERT_EQ(r.status, 0) << r.out;
    r = cli::run("build bean --age 10 --obstacle " + wall + " -o " + out);
    ASSERT_EQ(r.status, 0) << r.out;
    const auto ply = readPlyFile(out);
    std::size_t obstacleFaces = 0;
    for (std::size_t f = 0; f < ply.faces.size(); ++f) {
        const bool obstacle = ply.face.at("organ")[f] == 9;  // kOrganLabels: obstacle
        obstacleFaces += obstacle;
        if (obstacle) {
            EXPECT_EQ(ply.face.at("plant_id")[f], -1);
            EXPECT_EQ(ply.face.at("leaf_id")[f], -1);
        }
    }
    EXPECT_GT(obstacleFaces, 100u);
    fs::remove_all(d);
}
