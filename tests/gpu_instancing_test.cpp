// Instancing::Gpu: organs of one shape drawn as the instances of an EXT_mesh_gpu_instancing
// node (USD: a PointInstancer, python/tests/test_usd_instancing.py). Every organ is shown where
// the file with a node per organ shows it, labelled per instance; the refusals leave no file.

#include <gtest/gtest.h>
#include <unistd.h>

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

using namespace plantarch;
namespace fs = std::filesystem;
using json = nlohmann::json;
using plantarch::testing::accessorValues;
using plantarch::testing::Glb;
using plantarch::testing::organVertices;
using plantarch::testing::parseGlb;
using plantarch::testing::readAll;
using plantarch::testing::sameOrgans;
using plantarch::testing::shownAt;
using plantarch::testing::tempPath;

namespace {

Glb written(const Context& ctx, const std::string& name, Instancing instancing) {
    const fs::path path = tempPath(name);
    GltfOptions options;
    options.nodes = NodeLevel::Organ;
    options.instancing = instancing;
    writeGLTF(ctx, path.string(), options);
    Glb g = parseGlb(readAll(path.string()));
    fs::remove(path);
    return g;
}

std::vector<const json*> instancingNodes(const Glb& g) {
    std::vector<const json*> out;
    for (const json& n : g.doc["nodes"])
        if (n.contains("extensions") && n["extensions"].contains("EXT_mesh_gpu_instancing"))
            out.push_back(&n);
    return out;
}

bool listed(const Glb& g, const char* list, const char* name) {
    if (!g.doc.contains(list)) return false;
    for (const json& e : g.doc[list])
        if (e == name) return true;
    return false;
}

std::size_t triangles(const Glb& g, const json& node) {
    const json& p = g.doc["meshes"][node["mesh"].get<std::size_t>()]["primitives"][0];
    return g.doc["accessors"][p["indices"].get<std::size_t>()]["count"].get<std::size_t>() / 3;
}

// Every instance's labels are its organ's: object, feature row, shoot, node, leaf, age.
void expectInstanceLabels(const Context& ctx, const Glb& g, const json& n) {
    const json& a = n["extensions"]["EXT_mesh_gpu_instancing"]["attributes"];
    const auto ids = accessorValues<float>(g, a["_OBJECT_ID"]);
    const auto features = accessorValues<float>(g, a["_FEATURE_ID_0"]);
    const auto shoot = accessorValues<float>(g, a["_SHOOT"]);
    const auto node = accessorValues<float>(g, a["_NODE"]);
    const auto leaf = accessorValues<float>(g, a["_LEAF"]);
    const auto age = accessorValues<float>(g, a["_AGE"]);
    const json& table = g.doc["extensions"]["EXT_structural_metadata"]["propertyTables"][0];
    const json& objectColumn = table["properties"]["object"];
    const json& view = g.doc["bufferViews"][objectColumn["values"].get<int>()];
    const std::size_t rows = table["count"];
    std::vector<std::uint32_t> objects(rows);
    std::memcpy(objects.data(), g.bin.data() + view["byteOffset"].get<std::size_t>(), 4 * rows);
    ASSERT_EQ(n["extras"]["objectIDs"].size(), ids.size());
    EXPECT_EQ(n["extensions"]["EXT_instance_features"]["featureIds"][0]["featureCount"],
              ids.size());
    for (std::size_t i = 0; i < ids.size(); ++i) {
        const ObjectID id = ObjectID(ids[i]);
        EXPECT_EQ(n["extras"]["objectIDs"][i], id);
        EXPECT_EQ(objects.at(std::size_t(features[i])), id);
        EXPECT_EQ(ctx.objectDataString(id, "organ").value(), n["extras"]["organ"]);
        EXPECT_EQ(int(shoot[i]), ctx.objectDataInt(id, "shootID").value_or(-1));
        EXPECT_EQ(int(node[i]), ctx.objectDataInt(id, "node").value_or(-1));
        EXPECT_EQ(int(leaf[i]), ctx.objectDataInt(id, "leafID").value_or(-1));
        EXPECT_FLOAT_EQ(age[i], ctx.objectDataFloat(id, "age").value_or(-1.0f));
    }
}

// Three leaves of one plant, each a triangle of its own shape: nothing to instance.
void addUniqueLeaves(Context& ctx) {
    for (int k = 1; k <= 3; ++k) {
        Mesh m;
        m.positions = {vec3(0.0f), vec3(0.1f * float(k), 0.0f, 0.0f), vec3(0.0f, 0.05f, 0.02f)};
        m.indices = {0, 1, 2};
        const ObjectID id = ctx.addObject(m);
        ctx.setObjectData(id, "organ", std::string("leaf"));
        ctx.setObjectData(id, "plantID", 0);
        ctx.setObjectData(id, "leafID", k);
    }
}

}  // namespace

