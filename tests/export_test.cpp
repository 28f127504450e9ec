// Exporters and the OBJ reader: OBJ/MTL and PLY written then read back and compared,
// byte-for-byte determinism, atomic writes (failures leave no file and never damage an
// existing one), per-object split, and readOBJ's errors.

#include "plantarch/Export.h"

#include <gtest/gtest.h>
#include <omp.h>
#include <sys/resource.h>

#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "plantarch/Context.h"
#include "plantarch/Error.h"
#include "ply_reader.h"
#include "scene_io/export_common.h"

using namespace plantarch;
namespace fs = std::filesystem;

namespace {

// ---- helpers ---------------------------------------------------------------------------

// A leaf-like grid of nx*ny quads (2*nx*ny triangles), optionally with UVs.
Mesh grid(int nx, int ny, bool withUVs, float size = 0.1f) {
    Mesh m;
    for (int j = 0; j <= ny; ++j)
        for (int i = 0; i <= nx; ++i) {
            const float u = float(i) / float(nx), v = float(j) / float(ny);
            m.positions.push_back({size * u, 0.4f * size * (v - 0.5f), 0.1f * size * u * u});
            if (withUVs) m.uvs.push_back({u, v});
        }
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const std::uint32_t a = j * (nx + 1) + i, b = a + 1, c = a + nx + 1, d = c + 1;
            m.indices.insert(m.indices.end(), {a, b, d, a, d, c});
        }
    return m;
}

// Objects covering what the writers must handle: colours, a texture with UVs, a hidden
// object, plant and organ data (standard, unknown and missing organ names).
struct Scene {
    Context ctx;
    ObjectID leaf, textured, hidden, bare, odd1, odd2;
};

void buildScene(Scene& s) {
    Context& c = s.ctx;
    const MaterialID green = c.addMaterial({.color = {0.2f, 0.6f, 0.1f}, .name = "leaf green"});
    const MaterialID tex =
        c.addMaterial({.color = {1.0f, 1.0f, 1.0f}, .texture = "textures/leaf.png"});
    const MaterialID red = c.addMaterial({.color = {0.9f, 0.1f, 0.1f}});
    s.leaf = c.addObject(grid(4, 3, false), green);
    c.setObjectData(s.leaf, "organ", std::string("leaf"));
    c.setObjectData(s.leaf, "plantID", 0);
    s.textured = c.addObject(grid(2, 2, true), tex);
    c.transformObject(s.textured, glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, -2.5f, 0.3f)));
    c.setObjectData(s.textured, "organ", std::string("petiole"));
    c.setObjectData(s.textured, "plantID", 1);
    s.hidden = c.addObject(grid(1, 1, false), red);
    c.setObjectData(s.hidden, "organ", std::string("fruit"));
    c.setObjectData(s.hidden, "plantID", 1);
    c.setObjectHidden(s.hidden, true);
    s.bare = c.addObject(grid(3, 1, false));  // default material, no data
    s.odd1 = c.addObject(grid(1, 2, false), red);
    c.setObjectData(s.odd1, "organ", std::string("weird organ"));
    s.odd2 = c.addObject(grid(2, 1, false), green);
    c.setObjectData(s.odd2, "organ", std::string("aardvark"));
    c.setObjectData(s.odd2, "plantID", 7);
}

std::string readBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeText(const fs::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

std::vector<std::string> filesIn(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename());
    std::sort(names.begin(), names.end());
    return names;
}

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

// A fresh directory per test, removed afterwards.
class ExportTest : public ::testing::Test {
protected:
    void SetUp() override {
        std::string pattern = (fs::temp_directory_path() / "plantarch-export-XXXXXX").string();
        ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
        dir_ = pattern;
    }
    void TearDown() override { fs::remove_all(dir_); }
    fs::path dir_;
};

// ---- PLY files as the tests look at them (tests/ply_reader.h) ----------------------------

struct Ply {
    bool binary = false;
    std::vector<std::string> comments;
    std::vector<std::string> vertexProperties;
    std::vector<float> vertices;  // vertexProperties.size() floats per vertex
    std::vector<std::array<int, 3>> faces;
    std::vector<int> plant, object, organ;
};

