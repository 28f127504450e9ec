// glTF writer: the binary and text forms read back as the scene they were written from
// (triangles, positions relative to each plant's node, labels per vertex and in the property
// table), the same bytes every time, and the errors it gives.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "glb_reader.h"
#include "plantarch/Context.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/Render.h"

using namespace plantarch;
namespace fs = std::filesystem;
using json = nlohmann::json;
using plantarch::testing::accessorValues;
using plantarch::testing::Glb;
using plantarch::testing::parseGlb;
using plantarch::testing::readAll;
using plantarch::testing::tempPath;
using plantarch::testing::viewValues;

namespace {

struct Scene {
    Context ctx;
    PlantArchitecture arch{&ctx};
    std::vector<GltfPlant> plants;

    explicit Scene(const char* species, int count = 2) {
        arch.setSeed(5);
        arch.loadPlantModelFromLibrary(species);
        for (int i = 0; i < count; ++i) {
            const unsigned id =
                arch.buildPlantInstanceFromLibrary(vec3(0.5f * float(i), 0.2f, 0.0f), 30);
            plants.push_back({std::int32_t(id), species, arch.getPlantBasePosition(id),
                              arch.getPlantAge(id), 5});
        }
    }
};

}  // namespace

TEST(Gltf, GlbHoldsEveryTriangleWithItsLabelsAndPlantNodes) {
    Scene s("bean");
    GltfOptions o;
    o.plants = s.plants;
    const fs::path path = tempPath("bean.glb");
    writeGLTF(s.ctx, path.string(), o);
    const Glb g = parseGlb(readAll(path.string()));
    fs::remove(path);

    // Plant nodes: named, placed at the base, with extras.
    std::map<int, json> plantNodes;
    for (const json& n : g.doc["nodes"])
        if (n.contains("extras")) plantNodes[n["extras"]["plantID"].get<int>()] = n;
    ASSERT_EQ(plantNodes.size(), 2u);
    for (const GltfPlant& p : s.plants) {
        const json& n = plantNodes.at(p.id);
        EXPECT_EQ(n["name"], "bean_" + std::to_string(p.id));
        EXPECT_EQ(n["extras"]["species"], "bean");
        EXPECT_EQ(n["extras"]["seed"], 5);
        EXPECT_DOUBLE_EQ(n["extras"]["age"].get<double>(), 30.0);
        if (p.base != vec3(0.0f)) {
            EXPECT_FLOAT_EQ(n["translation"][0].get<float>(), p.base.x);
            EXPECT_FLOAT_EQ(n["translation"][1].get<float>(), p.base.y);
        }
    }

    // Every triangle once; per-vertex labels name each vertex's object, plant and organ; the
    // feature IDs index property table rows that say the same.
    const json& table = g.doc["extensions"]["EXT_structural_metadata"]["propertyTables"][0];
    const std::size_t rows = table["count"];
    EXPECT_EQ(rows, s.ctx.objectCount());
    const auto tableObject =
        viewValues<std::uint32_t>(g, table["properties"]["object"]["values"], rows);
    const auto tablePlant =
        viewValues<std::int32_t>(g, table["properties"]["plant"]["values"], rows);
    const auto tableOrgan =
        viewValues<std::uint8_t>(g, table["properties"]["organ"]["values"], rows);
    const auto tableLeaf = viewValues<std::int32_t>(g, table["properties"]["leaf"]["values"], rows);
    std::set<std::uint32_t> tableIDs(tableObject.begin(), tableObject.end());
    EXPECT_EQ(tableIDs.size(), rows);
    for (std::size_t r = 0; r < rows; ++r) {
        const ObjectID id = tableObject[r];
        ASSERT_TRUE(s.ctx.doesObjectExist(id));
        EXPECT_EQ(tablePlant[r], s.ctx.objectDataInt(id, "plantID").value_or(-1));
        EXPECT_EQ(std::string(kOrganLabels[tableOrgan[r]]),
                  s.ctx.objectDataString(id, "organ").value());
        EXPECT_EQ(tableLeaf[r], s.ctx.objectDataInt(id, "leafID").value_or(-1));
    }
    std::size_t triangles = 0;
    std::map<ObjectID, std::size_t> verticesOf;
    for (const json& mesh : g.doc["meshes"])
        for (const json& prim : mesh["primitives"]) {
            const json& at = prim["attributes"];
            const auto indices = accessorValues<std::uint32_t>(g, prim["indices"]);
            const auto object = accessorValues<float>(g, at["_OBJECT_ID"]);
            const auto plant = accessorValues<float>(g, at["_PLANT_ID"]);
            const auto organ = accessorValues<float>(g, at["_ORGAN"]);
            const auto feature = accessorValues<float>(g, at["_FEATURE_ID_0"]);
            const auto normal = accessorValues<float>(g, at["NORMAL"]);
            triangles += indices.size() / 3;
            for (std::uint32_t i : indices) ASSERT_LT(i, object.size());
            for (std::size_t v = 0; v < object.size(); ++v) {
                const ObjectID id = ObjectID(object[v]);
                ++verticesOf[id];
                EXPECT_EQ(int(plant[v]), s.ctx.objectDataInt(id, "plantID").value());
                EXPECT_EQ(std::string(kOrganLabels[std::size_t(organ[v])]), mesh["name"]);
                EXPECT_EQ(tableObject[std::size_t(feature[v])], id);
                const float len = std::sqrt(normal[3 * v] * normal[3 * v] +
                                            normal[3 * v + 1] * normal[3 * v + 1] +
                                            normal[3 * v + 2] * normal[3 * v + 2]);
                EXPECT_NEAR(len, 1.0f, 1e-4f);
            }
            EXPECT_EQ(prim["extensions"]["EXT_mesh_features"]["featureIds"][0]["propertyTable"], 0);
        }
    EXPECT_EQ(triangles, s.ctx.triangleCount());
    for (const auto& [id, n] : verticesOf) EXPECT_EQ(n, s.ctx.object(id).positions.size());
    EXPECT_EQ(verticesOf.size(), s.ctx.objectCount());
}