// A tomato: each shape several organs share is one node whose instances land vertex for vertex
// where the organ nodes of --instancing shared put them; organs of a shape of their own keep
// their nodes, and every triangle is drawn once.
TEST(GpuInstancing, InstancesShowEveryOrganWhereTheSharedFileDoesLabelledPerInstance) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.setSeed(5);
    arch.loadPlantModelFromLibrary("tomato");
    arch.buildPlantInstanceFromLibrary(vec3(0.3f, -0.2f, 0.0f), 60.0f);
    const Glb shared = written(ctx, "shared.glb", Instancing::Shared);
    const Glb gpu = written(ctx, "gpu.glb", Instancing::Gpu);
    EXPECT_TRUE(sameOrgans(shownAt(gpu), organVertices(ctx)));
    EXPECT_TRUE(sameOrgans(shownAt(gpu), shownAt(shared)));
    EXPECT_TRUE(listed(gpu, "extensionsUsed", "EXT_mesh_gpu_instancing"));
    EXPECT_TRUE(listed(gpu, "extensionsRequired", "EXT_mesh_gpu_instancing"));
    EXPECT_TRUE(listed(gpu, "extensionsUsed", "EXT_instance_features"));
    EXPECT_FALSE(listed(shared, "extensionsUsed", "EXT_mesh_gpu_instancing"));
    const std::vector<const json*> nodes = instancingNodes(gpu);
    ASSERT_FALSE(nodes.empty());
    std::size_t drawn = 0, instances = 0;
    std::set<std::size_t> meshes;
    for (const json& n : gpu.doc["nodes"]) {
        if (n.contains("extras") && n["extras"].contains("objectID")) {
            drawn += triangles(gpu, n);
            EXPECT_FALSE(meshes.count(n["mesh"])) << "an organ node shares its mesh";
            meshes.insert(n["mesh"].get<std::size_t>());
        }
    }
    for (const json* n : nodes) {
        const std::size_t count = (*n)["extras"]["instances"].size();
        EXPECT_GE(count, 2u);
        instances += count;
        drawn += count * triangles(gpu, *n);
        EXPECT_FALSE(meshes.count((*n)["mesh"])) << "a shape drawn twice";
        meshes.insert((*n)["mesh"].get<std::size_t>());
        expectInstanceLabels(ctx, gpu, *n);
        // The mesh carries the labels its instances share, per vertex.
        const json& a =
            gpu.doc["meshes"][(*n)["mesh"].get<std::size_t>()]["primitives"][0]["attributes"];
        EXPECT_TRUE(a.contains("_PLANT_ID") && a.contains("_ORGAN") && !a.contains("_OBJECT_ID"));
    }
    EXPECT_EQ(drawn, ctx.triangleCount());
    EXPECT_GT(instances, nodes.size());
    // The same bytes every time.
    const Glb again = written(ctx, "gpu.glb", Instancing::Gpu);
    EXPECT_EQ(again.doc, gpu.doc);
    EXPECT_EQ(again.bin, gpu.bin);
}

// A canopy: each plant's instances are under its own node, placed from its base.
TEST(GpuInstancing, ACanopyInstancesEachPlantsOwnShapesUnderItsNode) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.setSeed(7);
    arch.loadPlantModelFromLibrary("bean");
    std::vector<GltfPlant> plants;
    for (int i = 0; i < 3; ++i) {
        const unsigned id =
            arch.buildPlantInstanceFromLibrary(vec3(0.4f * float(i), 0.1f * float(i), 0.0f), 35);
        plants.push_back(
            {std::int32_t(id), "bean", arch.getPlantBasePosition(id), arch.getPlantAge(id), 7});
    }
    const fs::path path = tempPath("canopy.glb");
    GltfOptions options;
    options.nodes = NodeLevel::Organ;
    options.plants = plants;
    writeGLTF(ctx, path.string(), options);
    const Glb shared = parseGlb(readAll(path.string()));
    options.instancing = Instancing::Gpu;
    writeGLTF(ctx, path.string(), options);
    const Glb g = parseGlb(readAll(path.string()));
    fs::remove(path);
    // Organs of equal labels on several plants are keyed together, in plant order in both.
    EXPECT_TRUE(sameOrgans(shownAt(g), shownAt(shared)));
    std::set<int> plantsInstanced;
    for (const json& n : g.doc["nodes"]) {
        if (!n.contains("extras") || !n["extras"].contains("plantID") || !n.contains("children"))
            continue;
        for (const json& c : n["children"]) {
            const json& child = g.doc["nodes"][c.get<std::size_t>()];
            if (!child.contains("extensions")) continue;
            EXPECT_EQ(child["extras"]["plantID"], n["extras"]["plantID"]);
            plantsInstanced.insert(n["extras"]["plantID"].get<int>());
            expectInstanceLabels(ctx, g, child);
        }
    }
    EXPECT_EQ(plantsInstanced.size(), plants.size());
}