Ply readPLY(const fs::path& path) {
    const plantarch::testing::PlyData data = plantarch::testing::readPlyFile(path.string());
    Ply ply;
    ply.binary = data.binary;
    ply.comments = data.comments;
    ply.faces = data.faces;
    for (const auto& p : data.vertexProperties) {
        EXPECT_EQ(p.type, "float");
        ply.vertexProperties.push_back(p.name);
    }
    const std::size_t n = ply.vertexProperties.size();
    const std::size_t count = n ? data.vertex.at(ply.vertexProperties[0]).size() : 0;
    ply.vertices.resize(count * n);
    for (std::size_t v = 0; v < count; ++v)
        for (std::size_t k = 0; k < n; ++k)
            ply.vertices[v * n + k] = float(data.vertex.at(ply.vertexProperties[k])[v]);
    auto column = [&](const char* name, std::vector<int>& out) {
        EXPECT_TRUE(data.face.count(name)) << name;
        if (data.face.count(name))
            for (double x : data.face.at(name)) out.push_back(int(x));
    };
    column("plant_id", ply.plant);
    column("object_id", ply.object);
    column("organ", ply.organ);
    return ply;
}

// ---- OBJ -------------------------------------------------------------------------------

TEST_F(ExportTest, ObjRoundTripKeepsPositionsTrianglesColoursAndUVs) {
    Scene s;
    buildScene(s);
    fs::create_directory(dir_ / "out");
    const std::string path = (dir_ / "out" / "scene.obj").string();
    writeOBJ(s.ctx, path);
    EXPECT_EQ(filesIn(dir_ / "out"), (std::vector<std::string>{"scene.mtl", "scene.obj"}));

    Context back;
    const std::vector<ObjectID> ids = readOBJ(back, path);
    const std::vector<ObjectID> visible = {s.leaf, s.textured, s.bare, s.odd1, s.odd2};
    ASSERT_EQ(ids.size(), visible.size());
    for (std::size_t i = 0; i < ids.size(); ++i) {
        const ObjectView a = s.ctx.object(visible[i]);
        const ObjectView b = back.object(ids[i]);
        ASSERT_EQ(a.triangleCount(), b.triangleCount()) << "object " << i;
        for (std::size_t k = 0; k < a.indices.size(); ++k) {
            const vec3 pa = a.positions[a.indices[k]], pb = b.positions[b.indices[k]];
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(pa[c], pb[c], 1e-6f);
        }
        EXPECT_EQ(a.uvs.empty(), b.uvs.empty());
        if (!a.uvs.empty())
            for (std::size_t k = 0; k < a.indices.size(); ++k) {
                EXPECT_NEAR(a.uvs[a.indices[k]].x, b.uvs[b.indices[k]].x, 1e-6f);
                EXPECT_NEAR(a.uvs[a.indices[k]].y, b.uvs[b.indices[k]].y, 1e-6f);
            }
        const Material& ma = s.ctx.material(a.material);
        const Material& mb = back.material(b.material);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(ma.color[c], mb.color[c], 1e-6f);
        // The .mtl names the texture relative to itself; reading resolves it back.
        EXPECT_EQ(ma.texture.empty(), mb.texture.empty());
        if (!ma.texture.empty()) {
            EXPECT_EQ(fs::absolute(ma.texture).lexically_normal(),
                      fs::absolute(mb.texture).lexically_normal());
        }
    }
    EXPECT_EQ(back.objectDataString(ids[0], "name"), "obj0_plant0_leaf");
    EXPECT_EQ(back.objectDataString(ids[3], "name"), "obj4_weird_organ");
    EXPECT_EQ(back.material(back.object(ids[0]).material).name, "leaf_green");
}

TEST_F(ExportTest, ObjTextLayoutForOneQuad) {
    Context c;
    Mesh quad;
    quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    quad.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    quad.indices = {0, 1, 2, 0, 2, 3};
    const ObjectID id = c.addObject(quad, Material{.color = {0.25f, 0.5f, 0.1f}, .name = "m"});
    c.setObjectData(id, "organ", std::string("leaf"));
    writeOBJ(c, (dir_ / "quad.obj").string());
    EXPECT_EQ(readBytes(dir_ / "quad.obj"),
              "# plantarch OBJ: 1 objects, 2 triangles\n"
              "mtllib quad.mtl\n"
              "o obj0_leaf\ng obj0_leaf\n# plantarch labels object=0 organ=leaf\nusemtl m\n"
              "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
              "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
              "vn 0 0 1\nvn 0 0 1\nvn 0 0 1\nvn 0 0 1\n"
              "f 1/1/1 2/2/2 3/3/3\nf 1/1/1 3/3/3 4/4/4\n");
    EXPECT_EQ(readBytes(dir_ / "quad.mtl"),
              "# plantarch material library\n\n"
              "newmtl m\nKa 0 0 0\nKd 0.25 0.5 0.1\nKs 0 0 0\nd 1\nillum 1\n");

    writeOBJ(c, (dir_ / "plain.obj").string(),
             {.normals = false, .uvs = false, .materials = false});
    EXPECT_EQ(readBytes(dir_ / "plain.obj"),
              "# plantarch OBJ: 1 objects, 2 triangles\n"
              "o obj0_leaf\ng obj0_leaf\n# plantarch labels object=0 organ=leaf\n"
              "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
              "f 1 2 3\nf 1 3 4\n");
    EXPECT_FALSE(fs::exists(dir_ / "plain.mtl"));

    writeOBJ(c, (dir_ / "normals.obj").string(), {.uvs = false, .materials = false});
    EXPECT_TRUE(contains(readBytes(dir_ / "normals.obj"), "f 1//1 2//2 3//3\n"));
}