TEST(Gltf, PositionsAreRelativeToThePlantNodeAndTheRootTurnsZUpToYUp) {
    Scene s("bean", 1);
    s.plants[0].base = s.arch.getPlantBasePosition(0);
    ASSERT_NE(s.plants[0].base, vec3(0.0f));
    GltfOptions o;
    o.plants = s.plants;
    const fs::path path = tempPath("one.glb");
    writeGLTF(s.ctx, path.string(), o);
    const Glb g = parseGlb(readAll(path.string()));
    fs::remove(path);
    const json& root = g.doc["nodes"][g.doc["scenes"][0]["nodes"][0].get<int>()];
    EXPECT_NEAR(root["rotation"][0].get<double>(), -std::sqrt(0.5), 1e-6);
    EXPECT_NEAR(root["rotation"][3].get<double>(), std::sqrt(0.5), 1e-6);
    // The leaf vertices plus the node's translation are the Context's positions.
    const ObjectID leaf = s.arch.getPlantObjectIDs(0, OrganKind::Leaf).front();
    std::size_t found = 0;
    for (const json& mesh : g.doc["meshes"])
        for (const json& prim : mesh["primitives"]) {
            const auto object = accessorValues<float>(g, prim["attributes"]["_OBJECT_ID"]);
            const auto pos = accessorValues<float>(g, prim["attributes"]["POSITION"]);
            std::size_t k = 0;
            for (std::size_t v = 0; v < object.size(); ++v) {
                if (ObjectID(object[v]) != leaf) continue;
                const vec3 world =
                    vec3(pos[3 * v], pos[3 * v + 1], pos[3 * v + 2]) + s.plants[0].base;
                const vec3 expected = s.ctx.object(leaf).positions[k++];
                EXPECT_NEAR(world.x, expected.x, 1e-5f);
                EXPECT_NEAR(world.y, expected.y, 1e-5f);
                EXPECT_NEAR(world.z, expected.z, 1e-5f);
            }
            found += k;
        }
    EXPECT_EQ(found, s.ctx.object(leaf).positions.size());
}

TEST(Gltf, TextFormEmbedsTheSameBufferAndBothAreDeterministic) {
    Scene s("strawberry", 1);
    GltfOptions o;
    o.plants = s.plants;
    const fs::path glb = tempPath("s.glb"), glb2 = tempPath("s2.glb"), text = tempPath("s.gltf");
    writeGLTF(s.ctx, glb.string(), o);
    writeGLTF(s.ctx, glb2.string(), o);
    writeGLTF(s.ctx, text.string(), o);
    const std::string a = readAll(glb.string()), b = readAll(glb2.string());
    EXPECT_EQ(a, b);
    const Glb g = parseGlb(a);
    const json t = json::parse(readAll(text.string()));
    const std::string uri = t["buffers"][0]["uri"];
    const std::string prefix = "data:application/octet-stream;base64,";
    ASSERT_EQ(uri.rfind(prefix, 0), 0u);
    // Decode the base64 and compare with the binary chunk.
    std::string decoded;
    int bits = 0, value = 0;
    for (char c : uri.substr(prefix.size())) {
        const std::string alphabet =
            "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        const auto at = alphabet.find(c);
        if (at == std::string::npos) break;
        value = (value << 6) | int(at);
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            decoded += char((value >> bits) & 0xff);
        }
    }
    EXPECT_EQ(decoded, g.bin);
    json withoutUri = t;
    withoutUri["buffers"][0].erase("uri");
    EXPECT_EQ(withoutUri, g.doc);
    for (const auto& p : {glb, glb2, text}) fs::remove(p);
}