// Nothing to instance: an empty scene, and organs of shapes all different, are written as with
// shared instancing, the extension not listed.
TEST(GpuInstancing, NoRepeatedShapeWritesNoInstancesAndNoExtension) {
    Context empty;
    const Glb none = written(empty, "empty.glb", Instancing::Gpu);
    EXPECT_FALSE(none.doc.contains("extensionsUsed"));
    EXPECT_FALSE(none.doc.contains("extensionsRequired"));
    Context ctx;
    addUniqueLeaves(ctx);
    const Glb g = written(ctx, "unique.glb", Instancing::Gpu);
    EXPECT_TRUE(instancingNodes(g).empty());
    EXPECT_FALSE(listed(g, "extensionsUsed", "EXT_mesh_gpu_instancing"));
    EXPECT_FALSE(g.doc.contains("extensionsRequired"));
    EXPECT_TRUE(sameOrgans(shownAt(g), organVertices(ctx)));
}

// Gpu instancing needs a node per organ and a still scene: refused before anything is written.
TEST(GpuInstancing, WithoutANodePerOrganOrInAnAnimationItIsRefusedAndLeavesNoFile) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.setSeed(5);
    arch.loadPlantModelFromLibrary("bean");
    arch.buildPlantInstanceFromLibrary(vec3(0.0f), 20);
    for (const char* ext : {".glb", ".usda"}) {
        const fs::path path = tempPath(std::string("refused") + ext);
        auto write = [&](NodeLevel nodes, bool animated) {
            const std::vector<AnimationFrame> frames = {{&ctx, 0.0, {}}, {&ctx, 1.0, {}}};
            if (std::string(ext) == ".glb") {
                GltfOptions o;
                o.nodes = nodes;
                o.instancing = Instancing::Gpu;
                animated ? writeGLTF(frames, path.string(), o) : writeGLTF(ctx, path.string(), o);
            } else {
                UsdOptions o;
                o.nodes = nodes;
                o.instancing = Instancing::Gpu;
                animated ? writeUSDA(frames, path.string(), o) : writeUSDA(ctx, path.string(), o);
            }
        };
        for (NodeLevel level : {NodeLevel::Plant, NodeLevel::Kind}) {
            try {
                write(level, false);
                ADD_FAILURE() << "not refused: " << nodeLevelName(level) << ext;
            } catch (const Error& e) {
                EXPECT_EQ(e.parameter(), "instancing");
                EXPECT_NE(std::string(e.what()).find("needs a node per organ"), std::string::npos)
                    << e.what();
            }
            EXPECT_FALSE(fs::exists(path));
        }
        try {
            write(NodeLevel::Organ, true);
            ADD_FAILURE() << "an animation not refused" << ext;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("cannot be animated"), std::string::npos)
                << e.what();
        }
        EXPECT_FALSE(fs::exists(path));
        EXPECT_EQ(instancingFromName("GPU"), std::nullopt);
        EXPECT_EQ(instancingFromName(instancingName(Instancing::Gpu)), Instancing::Gpu);
    }
}