TEST_F(ExportTest, ObjMaterialLibraryHasTexturesRelativeToItself) {
    Scene s;
    buildScene(s);
    fs::create_directory(dir_ / "out");
    writeOBJ(s.ctx, (dir_ / "out" / "scene.obj").string());
    const std::string mtl = readBytes(dir_ / "out" / "scene.mtl");
    const std::string relative =
        fs::absolute("textures/leaf.png").lexically_relative(fs::absolute(dir_ / "out"));
    EXPECT_TRUE(contains(mtl, "map_Kd " + relative + "\n")) << mtl;
    EXPECT_TRUE(contains(mtl, "newmtl leaf_green\n"));
    EXPECT_TRUE(contains(mtl, "newmtl material0\n"));  // the default material, used by `bare`
    const std::string obj = readBytes(dir_ / "out" / "scene.obj");
    EXPECT_TRUE(contains(obj, "# plantarch OBJ: 5 objects, "));
    EXPECT_FALSE(contains(obj, "fruit"));  // hidden
}

TEST_F(ExportTest, ObjHiddenObjectsOnlyWhenAsked) {
    Scene s;
    buildScene(s);
    const std::string path = (dir_ / "all.obj").string();
    writeOBJ(s.ctx, path, {.includeHidden = true});
    Context back;
    EXPECT_EQ(readOBJ(back, path).size(), 6u);
    EXPECT_TRUE(contains(readBytes(path), "o obj2_plant1_fruit\n"));
}

TEST_F(ExportTest, ObjNormalsAreAreaWeighted) {
    // Vertex 0 is shared by a triangle of area 1 facing +z and one of area 0.5 facing +y.
    Mesh m;
    m.positions = {{0, 0, 0}, {2, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 0}};
    m.indices = {0, 1, 2, 0, 3, 4};
    Context c;
    c.addObject(m);
    writeOBJ(c, (dir_ / "n.obj").string(), {.materials = false});
    std::istringstream text(readBytes(dir_ / "n.obj"));
    std::string line;
    while (std::getline(text, line) && line.rfind("vn ", 0) != 0) {
    }
    std::istringstream first(line.substr(3));
    vec3 n;
    first >> n.x >> n.y >> n.z;
    const vec3 expected = glm::normalize(vec3(0.0f, 1.0f, 2.0f));
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(n[k], expected[k], 1e-6f);
}

TEST(ExportFormat, FixedSixDecimals) {
    auto text = [](float v) {
        char buffer[32];
        return std::string(buffer, io::writeFixed6(buffer, v));
    };
    EXPECT_EQ(text(0.70710678f), "0.707107");
    EXPECT_EQ(text(-1.0f), "-1");
    EXPECT_EQ(text(1.0f), "1");
    EXPECT_EQ(text(0.0f), "0");
    EXPECT_EQ(text(-0.0f), "0");
    EXPECT_EQ(text(-4e-7f), "0");  // rounds to zero: no "-0"
    EXPECT_EQ(text(0.1f), "0.1");
    EXPECT_EQ(text(-0.000123f), "-0.000123");
    EXPECT_EQ(text(12.25f), "12.25");
}

TEST_F(ExportTest, ObjSplitPerObjectWritesOneFilePerObject) {
    Scene s;
    buildScene(s);
    const fs::path out = dir_ / "parts" / "plant";  // created with its parent
    writeOBJ(s.ctx, out.string(), {.splitPerObject = true});
    EXPECT_EQ(filesIn(out), (std::vector<std::string>{
                                "materials.mtl", "obj0_plant0_leaf.obj", "obj1_plant1_petiole.obj",
                                "obj3.obj", "obj4_weird_organ.obj", "obj5_plant7_aardvark.obj"}));
    const std::vector<ObjectID> visible = {s.leaf, s.textured, s.bare, s.odd1, s.odd2};
    const std::vector<std::string> files = filesIn(out);
    for (std::size_t i = 0; i < visible.size(); ++i) {
        const ObjectID id = visible[i];
        Context back;
        const fs::path file = out / files[i + 1];  // same order as the IDs
        const std::vector<ObjectID> ids = readOBJ(back, file.string());
        ASSERT_EQ(ids.size(), 1u) << file;
        EXPECT_EQ(back.object(ids[0]).triangleCount(), s.ctx.object(id).triangleCount());
        EXPECT_EQ(back.object(ids[0]).positions.size(), s.ctx.object(id).positions.size());
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(back.material(back.objectMaterial(ids[0])).color[c],
                        s.ctx.material(s.ctx.objectMaterial(id)).color[c], 1e-6f);
    }
}