TEST(Gltf, ObjectsOfNoPlantGoUnderTheSceneNode) {
    Context ctx;
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    m.indices = {0, 1, 2};
    const ObjectID id = ctx.addObject(m, Material{vec3(0.5f), "", "wall"});
    ctx.setObjectData(id, "organ", std::string("obstacle"));
    const fs::path path = tempPath("wall.glb");
    writeGLTF(ctx, path.string());
    const Glb g = parseGlb(readAll(path.string()));
    fs::remove(path);
    bool scene = false;
    for (const json& n : g.doc["nodes"]) scene = scene || n.value("name", "") == "scene";
    EXPECT_TRUE(scene);
    EXPECT_EQ(g.doc["meshes"][0]["name"], "obstacle");
    EXPECT_EQ(g.doc["materials"][0]["name"], "wall");
    EXPECT_TRUE(g.doc["materials"][0]["doubleSided"].get<bool>());
}

TEST(Gltf, BadPathsAreOneLineErrorsAndLeaveNothing) {
    Context ctx;
    try {
        writeGLTF(ctx, tempPath("x.gltb").string());
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("valid: .glb, .gltf"), std::string::npos);
    }
    const fs::path missing = fs::temp_directory_path() / "plantarch_no_such_dir" / "a.glb";
    EXPECT_THROW(writeGLTF(ctx, missing.string()), Error);
    EXPECT_FALSE(fs::exists(missing));
}

