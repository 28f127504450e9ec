// readPLY: plantarch's own PLY files read back as the objects and labels they were written
// from (ASCII and binary), other tools' PLY meshes, and hostile files refused with one line.

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "error_of.h"
#include "folder_test.h"
#include "object_corners.h"
#include "plantarch/Export.h"
#include "plantarch/PlantArchitecture.h"

using namespace plantarch;
using plantarch::testing::errorOf;
using plantarch::testing::objectCorners;

namespace {

class PlyReader : public FolderTest {
protected:
    PlyReader() : FolderTest("plantarch_ply_") {}
    std::string write(const std::string& name, const std::string& bytes) {
        put(at(name), bytes);
        return at(name);
    }
};

}  // namespace

// A bean written as PLY (binary and ASCII) reads back as its objects: the same triangles, the
// same plant, organ, leaf, shoot, rank and node labels.
TEST_F(PlyReader, PlantarchFilesReadBackAsTheirObjects) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    arch.buildPlantInstanceFromLibrary(vec3(0.0f), 30.0f);
    const std::vector<ObjectID> source = arch.getAllObjectIDs();
    for (PlyFormat format : {PlyFormat::BinaryLittleEndian, PlyFormat::Ascii}) {
        const std::string path = at(format == PlyFormat::Ascii ? "a.ply" : "b.ply");
        writePLY(ctx, path, {.format = format});
        Context back;
        const std::vector<ObjectID> ids = readPLY(back, path);
        ASSERT_EQ(ids.size(), source.size());
        for (std::size_t i = 0; i < ids.size(); ++i) {
            const std::vector<vec3> a = objectCorners(ctx, source[i]),
                                    b = objectCorners(back, ids[i]);
            ASSERT_EQ(a.size(), b.size());
            for (std::size_t k = 0; k < a.size(); ++k) EXPECT_LT(glm::length(a[k] - b[k]), 1e-6f);
            for (const char* label : {"plantID", "leafID", "shootID", "rank", "node"})
                EXPECT_EQ(ctx.objectDataInt(source[i], label), back.objectDataInt(ids[i], label))
                    << label;
            EXPECT_EQ(ctx.objectDataString(source[i], "organ"),
                      back.objectDataString(ids[i], "organ"));
        }
        Context plain;
        EXPECT_EQ(readPLY(plain, path, {.labels = false}).size(), 1u);
        // Vertex colours written as the materials' become the objects' material colours.
        writePLY(ctx, at("c.ply"), {.format = format, .color = PlyColor::Material});
        Context coloured;
        const std::vector<ObjectID> painted = readPLY(coloured, at("c.ply"));
        ASSERT_EQ(painted.size(), source.size());
        for (std::size_t i = 0; i < painted.size(); ++i) {
            const vec3 want = ctx.material(ctx.objectMaterial(source[i])).color;
            const vec3 got = coloured.material(coloured.objectMaterial(painted[i])).color;
            EXPECT_LT(glm::length(got - want), 0.01f);
        }
        EXPECT_EQ(plain.triangleCount(), ctx.triangleCount());
    }
}