// The OBJ body is formatted in chunks of objects on all threads and written in order: the
// file must not depend on the thread count, and the vertex and UV numbers must run on across
// chunks (objects with and without UVs mixed, so the two numberings differ).
TEST_F(ExportTest, ObjSameBytesOnAnyThreadCountAndNumbersRunAcrossChunks) {
    Context c;
    const MaterialID green = c.addMaterial({.color = {0.2f, 0.6f, 0.1f}, .name = "leaf"});
    for (int i = 0; i < 700; ++i) {  // some 400,000 lines: several chunks
        Mesh m = grid(12, 8, i % 3 != 0, 0.05f + 0.001f * float(i));
        for (vec3& v : m.positions) v += vec3(0.37f * float(i % 17), 0.11f * float(i), 0.0f);
        const ObjectID id = c.addObject(m, green);
        if (i % 5) c.setObjectData(id, "organ", std::string(i % 2 ? "leaf" : "petiole"));
    }
    const int threads = omp_get_max_threads();
    for (const ObjOptions& options : {ObjOptions{}, ObjOptions{.normals = false}}) {
        std::string first;
        for (int n : {1, 2, 3}) {
            omp_set_num_threads(n);
            fs::create_directories(dir_ / std::to_string(n));  // the same names: same mtllib
            const fs::path file = dir_ / std::to_string(n) / "t.obj";
            writeOBJ(c, file.string(), options);
            const std::string bytes = readBytes(file);
            if (n == 1)
                first = bytes;
            else
                EXPECT_TRUE(bytes == first) << n << " threads, normals " << options.normals;
        }
        omp_set_num_threads(threads);

        Context back;
        const std::vector<ObjectID> ids = readOBJ(back, (dir_ / "2" / "t.obj").string());
        ASSERT_EQ(ids.size(), c.objectCount());
        for (std::size_t k = 0; k < ids.size(); ++k) {
            const ObjectView a = c.object(ObjectID(k)), b = back.object(ids[k]);
            ASSERT_EQ(b.triangleCount(), a.triangleCount()) << k;
            ASSERT_EQ(b.uvs.empty(), a.uvs.empty()) << k;
            for (std::size_t i = 0; i < a.indices.size(); ++i) {
                EXPECT_EQ(b.positions[b.indices[i]], a.positions[a.indices[i]]) << k;
                if (!a.uvs.empty()) {
                    EXPECT_EQ(b.uvs[b.indices[i]], a.uvs[a.indices[i]]) << k;
                }
            }
        }
    }
}

TEST_F(ExportTest, WritersAreDeterministic) {
    Scene s;
    buildScene(s);
    for (const char* sub : {"a", "b"}) {
        fs::create_directory(dir_ / sub);
        writeOBJ(s.ctx, (dir_ / sub / "scene.obj").string());
        writePLY(s.ctx, (dir_ / sub / "scene.ply").string());
        writePLY(s.ctx, (dir_ / sub / "ascii.ply").string(), {.format = PlyFormat::Ascii});
    }
    Scene again;  // an equal scene built anew gives the same bytes too
    buildScene(again);
    fs::create_directory(dir_ / "c");
    writeOBJ(again.ctx, (dir_ / "c" / "scene.obj").string());
    writePLY(again.ctx, (dir_ / "c" / "scene.ply").string());
    writePLY(again.ctx, (dir_ / "c" / "ascii.ply").string(), {.format = PlyFormat::Ascii});
    for (const char* file : {"scene.obj", "scene.mtl", "scene.ply", "ascii.ply"}) {
        const std::string a = readBytes(dir_ / "a" / file);
        EXPECT_FALSE(a.empty()) << file;
        EXPECT_EQ(a, readBytes(dir_ / "b" / file)) << file;
        EXPECT_EQ(a, readBytes(dir_ / "c" / file)) << file;
    }
}

// ---- PLY -------------------------------------------------------------------------------