TEST(Gltf, TexturedMaterialsCarryTheirImage) {
    const fs::path png = tempPath("bark.png");
    Image image(4, 2);
    for (std::size_t i = 0; i < image.rgb.size(); ++i) image.rgb[i] = std::uint8_t(i * 7);
    writePNG(image, png.string());
    Context ctx;
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    m.uvs = {{0, 0}, {1, 0}, {0, 1}};
    m.indices = {0, 1, 2};
    ctx.addObject(m, Material{vec3(1.0f), png.string(), "bark"});
    const fs::path path = tempPath("textured.glb");
    writeGLTF(ctx, path.string());
    const Glb g = parseGlb(readAll(path.string()));
    fs::remove(path);
    ASSERT_EQ(g.doc["images"].size(), 1u);
    EXPECT_EQ(g.doc["images"][0]["mimeType"], "image/png");
    const json& view = g.doc["bufferViews"][g.doc["images"][0]["bufferView"].get<int>()];
    const std::string embedded =
        g.bin.substr(view["byteOffset"].get<std::size_t>(), view["byteLength"].get<std::size_t>());
    EXPECT_EQ(embedded, readAll(png.string()));
    EXPECT_EQ(g.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"], 0);
    EXPECT_TRUE(g.doc["meshes"][0]["primitives"][0]["attributes"].contains("TEXCOORD_0"));
    fs::remove(png);
}

// The physiology's float data (absorbed_par, sunlit_fraction, net_photosynthesis,
// carbohydrate_concentration) become property table columns when some object carries them:
// FLOAT32 with noData for the other rows, each named in docs/formats.md. Without them the
// file is the bytes it always was.
TEST(Gltf, PhysiologyDataAddFloatColumnsWithNoDataAndLeaveOtherFilesAlone) {
    Scene s("bean", 2);
    GltfOptions o;
    o.plants = s.plants;
    const fs::path path = tempPath("physiology.glb");
    writeGLTF(s.ctx, path.string(), o);
    const std::string plain = readAll(path.string());
    const json plainTable =
        parseGlb(plain).doc["extensions"]["EXT_structural_metadata"]["propertyTables"][0];
    EXPECT_EQ(plainTable["properties"].size(), 8u);

    std::map<ObjectID, float> par, sugar;
    ObjectID shaded = 0;
    for (ObjectID id : s.ctx.objectIDs()) {
        const bool leaf = s.ctx.objectDataString(id, "organ") == "leaf";
        if (leaf) {
            par[id] = 10.0f + float(id % 97);
            s.ctx.setObjectData(id, "absorbed_par", par[id]);
            s.ctx.setObjectData(id, "net_photosynthesis", -0.5f);  // may be negative
            shaded = id;
        }
        if (s.ctx.objectDataInt(id, "plantID") == s.plants[0].id) {
            sugar[id] = 0.25f;
            s.ctx.setObjectData(id, "carbohydrate_concentration", 0.25f);
        }
        s.ctx.setObjectData(id, "sunlit_fraction", std::int32_t(1));  // not a float: absent
    }
    ASSERT_FALSE(par.empty());
    writeGLTF(s.ctx, path.string(), o);
    const Glb g = parseGlb(readAll(path.string()));
    const json& metadata = g.doc["extensions"]["EXT_structural_metadata"];
    const json& table = metadata["propertyTables"][0];
    const json& classProperties = metadata["schema"]["classes"]["organ"]["properties"];
    const std::size_t rows = table["count"];
    EXPECT_FALSE(table["properties"].contains("sunlit_fraction"));
    const auto objects =
        viewValues<std::uint32_t>(g, table["properties"]["object"]["values"], rows);
    for (const auto& [name, expected] :
         {std::pair{"absorbed_par", &par}, std::pair{"carbohydrate_concentration", &sugar}}) {
        ASSERT_TRUE(table["properties"].contains(name)) << name;
        const json& p = classProperties[name];
        EXPECT_EQ(p["type"], "SCALAR");
        EXPECT_EQ(p["componentType"], "FLOAT32");
        const float noData = p["noData"].get<float>();
        EXPECT_EQ(noData, -9999.0f);
        const auto values = viewValues<float>(g, table["properties"][name]["values"], rows);
        std::size_t carried = 0;
        for (std::size_t r = 0; r < rows; ++r) {
            const auto it = expected->find(objects[r]);
            EXPECT_EQ(values[r], it == expected->end() ? noData : it->second) << name << r;
            carried += it != expected->end();
        }
        EXPECT_EQ(carried, expected->size());
    }
    const auto net =
        viewValues<float>(g, table["properties"]["net_photosynthesis"]["values"], rows);
    for (std::size_t r = 0; r < rows; ++r)
        if (objects[r] == shaded) {
            EXPECT_EQ(net[r], -0.5f);
        }
    // Data removed again: the same bytes as before they were set.
    for (ObjectID id : s.ctx.objectIDs())
        for (const char* label :
             {"absorbed_par", "net_photosynthesis", "carbohydrate_concentration"})
            s.ctx.clearObjectData(id, label);
    writeGLTF(s.ctx, path.string(), o);
    EXPECT_EQ(readAll(path.string()), plain);
    fs::remove(path);
}

// Every optional column the writer declares (the properties with noData) is named in
// docs/formats.md, with the no-data value.
TEST(Gltf, EveryPhysiologyColumnIsDocumented) {
    Context ctx;
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    m.indices = {0, 1, 2};
    const ObjectID id = ctx.addObject(m, Material{vec3(0.3f, 0.6f, 0.2f), "", "leaf"});
    for (const char* label :
         {"absorbed_par", "sunlit_fraction", "net_photosynthesis", "carbohydrate_concentration"})
        ctx.setObjectData(id, label, 0.5f);
    const fs::path path = tempPath("documented.glb");
    writeGLTF(ctx, path.string());
    const Glb g = parseGlb(readAll(path.string()));
    fs::remove(path);
    const json& properties =
        g.doc["extensions"]["EXT_structural_metadata"]["schema"]["classes"]["organ"]["properties"];
    const std::string docs = readAll(std::string(PLANTARCH_SOURCE_DIR) + "/docs/formats.md");
    std::size_t optional = 0;
    for (const auto& [name, p] : properties.items()) {
        if (!p.contains("noData")) continue;
        ++optional;
        EXPECT_NE(docs.find("`" + name + "`"), std::string::npos) << name;
    }
    EXPECT_EQ(optional, 4u);
    EXPECT_NE(docs.find("-9999"), std::string::npos);
}

// --nodes organ: a node per organ under a node per shoot, each labelled, placing a shape that
// organs of the same geometry share; the scene shown is the scene written, organ for organ.
TEST(Gltf, ANodePerOrganShowsEveryOrganWhereItStandsAndSharesEqualShapes) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.setSeed(5);
    arch.loadPlantModelFromLibrary("tomato");
    const unsigned plant = arch.buildPlantInstanceFromLibrary(vec3(0.3f, -0.2f, 0.0f), 60.0f);
    const fs::path path = tempPath("organs.glb");
    GltfOptions options;
    options.nodes = NodeLevel::Organ;
    writeGLTF(ctx, path.string(), options);
    const Glb g = parseGlb(readAll(path.string()));
    EXPECT_TRUE(plantarch::testing::sameOrgans(plantarch::testing::shownAt(g),
                                               plantarch::testing::organVertices(ctx)));
    std::set<std::string> names;
    std::set<std::size_t> meshes;
    std::size_t organs = 0, triangles = 0;
    for (const json& n : g.doc["nodes"]) {
        if (!n.contains("extras") || !n["extras"].contains("objectID")) continue;
        ++organs;
        const ObjectID id = n["extras"]["objectID"];
        EXPECT_EQ(n["extras"]["plantID"], int(plant));
        EXPECT_EQ(n["extras"]["organ"], ctx.objectDataString(id, "organ").value());
        EXPECT_EQ(n["extras"]["node"], ctx.objectDataInt(id, "node").value_or(-1));
        const std::string shoot = "_s" + std::to_string(n["extras"]["shoot"].get<int>());
        EXPECT_NE(n["name"].get<std::string>().find(shoot), std::string::npos) << n["name"];
        names.insert(n["name"].get<std::string>() + "/" + shoot);
        meshes.insert(n["mesh"].get<std::size_t>());
        const json& p = g.doc["meshes"][n["mesh"].get<std::size_t>()]["primitives"][0];
        triangles +=
            g.doc["accessors"][p["indices"].get<std::size_t>()]["count"].get<std::size_t>() / 3;
    }
    EXPECT_EQ(organs, ctx.objectCount());
    EXPECT_EQ(names.size(), organs);  // every organ named apart
    EXPECT_EQ(triangles, ctx.triangleCount());
    EXPECT_LT(meshes.size(), organs);  // equal leaflets share their mesh
    // A shared mesh carries no object labels per vertex; a mesh of one organ does.
    std::map<std::size_t, int> users;
    for (const json& n : g.doc["nodes"])
        if (n.contains("mesh")) ++users[n["mesh"].get<std::size_t>()];
    for (const auto& [mesh, count] : users) {
        const json& a = g.doc["meshes"][mesh]["primitives"][0]["attributes"];
        EXPECT_TRUE(a.contains("_PLANT_ID") && a.contains("_ORGAN"));
        EXPECT_EQ(a.contains("_OBJECT_ID"), count == 1) << mesh;
    }
    // Without instancing every organ has a mesh of its own.
    options.instancing = Instancing::None;
    writeGLTF(ctx, path.string(), options);
    const Glb own = parseGlb(readAll(path.string()));
    EXPECT_EQ(own.doc["meshes"].size(), ctx.objectCount());
    EXPECT_TRUE(plantarch::testing::sameOrgans(plantarch::testing::shownAt(own),
                                               plantarch::testing::organVertices(ctx)));
    // --nodes plant: one mesh per plant, a primitive per material, every triangle.
    options.nodes = NodeLevel::Plant;
    writeGLTF(ctx, path.string(), options);
    const Glb one = parseGlb(readAll(path.string()));
    ASSERT_EQ(one.doc["meshes"].size(), 1u);
    EXPECT_EQ(one.doc["meshes"][0]["name"], "plant");
    std::size_t all = 0;
    for (const json& p : one.doc["meshes"][0]["primitives"])
        all +=
            one.doc["accessors"][p["indices"].get<std::size_t>()]["count"].get<std::size_t>() / 3;
    EXPECT_EQ(all, ctx.triangleCount());
    fs::remove(path);
}

// An empty scene is a valid file: no property table (a table of no rows is not allowed) and no
// buffer views of no bytes, at every node level.
TEST(Gltf, AnEmptySceneIsAValidFileWithNoEmptyArrays) {
    Context ctx;
    const fs::path path = tempPath("empty.glb");
    for (NodeLevel level : {NodeLevel::Plant, NodeLevel::Kind, NodeLevel::Organ}) {
        GltfOptions options;
        options.nodes = level;
        writeGLTF(ctx, path.string(), options);
        const Glb g = parseGlb(readAll(path.string()));
        EXPECT_FALSE(g.doc.contains("extensions")) << nodeLevelName(level);
        EXPECT_FALSE(g.doc.contains("bufferViews")) << nodeLevelName(level);
        EXPECT_EQ(g.doc["scenes"][0]["nodes"].size(), 1u);
    }
    fs::remove(path);
}