// A mesh of another tool: big-endian doubles, a quad, normals and an edge element to skip.
TEST_F(PlyReader, OtherToolsMeshesWithQuadsAndExtraElements) {
    std::string body;
    auto be = [&](double v) {
        unsigned char b[8];
        std::memcpy(b, &v, 8);
        for (int i = 7; i >= 0; --i) body += char(b[i]);
    };
    const double quad[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    for (const auto& q : quad) {
        for (double c : q) be(c);
        for (double n : {0.0, 0.0, 1.0}) be(n);
    }
    body += char(4);
    for (int i : {0, 1, 2, 3}) body += std::string{0, 0, 0, char(i)};
    body += std::string{0, 0, 0, 0, 0, 0, 0, 1};  // the edge (int, int)
    const std::string path =
        write("scan.ply",
              "ply\nformat binary_big_endian 1.0\ncomment made elsewhere\nelement vertex 4\n"
              "property double x\nproperty double y\nproperty double z\nproperty double nx\n"
              "property double ny\nproperty double nz\nelement face 1\n"
              "property list uchar int vertex_indices\nelement edge 1\nproperty int vertex1\n"
              "property int vertex2\nend_header\n" +
                  body);
    Context ctx;
    const std::vector<ObjectID> ids = readPLY(ctx, path);
    ASSERT_EQ(ids.size(), 1u);
    EXPECT_EQ(ctx.triangleCount(), 2u);
    EXPECT_NEAR(ctx.objectArea(ids[0]), 1.0, 1e-9);

    Context obstacles;
    const std::vector<ObjectID> wall = readObstacleMesh(obstacles, path);
    EXPECT_EQ(obstacles.objectDataString(wall[0], "organ"), "obstacle");
    EXPECT_EQ(
        errorOf([&] { readObstacleMesh(obstacles, write("wall.stl", "solid")); }).validRange(),
        ".obj, .ply");
}

// A file whose label table numbers "unlabelled" otherwise (found by fuzz/fuzz_ply.cpp): that
// name means no organ data whatever its number, so the object writes back and reads again as
// it read (writePLY gives objects without organ data label 0, "unlabelled").
TEST_F(PlyReader, AnOrganLabelNamedUnlabelledGivesNoOrganDataWhateverItsNumber) {
    const std::string path = write(
        "relabelled.ply",
        "ply\nformat ascii 1.0\ncomment organ_label 1 unlabelled\ncomment organ_label 2 leaf\n"
        "element vertex 6\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 2\nproperty list uchar int vertex_indices\nproperty int object_id\n"
        "property int organ\nend_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 0 1\n0 1 1\n"
        "3 0 1 2 7 1\n3 3 4 5 8 2\n");
    Context ctx;
    const std::vector<ObjectID> ids = readPLY(ctx, path);
    ASSERT_EQ(ids.size(), 2u);
    EXPECT_FALSE(ctx.hasObjectData(ids[0], "organ"));
    EXPECT_EQ(ctx.objectDataString(ids[1], "organ"), "leaf");
    writePLY(ctx, at("again.ply"));
    Context again;
    const std::vector<ObjectID> back = readPLY(again, at("again.ply"));
    ASSERT_EQ(back.size(), 2u);
    EXPECT_FALSE(again.hasObjectData(back[0], "organ"));
    EXPECT_EQ(again.objectDataString(back[1], "organ"), "leaf");
}

// Hostile files: one clear error each, and the Context left as it was.
TEST_F(PlyReader, BadFilesAreRefusedAndLeaveTheContextUnchanged) {
    const std::string head =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
        "property float y\nproperty float z\nelement face 1\n"
        "property list uchar int vertex_indices\nend_header\n";
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"plyx\n", "not a PLY file"},
        {"ply\nformat ascii 1.0\nelement vertex 3\n", "no end_header"},
        {"ply\nformat ascii 2.0\nend_header\n", "bad PLY header line 2"},
        {"ply\nformat ascii 1.0\nelement vertex 99999999999999\nend_header\n",
         "bad PLY header line 3"},
        {"ply\nformat ascii 1.0\nproperty float x\nend_header\n", "bad PLY header line 3"},
        {head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n", "names vertex 7"},
        {head + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n", "has 2 corners"},
        {head + "0 0 0\n1 0 0\n0 1 nan\n3 0 1 2\n", "not a finite float"},
        {head + "0 0 0\n1 0 0\n0 1 zz\n3 0 1 2\n", "not a number"},
        {head + "0 0 0\n1 0 0\n0 1 1e300\n3 0 1 2\n", "not a finite float"},
        {head + "0 0 0\n1 0 0\n", "more than the rest of the file holds"},
        {head + "0 0 0\n1 0 0\n0 1 0\n3 0 1", "ends before its data"},
        {"ply\nformat binary_little_endian 1.0\nelement vertex 40\nproperty float x\n"
         "property float y\nproperty float z\nend_header\n" +
             std::string(64, '\0'),
         "vertex claims 40 items"},
        {"ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
         "property float z\nend_header\n",
         "no faces"},
    };
    Context ctx;
    ctx.addObject(Mesh{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {}, {0, 1, 2}});
    int i = 0;
    for (const auto& [bytes, message] : cases) {
        const std::string path = write("bad" + std::to_string(i++) + ".ply", bytes);
        const Error e = errorOf([&] { readPLY(ctx, path); });
        EXPECT_NE(std::string(e.what()).find(message), std::string::npos)
            << e.what() << "\n(expected: " << message << ")";
        EXPECT_EQ(e.file(), path);
        EXPECT_EQ(ctx.objectCount(), 1u);
    }
    // Not a regular file.
    EXPECT_NE(std::string(errorOf([&] { readPLY(ctx, "/dev/zero"); }).what()).find("device"),
              std::string::npos);
}