void checkPlyMatchesScene(const Ply& ply, const Scene& s, bool normals) {
    const std::vector<ObjectID> visible = {s.leaf, s.textured, s.bare, s.odd1, s.odd2};
    const std::vector<int> plant = {0, 1, -1, -1, 7};
    const std::vector<int> organ = {3, 2, 0, 11, 10};  // aardvark 10, weird organ 11
    ASSERT_EQ(ply.vertexProperties.size(), normals ? 6u : 3u);
    std::size_t vertices = 0, faces = 0;
    for (ObjectID id : visible) {
        vertices += s.ctx.object(id).positions.size();
        faces += s.ctx.object(id).triangleCount();
    }
    ASSERT_EQ(ply.vertices.size(), vertices * ply.vertexProperties.size());
    ASSERT_EQ(ply.faces.size(), faces);
    const std::size_t stride = ply.vertexProperties.size();
    std::size_t face = 0;
    for (std::size_t i = 0; i < visible.size(); ++i) {
        const ObjectView o = s.ctx.object(visible[i]);
        for (std::size_t t = 0; t < o.triangleCount(); ++t, ++face) {
            EXPECT_EQ(ply.plant[face], plant[i]);
            EXPECT_EQ(ply.object[face], int(visible[i]));
            EXPECT_EQ(ply.organ[face], organ[i]);
            for (int k = 0; k < 3; ++k) {
                const vec3 expected = o.positions[o.indices[3 * t + k]];
                const float* got = &ply.vertices[std::size_t(ply.faces[face][k]) * stride];
                EXPECT_EQ(got[0], expected.x);  // exact: binary copy or shortest round-trip
                EXPECT_EQ(got[1], expected.y);
                EXPECT_EQ(got[2], expected.z);
                if (normals) {
                    EXPECT_NEAR(glm::length(vec3(got[3], got[4], got[5])), 1.0f, 1e-5f);
                }
            }
        }
    }
}

TEST_F(ExportTest, PlyBinaryHasLabelsAndCoordinates) {
    Scene s;
    buildScene(s);
    const fs::path path = dir_ / "scene.ply";
    writePLY(s.ctx, path.string());
    const Ply ply = readPLY(path);
    EXPECT_TRUE(ply.binary);
    checkPlyMatchesScene(ply, s, false);
    std::vector<std::string> labels;
    for (const std::string& c : ply.comments)
        if (c.rfind("organ_label ", 0) == 0) labels.push_back(c);
    EXPECT_EQ(labels, (std::vector<std::string>{
                          "organ_label 0 unlabelled", "organ_label 1 internode",
                          "organ_label 2 petiole", "organ_label 3 leaf", "organ_label 4 peduncle",
                          "organ_label 5 flower_closed", "organ_label 6 flower_open",
                          "organ_label 7 fruit", "organ_label 8 ground", "organ_label 9 obstacle",
                          "organ_label 10 aardvark", "organ_label 11 weird organ"}));
    const std::string header = readBytes(path).substr(0, 1200);
    EXPECT_TRUE(contains(header,
                         "property list uchar int vertex_indices\n"
                         "property int plant_id\nproperty int object_id\n"
                         "property int organ\nproperty int leaf_id\nproperty int shoot_id\n"
                         "property int rank\nproperty int node\nproperty float age\n"
                         "end_header\n"));
}

TEST_F(ExportTest, PlyAsciiMatchesBinary) {
    Scene s;
    buildScene(s);
    writePLY(s.ctx, (dir_ / "a.ply").string(), {.format = PlyFormat::Ascii, .normals = true});
    writePLY(s.ctx, (dir_ / "b.ply").string(), {.normals = true});
    const Ply ascii = readPLY(dir_ / "a.ply"), binary = readPLY(dir_ / "b.ply");
    EXPECT_FALSE(ascii.binary);
    checkPlyMatchesScene(ascii, s, true);
    checkPlyMatchesScene(binary, s, true);
    // Positions are exact in both; ASCII normals have 6 decimals.
    ASSERT_EQ(ascii.vertices.size(), binary.vertices.size());
    for (std::size_t i = 0; i < ascii.vertices.size(); ++i) {
        if (i % 6 < 3) {
            EXPECT_EQ(ascii.vertices[i], binary.vertices[i]);
        } else {
            EXPECT_NEAR(ascii.vertices[i], binary.vertices[i], 6e-7f);
        }
    }
    EXPECT_EQ(ascii.faces, binary.faces);
    EXPECT_EQ(ascii.comments, binary.comments);
    EXPECT_EQ(ascii.vertexProperties, (std::vector<std::string>{"x", "y", "z", "nx", "ny", "nz"}));
}

TEST_F(ExportTest, PlyHiddenObjectsOnlyWhenAsked) {
    Scene s;
    buildScene(s);
    writePLY(s.ctx, (dir_ / "all.ply").string(), {.includeHidden = true});
    const Ply ply = readPLY(dir_ / "all.ply");
    EXPECT_EQ(ply.faces.size(), s.ctx.triangleCount());
    EXPECT_NE(std::find(ply.organ.begin(), ply.organ.end(), 7), ply.organ.end());  // fruit
}

