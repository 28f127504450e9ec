// readGLTF: plantarch's own glTF and GLB files read back as the objects and labels they were
// written from, other tools' scenes (node transforms, y up), and hostile files refused.

#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "error_of.h"
#include "folder_test.h"
#include "object_corners.h"
#include "plantarch/Export.h"
#include "plantarch/ExportPlants.h"
#include "plantarch/PlantArchitecture.h"

using namespace plantarch;
using plantarch::testing::errorOf;
using plantarch::testing::objectCorners;

namespace {

class GltfReader : public FolderTest {
protected:
    GltfReader() : FolderTest("plantarch_gltf_") {}
    std::string write(const std::string& name, const std::string& bytes) {
        put(at(name), bytes);
        return at(name);
    }
};

// A .gltf of one triangle, its buffer embedded: three float positions (36 bytes).
std::string triangleGltf(const std::string& nodes, const std::string& extra = "") {
    return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":)" + nodes +
           R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
           R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}],)"
           R"("bufferViews":[{"buffer":0,"byteLength":36}],)"
           R"("buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,)"
           // (0,0,0), (1,0,0), (0,1,0) as little-endian floats
           R"(AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}])" +
           extra + "}";
}

}  // namespace

TEST_F(GltfReader, PlantarchFilesReadBackAsTheirObjects) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    arch.buildPlantInstanceFromLibrary(vec3(0.3f, -0.2f, 0.05f), 30.0f);
    const std::vector<ObjectID> source = arch.getAllObjectIDs();
    for (const char* name : {"bean.glb", "bean.gltf"}) {
        GltfOptions o;
        o.plants = exportPlants(arch);
        writeGLTF(ctx, at(name), o);
        Context back;
        const std::vector<ObjectID> ids = readGLTF(back, at(name));
        ASSERT_EQ(ids.size(), source.size()) << name;
        // Objects come back grouped by organ kind, as the file lays them out: match by label.
        std::map<int, ObjectID> byObject;
        for (ObjectID id : source) byObject[int(id)] = id;
        std::size_t matched = 0;
        for (ObjectID id : ids) {
            const auto organ = back.objectDataString(id, "organ");
            ASSERT_TRUE(organ.has_value());
            EXPECT_EQ(back.objectDataInt(id, "plantID"), std::optional<std::int32_t>(0));
            const std::vector<vec3> b = objectCorners(back, id);
            for (ObjectID s : source) {
                const std::vector<vec3> a = objectCorners(ctx, s);
                if (a.size() != b.size() || glm::length(a[0] - b[0]) > 1e-5f) continue;
                EXPECT_EQ(ctx.objectDataString(s, "organ"), organ);
                float worst = 0.0f;
                for (std::size_t k = 0; k < a.size(); ++k)
                    worst = std::max(worst, glm::length(a[k] - b[k]));
                EXPECT_LT(worst, 1e-5f);
                ++matched;
                break;
            }
        }
        EXPECT_EQ(matched, ids.size()) << name;
    }
}

// Another tool's scene: y up and a node transform (scale 2, then a translation).
// The writer groups objects by plant and organ kind; the reader puts them back in their
// _OBJECT_ID order, so a scene reads back in the order it had (found by fuzz/fuzz_gltf.cpp).
TEST_F(GltfReader, ObjectsComeBackInTheOrderTheyHad) {
    Context ctx;
    const Mesh triangle{{vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)}, {}, {0, 1, 2}};
    const char* organs[] = {"leaf", "", "internode", "leaf"};
    for (const char* organ : organs) {
        const ObjectID id = ctx.addObject(triangle);
        ctx.setObjectData(id, "plantID", std::int32_t(0));
        if (*organ) ctx.setObjectData(id, "organ", std::string(organ));
    }
    writeGLTF(ctx, at("order.glb"));
    Context back;
    const std::vector<ObjectID> ids = readGLTF(back, at("order.glb"));
    ASSERT_EQ(ids.size(), 4u);
    for (std::size_t i = 0; i < ids.size(); ++i)
        EXPECT_EQ(back.hasObjectData(ids[i], "organ") ? back.objectDataString(ids[i], "organ")
                                                      : std::string(),
                  organs[i])
            << "object " << i;
}

TEST_F(GltfReader, NodeTransformsAndYUp) {
    const std::string path =
        write("t.gltf", triangleGltf(R"([{"mesh":0,"translation":[1,2,3],"scale":[2,2,2]}])"));
    Context ctx;
    const std::vector<ObjectID> ids = readGLTF(ctx, path);
    ASSERT_EQ(ids.size(), 1u);
    const std::vector<vec3> c = objectCorners(ctx, ids[0]);
    // glTF (x, y, z) -> plantarch (x, -z, y)
    EXPECT_EQ(c[0], vec3(1, -3, 2));
    EXPECT_EQ(c[1], vec3(3, -3, 2));
    EXPECT_EQ(c[2], vec3(1, -3, 4));
}

TEST_F(GltfReader, BadFilesAreRefusedAndLeaveTheContextUnchanged) {
    std::string deep = R"({"asset":)";
    for (int i = 0; i < 100; ++i) deep += "[";
    const std::vector<std::pair<std::string, std::pair<std::string, std::string>>> cases = {
        {"a.glb", {"glTX0000000000000000", "not a binary glTF"}},
        {"b.glb", {std::string("glTF\1\0\0\0\24\0\0\0\0\0\0\0JSON", 20), "glTF version 1"}},
        {"c.gltf", {"{\"asset\": ", "not JSON"}},
        {"d.gltf", {deep, "nested too deeply"}},
        {"e.gltf", {triangleGltf("[{\"children\":[0]}]"), "cycle"}},
        {"f.gltf",
         {triangleGltf("[{\"mesh\":0}]")
              .replace(triangleGltf("[{\"mesh\":0}]").find("\"count\":3"), 9, "\"count\":4"),
          "reaches past"}},
        {"g.gltf",
         {triangleGltf("[{\"mesh\":0}]")
              .replace(triangleGltf("[{\"mesh\":0}]").find("data:"), 5, "x.bin#"),
          "separate file"}},
        {"h.gltf", {triangleGltf("[{\"mesh\":5}]"), "out of range"}},
        {"i.gltf", {R"({"asset":{"version":"2.0"}})", "no triangles"}},
    };
    Context ctx;
    ctx.addObject(Mesh{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {}, {0, 1, 2}});
    for (const auto& [name, content] : cases) {
        const auto& [bytes, message] = content;
        const std::string path = write(name, bytes);
        const Error e = errorOf([&] { readGLTF(ctx, path); });
        EXPECT_NE(std::string(e.what()).find(message), std::string::npos)
            << name << ": " << e.what() << "\n(expected: " << message << ")";
        EXPECT_EQ(e.file(), path);
        EXPECT_EQ(ctx.objectCount(), 1u);
    }
    EXPECT_EQ(errorOf([&] { readGLTF(ctx, write("x.obj", "v 0 0 0")); }).validRange(),
              ".glb, .gltf");
}