// plantarch's own reader (readGLTF, render) draws every instance: the gpu file reads back as the
// file with a node per organ does, triangle for triangle and within the writers' tolerance.
TEST(GpuInstancing, ReadGltfPlacesEveryInstance) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.setSeed(5);
    arch.loadPlantModelFromLibrary("tomato");
    arch.buildPlantInstanceFromLibrary(vec3(0.3f, -0.2f, 0.0f), 60.0f);
    std::vector<Context> read(2);
    for (int k = 0; k < 2; ++k) {
        const fs::path path = tempPath(k ? "read_gpu.glb" : "read_shared.glb");
        GltfOptions options;
        options.nodes = NodeLevel::Organ;
        options.instancing = k ? Instancing::Gpu : Instancing::Shared;
        writeGLTF(ctx, path.string(), options);
        readGLTF(read[std::size_t(k)], path.string());
        fs::remove(path);
    }
    ASSERT_EQ(read[1].triangleCount(), ctx.triangleCount());
    ASSERT_EQ(read[0].triangleCount(), read[1].triangleCount());
    auto box = [](const Context& c) {
        vec3 lo(1e30f), hi(-1e30f);
        for (ObjectID id : c.objectIDs())
            for (const vec3& p : c.object(id).positions) {
                lo = glm::min(lo, p);
                hi = glm::max(hi, p);
            }
        return std::pair{lo, hi};
    };
    const auto [lo0, hi0] = box(read[0]);
    const auto [lo1, hi1] = box(read[1]);
    EXPECT_LT(glm::length(lo0 - lo1) + glm::length(hi0 - hi1), 1e-5f);
}

// USD: a point instancer per plant only where shapes repeat; an empty scene and organs all of
// different shapes have none; the same bytes every time.
TEST(GpuInstancing, UsdHasAPointInstancerOnlyWhereShapesRepeat) {
    auto usda = [](const Context& ctx, const std::string& name) {
        const fs::path path = tempPath(name);
        UsdOptions options;
        options.nodes = NodeLevel::Organ;
        options.instancing = Instancing::Gpu;
        writeUSDA(ctx, path.string(), options);
        std::string text = readAll(path.string());
        fs::remove(path);
        return text;
    };
    Context empty;
    EXPECT_EQ(usda(empty, "empty.usda").find("PointInstancer"), std::string::npos);
    Context unique;
    addUniqueLeaves(unique);
    EXPECT_EQ(usda(unique, "unique.usda").find("PointInstancer"), std::string::npos);
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.setSeed(7);
    arch.loadPlantModelFromLibrary("bean");
    for (int i = 0; i < 2; ++i) arch.buildPlantInstanceFromLibrary(vec3(0.5f * float(i), 0, 0), 30);
    const std::string text = usda(ctx, "beans.usda");
    std::size_t instancers = 0;
    for (std::size_t at = text.find("def PointInstancer"); at != std::string::npos;
         at = text.find("def PointInstancer", at + 1))
        ++instancers;
    EXPECT_EQ(instancers, 2u);
    EXPECT_EQ(usda(ctx, "beans.usda"), text);
}

// A malformed EXT_mesh_gpu_instancing node is one line naming the file, the Context untouched.
TEST(GpuInstancing, ReadGltfRefusesMalformedInstances) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.setSeed(5);
    arch.loadPlantModelFromLibrary("bean");
    arch.buildPlantInstanceFromLibrary(vec3(0.0f), 30);
    const Glb g = written(ctx, "good.glb", Instancing::Gpu);
    auto glb = [](const json& doc, const std::string& bin) {
        std::string text = doc.dump();
        text.append((4 - text.size() % 4) % 4, ' ');
        auto u32 = [](std::uint32_t v) { return std::string(reinterpret_cast<char*>(&v), 4); };
        return u32(0x46546C67u) + u32(2) + u32(std::uint32_t(28 + text.size() + bin.size())) +
               u32(std::uint32_t(text.size())) + u32(0x4E4F534Au) + text +
               u32(std::uint32_t(bin.size())) + u32(0x004E4942u) + bin;
    };
    std::size_t node = 0;
    while (!g.doc["nodes"][node].contains("extensions")) ++node;
    const json attributes =
        g.doc["nodes"][node]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"];
    std::vector<std::pair<json, std::string>> bad;
    json doc = g.doc;
    doc["nodes"][node]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"]["ROTATION"] =
        attributes["SCALE"];  // a VEC3 as rotations
    bad.push_back({doc, "not of type VEC4"});
    doc = g.doc;
    doc["accessors"][attributes["SCALE"].get<std::size_t>()]["count"] = 1;
    bad.push_back({doc, "attributes of different counts"});
    doc = g.doc;
    doc["nodes"][node]["extensions"]["EXT_mesh_gpu_instancing"] = 7;
    bad.push_back({doc, "has no attributes"});
    const fs::path path = tempPath("bad.glb");
    for (const auto& [d, message] : bad) {
        { std::ofstream(path, std::ios::binary) << glb(d, g.bin); }
        Context read;
        try {
            readGLTF(read, path.string());
            ADD_FAILURE() << "read: " << message;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
            EXPECT_EQ(e.file(), path.string());
        }
        EXPECT_EQ(read.objectCount(), 0u);
    }
    fs::remove(path);
}