TEST_F(ExportTest, OrganLabelTableListsStandardThenSortedExtras) {
    Scene s;
    buildScene(s);
    const std::vector<std::string> table = organLabelTable(s.ctx);
    ASSERT_EQ(table.size(), 12u);
    EXPECT_EQ(table[0], "unlabelled");
    EXPECT_EQ(table[9], "obstacle");
    EXPECT_EQ(table[10], "aardvark");
    EXPECT_EQ(table[11], "weird organ");
    Context empty;
    EXPECT_EQ(organLabelTable(empty).size(), kOrganLabels.size());
}

TEST_F(ExportTest, WrongDataTypesAreErrors) {
    Context c;
    const ObjectID id = c.addObject(grid(1, 1, false));
    c.setObjectData(id, "plantID", std::string("three"));
    const std::string path = (dir_ / "x.ply").string();
    try {
        writePLY(c, path);
        FAIL() << "expected an Error";
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), path);
        EXPECT_EQ(e.parameter(), "plantID");
    }
    Context d;
    d.setObjectData(d.addObject(grid(1, 1, false)), "organ", 3);
    EXPECT_THROW(writeOBJ(d, (dir_ / "x.obj").string()), Error);
    EXPECT_TRUE(fs::is_empty(dir_));
}

// ---- atomic writes ---------------------------------------------------------------------

TEST_F(ExportTest, MissingDirectoryGivesErrorNamingTheFile) {
    Scene s;
    buildScene(s);
    for (const std::string& name : {std::string("scene.obj"), std::string("scene.ply")}) {
        const std::string path = (dir_ / "missing" / name).string();
        try {
            if (name.ends_with(".obj"))
                writeOBJ(s.ctx, path);
            else
                writePLY(s.ctx, path);
            FAIL() << "expected an Error for " << path;
        } catch (const Error& e) {
            EXPECT_EQ(e.file(), path);
            EXPECT_TRUE(contains(e.what(), "cannot open for writing: No such file or directory"))
                << e.what();
        }
    }
    // A path through a regular file cannot be created either.
    writeText(dir_ / "file", "x");
    EXPECT_THROW(writePLY(s.ctx, (dir_ / "file" / "scene.ply").string()), Error);
    EXPECT_THROW(writeOBJ(s.ctx, (dir_ / "file" / "split").string(), {.splitPerObject = true}),
                 Error);
    EXPECT_EQ(filesIn(dir_), std::vector<std::string>{"file"});
}

TEST_F(ExportTest, SuccessfulWriteReplacesExistingFile) {
    Scene s;
    buildScene(s);
    writeText(dir_ / "scene.obj", "old");
    writeText(dir_ / "scene.ply", "old");
    writeOBJ(s.ctx, (dir_ / "scene.obj").string());
    writePLY(s.ctx, (dir_ / "scene.ply").string());
    EXPECT_TRUE(readBytes(dir_ / "scene.obj").starts_with("# plantarch OBJ"));
    EXPECT_TRUE(readBytes(dir_ / "scene.ply").starts_with("ply\n"));
    EXPECT_EQ(filesIn(dir_), (std::vector<std::string>{"scene.mtl", "scene.obj", "scene.ply"}));
}

// Runs `f` with the process's file size limit lowered, so that writes fail part-way
// (EFBIG) exactly as a full disk would.
template <class F>
void withFileSizeLimit(rlim_t bytes, F&& f) {
    rlimit old{};
    ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
    const auto oldHandler = std::signal(SIGXFSZ, SIG_IGN);
    rlimit low = old;
    low.rlim_cur = bytes;
    ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &low), 0);
    try {
        f();
    } catch (...) {
        ::setrlimit(RLIMIT_FSIZE, &old);
        std::signal(SIGXFSZ, oldHandler);
        throw;
    }
    ::setrlimit(RLIMIT_FSIZE, &old);
    std::signal(SIGXFSZ, oldHandler);
}

TEST_F(ExportTest, FailedWriteLeavesExistingFileUntouchedAndNoTemporaries) {
    Context big;  // several MB of OBJ, far over the limit below
    const Mesh leaf = grid(10, 5, true);
    for (int i = 0; i < 2000; ++i) {
        const ObjectID id = big.addObject(leaf);
        big.setObjectData(id, "organ", std::string("leaf"));
    }
    writeText(dir_ / "scene.obj", "old obj");
    writeText(dir_ / "scene.mtl", "old mtl");
    writeText(dir_ / "scene.ply", "old ply");
    fs::create_directory(dir_ / "split");
    std::vector<std::string> errors;
    withFileSizeLimit(64 * 1024, [&] {
        try {
            writeOBJ(big, (dir_ / "scene.obj").string());
        } catch (const Error& e) {
            errors.push_back(e.what());
        }
        try {
            writePLY(big, (dir_ / "scene.ply").string(), {.format = PlyFormat::Ascii});
        } catch (const Error& e) {
            errors.push_back(e.what());
        }
        try {  // the limit hits the last object's file, after the first ones are finished
            Context lastBig;
            lastBig.addObject(grid(1, 1, true));
            lastBig.addObject(grid(2, 1, true));
            lastBig.addObject(grid(100, 50, true));
            writeOBJ(lastBig, (dir_ / "split").string(), {.splitPerObject = true});
        } catch (const Error& e) {
            errors.push_back(e.what());
        }
    });
    ASSERT_EQ(errors.size(), 3u);
    EXPECT_TRUE(contains(errors[0], "scene.obj: cannot write: File too large")) << errors[0];
    EXPECT_TRUE(contains(errors[1], "scene.ply: cannot write: File too large")) << errors[1];
    EXPECT_EQ(readBytes(dir_ / "scene.obj"), "old obj");
    EXPECT_EQ(readBytes(dir_ / "scene.mtl"), "old mtl");
    EXPECT_EQ(readBytes(dir_ / "scene.ply"), "old ply");
    EXPECT_EQ(filesIn(dir_),
              (std::vector<std::string>{"scene.mtl", "scene.obj", "scene.ply", "split"}));
    EXPECT_TRUE(fs::is_empty(dir_ / "split"));
}

TEST_F(ExportTest, AtomicFileWritesBuffersAndCleansUp) {
    const std::string path = (dir_ / "f.bin").string();
    {
        io::AtomicFile f(path, 16);        // tiny buffer: every path through write() is taken
        EXPECT_EQ(f.temporaryPath(), "");  // unnamed: nothing in the folder while writing
        f.write("hello ");
        const std::string large(100000, 'x');
        f.write(large);
        char* p = f.reserve(3);
        std::memcpy(p, "end", 3);
        f.advance(p + 3);
        EXPECT_EQ(f.size(), 6u + large.size() + 3u);
        EXPECT_FALSE(fs::exists(path));  // nothing visible before commit
        f.finish();
        EXPECT_EQ(filesIn(dir_), std::vector<std::string>{});
        f.commit();
    }
    EXPECT_EQ(readBytes(path), "hello " + std::string(100000, 'x') + "end");
    {
        io::AtomicFile abandoned(path);
        abandoned.write("new");
        abandoned.finish();
    }  // destroyed without commit
    EXPECT_EQ(readBytes(path).size(), 100009u);
    EXPECT_EQ(filesIn(dir_), std::vector<std::string>{"f.bin"});
    {
        // A stale temporary with the next name (left by a killed process) is stepped over.
        ::setenv("PLANTARCH_NAMED_TEMPORARIES", "1", 1);
        io::AtomicFile probe(path);
        ::unsetenv("PLANTARCH_NAMED_TEMPORARIES");
        ASSERT_TRUE(probe.temporaryPath().starts_with(path + ".tmp-"));
        const std::string used = probe.temporaryPath();
        const std::string counter = used.substr(used.rfind('-') + 1);
        const std::string next =
            used.substr(0, used.rfind('-') + 1) + std::to_string(std::stoul(counter) + 1);
        writeText(next, "stale");
        ::setenv("PLANTARCH_NAMED_TEMPORARIES", "1", 1);
        io::AtomicFile f(path);
        ::unsetenv("PLANTARCH_NAMED_TEMPORARIES");
        EXPECT_NE(f.temporaryPath(), "");
        EXPECT_NE(f.temporaryPath(), next);
        f.write("fresh");
        f.commit();
        fs::remove(next);
    }
    EXPECT_EQ(readBytes(path), "fresh");
    EXPECT_EQ(filesIn(dir_), std::vector<std::string>{"f.bin"});
}

// ---- readOBJ errors and features -------------------------------------------------------

TEST_F(ExportTest, ReadObjMissingFileIsError) {
    Context c;
    const std::string path = (dir_ / "nope.obj").string();
    try {
        readOBJ(c, path);
        FAIL() << "expected an Error";
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), path);
        EXPECT_TRUE(contains(e.what(), "cannot open OBJ file: No such file or directory"))
            << e.what();
    }
}

TEST_F(ExportTest, ReadObjMalformedFilesAreErrorsAndLeaveContextUnchanged) {
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n"},
        {"uv.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/5\n"},
        {"nofaces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"},
        {"empty.obj", ""},
        {"text.obj", "this is not\nan OBJ file at all\n"},
        {"nan.obj", "v 0 0 0\nv nan 1 0\nv 0 1 0\nf 1 2 3\n"},
        {"inf.obj", "v 0 0 0\nv 1 0 0\nv 0 1 -inf\nf 1 2 3\n"},
        {"word.obj", "v 0 0 0\nv 1 0 0\nv 0 1x 0\nf 1 2 3\n"},
    };
    for (const auto& [name, text] : cases) {
        writeText(dir_ / name, text);
        Context c;
        c.addObject(grid(1, 1, false));
        const std::string path = (dir_ / name).string();
        try {
            readOBJ(c, path);
            ADD_FAILURE() << "expected an Error for " << name;
        } catch (const Error& e) {
            EXPECT_EQ(e.file(), path);
            if (name == "index.obj") {
                EXPECT_TRUE(contains(e.what(), ":5: f = 9: vertex index out of range")) << e.what();
            }
            if (name == "nofaces.obj") {
                EXPECT_TRUE(contains(e.what(), "no faces")) << e.what();
            }
            if (name == "nan.obj") {
                EXPECT_EQ(e.line(), 2) << e.what();
            }
            if (name == "nan.obj" || name == "inf.obj" || name == "word.obj") {
                EXPECT_TRUE(contains(e.what(), "vertex coordinate is not a finite number"))
                    << e.what();
                EXPECT_EQ(e.validRange(), "finite numbers");
            }
        }
        EXPECT_EQ(c.objectCount(), 1u) << name;
        EXPECT_EQ(c.materialCount(), 1u) << name;
    }
}

TEST_F(ExportTest, ReadObjSplitsMaterialRunsAndTriangulates) {
    fs::create_directory(dir_ / "m");
    writeText(dir_ / "m" / "two.mtl",
              "newmtl bark\nKd 0.4 0.3 0.2\n"
              "newmtl skin\nKd 1 1 1\nmap_Kd tex/skin.png\n");
    writeText(dir_ / "m" / "two.obj",
              "mtllib two.mtl\n"
              "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\n"
              "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
              "o stem\nusemtl bark\nf 1 2 3 4\n"  // a quad: two triangles
              "usemtl skin\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n"
              "o twig\nf 1 2 5\n");
    Context c;
    std::vector<std::string> warnings;
    const auto ids = readOBJ(c, (dir_ / "m" / "two.obj").string(),
                             {.onWarning = [&](const std::string& w) { warnings.push_back(w); }});
    EXPECT_TRUE(warnings.empty());
    ASSERT_EQ(ids.size(), 3u);
    EXPECT_EQ(c.object(ids[0]).triangleCount(), 2u);
    EXPECT_TRUE(c.object(ids[0]).uvs.empty());
    EXPECT_EQ(c.object(ids[1]).triangleCount(), 2u);
    EXPECT_EQ(c.object(ids[1]).positions.size(), 4u);  // shared corners merged
    EXPECT_EQ(c.object(ids[1]).uvs.size(), 4u);
    EXPECT_EQ(c.object(ids[2]).triangleCount(), 1u);
    const Material& bark = c.material(c.objectMaterial(ids[0]));
    EXPECT_EQ(bark.name, "bark");
    EXPECT_NEAR(bark.color.g, 0.3f, 1e-6f);
    const Material& skin = c.material(c.objectMaterial(ids[1]));
    EXPECT_EQ(skin.texture, (dir_ / "m" / "tex" / "skin.png").lexically_normal().string());
    EXPECT_EQ(c.objectMaterial(ids[2]), c.objectMaterial(ids[1]));  // usemtl carries over
    EXPECT_EQ(c.objectDataString(ids[0], "name"), "stem");
    EXPECT_EQ(c.objectDataString(ids[2], "name"), "twig");
}

TEST_F(ExportTest, ReadObjMissingMaterialLibraryIsAWarning) {
    writeText(dir_ / "a.obj", "mtllib gone.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl x\nf 1 2 3\n");
    Context c;
    std::vector<std::string> warnings;
    const auto ids = readOBJ(c, (dir_ / "a.obj").string(),
                             {.storeShapeNames = false,
                              .onWarning = [&](const std::string& w) { warnings.push_back(w); }});
    ASSERT_EQ(ids.size(), 1u);
    EXPECT_FALSE(warnings.empty());
    EXPECT_EQ(c.material(c.objectMaterial(ids[0])), Material{});
    EXPECT_FALSE(c.hasObjectData(ids[0], "name"));
}

}  // namespace
