// Vertex normals of the PLY (ASCII and binary) and OBJ exporters point the way the faces wind.
// The exporters document (include/plantarch/Export.h) each vertex normal as the area-weighted
// average of the normals of the triangles around it, a triangle (a, b, c) facing
// cross(b - a, c - a). Files are read back here with small readers of this test's own, and the
// normals checked against that definition recomputed from the file's own positions and faces,
// against the analytic normals of hand-made meshes (a square each way up, a cube), and between
// the formats.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "plantarch/Export.h"
#include "plantarch/PlantArchitecture.h"
#include "ply_reader.h"

using namespace plantarch;

namespace {

using dvec3 = glm::dvec3;

struct MeshFile {
    std::vector<dvec3> positions;
    std::vector<dvec3> normals;                // per vertex (OBJ: per face corner, see corners)
    std::vector<std::uint32_t> faces;          // three vertex indices per triangle
    std::vector<std::uint32_t> cornerNormals;  // OBJ: the normal index of each face corner
};

std::string tempPath(const std::string& name) {
    const auto dir = std::filesystem::temp_directory_path() / "plantarch-conformance-normals";
    std::filesystem::create_directories(dir);
    return (dir / name).string();
}

// ---- readers -------------------------------------------------------------------------------

MeshFile readPLY(const std::string& path) {
    const plantarch::testing::PlyData ply = plantarch::testing::readPlyFile(path);
    std::vector<std::string> vertexProperties;
    for (const auto& p : ply.vertexProperties) {
        EXPECT_EQ(p.type, "float");
        vertexProperties.push_back(p.name);
    }
    const std::vector<std::string> expected = {"x", "y", "z", "nx", "ny", "nz"};
    EXPECT_EQ(vertexProperties, expected) << path;
    MeshFile m;
    if (vertexProperties != expected) return m;
    const std::size_t vertices = ply.vertex.at("x").size();
    m.positions.resize(vertices);
    m.normals.resize(vertices);
    for (std::size_t i = 0; i < vertices; ++i) {
        // Written to round-trip as floats: the doubles read are those floats.
        m.positions[i] = dvec3(ply.vertex.at("x")[i], ply.vertex.at("y")[i], ply.vertex.at("z")[i]);
        m.normals[i] =
            dvec3(ply.vertex.at("nx")[i], ply.vertex.at("ny")[i], ply.vertex.at("nz")[i]);
    }
    m.faces.reserve(3 * ply.faces.size());
    for (const auto& f : ply.faces)
        m.faces.insert(m.faces.end(),
                       {std::uint32_t(f[0]), std::uint32_t(f[1]), std::uint32_t(f[2])});
    return m;
}

// Reads v, vn and f lines ("f v/vt/vn" or "f v//vn"); indices made 0-based.
MeshFile readOBJ(const std::string& path) {
    std::ifstream in(path);
    EXPECT_TRUE(in) << path;
    MeshFile m;
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream words(line);
        std::string tag;
        words >> tag;
        dvec3 v;
        if (tag == "v") {
            vec3 p;  // written to round-trip as floats
            words >> p.x >> p.y >> p.z;
            m.positions.push_back(dvec3(p));
        } else if (tag == "vn") {
            words >> v.x >> v.y >> v.z;
            m.normals.push_back(v);
        } else if (tag == "f") {
            for (int k = 0; k < 3; ++k) {
                std::string corner;
                words >> corner;
                const auto first = corner.find('/'), last = corner.rfind('/');
                EXPECT_NE(first, std::string::npos) << "face without a normal: " << line;
                m.faces.push_back(std::uint32_t(std::stoul(corner.substr(0, first)) - 1));
                m.cornerNormals.push_back(std::uint32_t(std::stoul(corner.substr(last + 1)) - 1));
            }
        }
    }
    return m;
}

// ---- the definition ------------------------------------------------------------------------

dvec3 faceNormal(const MeshFile& m, std::size_t t) {
    const dvec3 a = m.positions[m.faces[3 * t]], b = m.positions[m.faces[3 * t + 1]],
                c = m.positions[m.faces[3 * t + 2]];
    return glm::cross(b - a, c - a);
}

// Per vertex: the sum of cross(b - a, c - a) over the triangles using it.
std::vector<dvec3> areaWeightedSums(const MeshFile& m) {
    std::vector<dvec3> sum(m.positions.size(), dvec3(0.0));
    for (std::size_t t = 0; t < m.faces.size() / 3; ++t) {
        const dvec3 n = faceNormal(m, t);
        for (int k = 0; k < 3; ++k) sum[m.faces[3 * t + std::size_t(k)]] += n;
    }
    return sum;
}

struct Agreement {
    std::size_t vertices = 0, checked = 0, opposite = 0;  // opposite: dot(normal, sum) <= 0
    double worstAngle = 0.0;                              // radians, normal vs its sum
    std::size_t pairs = 0, pairsFacing = 0;               // (vertex, face using it) with dot > 0
};

Agreement agreement(const MeshFile& m) {
    Agreement a;
    const std::vector<dvec3> sum = areaWeightedSums(m);
    a.vertices = m.positions.size();
    for (std::size_t i = 0; i < sum.size(); ++i) {
        const double length = glm::length(sum[i]);
        if (length < 1e-14) continue;  // degenerate: the documented (0, 0, 1) is not checked
        ++a.checked;
        const dvec3 n = m.normals[i];
        const double cosine = glm::dot(n, sum[i]) / (glm::length(n) * length);
        if (!(cosine > 0.0)) ++a.opposite;
        a.worstAngle = std::max(a.worstAngle, std::acos(std::clamp(cosine, -1.0, 1.0)));
    }
    for (std::size_t t = 0; t < m.faces.size() / 3; ++t) {
        const dvec3 f = faceNormal(m, t);
        for (int k = 0; k < 3; ++k) {
            ++a.pairs;
            if (glm::dot(m.normals[m.faces[3 * t + std::size_t(k)]], f) > 0.0) ++a.pairsFacing;
        }
    }
    return a;
}

// The three files of one Context, read back.
struct Exports {
    MeshFile plyAscii, plyBinary, obj;
};

Exports exportAll(const Context& ctx, const std::string& stem) {
    writePLY(ctx, tempPath(stem + "_ascii.ply"), {.format = PlyFormat::Ascii, .normals = true});
    writePLY(ctx, tempPath(stem + "_binary.ply"),
             {.format = PlyFormat::BinaryLittleEndian, .normals = true});
    writeOBJ(ctx, tempPath(stem + ".obj"), {.uvs = false, .materials = false});
    return {readPLY(tempPath(stem + "_ascii.ply")), readPLY(tempPath(stem + "_binary.ply")),
            readOBJ(tempPath(stem + ".obj"))};
}

// The OBJ's normal at every face corner is the PLY's normal at that vertex (the writers list
// objects and vertices in the same order), to the OBJ's 6 decimals.
void expectObjMatchesPly(const MeshFile& obj, const MeshFile& ply) {
    ASSERT_EQ(obj.positions.size(), ply.positions.size());
    ASSERT_EQ(obj.faces, ply.faces);
    std::size_t differing = 0;
    for (std::size_t c = 0; c < obj.faces.size(); ++c) {
        const std::uint32_t v = obj.faces[c];
        if (obj.positions[v] != ply.positions[v] ||
            glm::length(obj.normals[obj.cornerNormals[c]] - ply.normals[v]) > 1e-6)
            ++differing;
    }
    EXPECT_EQ(differing, 0u) << "face corners whose OBJ position or normal is not the PLY's";
}

// ---- tests ---------------------------------------------------------------------------------

// A unit square facing +z, the same square wound the other way (facing -z) one metre above,
// and a cube with shared corners wound outward: every cube normal points from the cube's
// centre through its vertex (a corner, where three equal faces meet, or a face centre).
TEST(ConformanceNormals, HandMadeMeshesPointTheWayTheirFacesWind) {
    Context ctx;
    const std::vector<vec3> square = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    const std::vector<std::uint32_t> up = {0, 1, 2, 0, 2, 3}, down = {0, 2, 1, 0, 3, 2};
    std::vector<vec3> raised = square;
    for (vec3& p : raised) p.z = 1.0f;
    ctx.addObject(square, {}, up);
    ctx.addObject(raised, {}, down);
    const vec3 centre(3.5f, 0.5f, 0.5f);
    std::vector<vec3> cube;
    for (int k = 0; k < 8; ++k)
        cube.push_back(centre +
                       vec3(k & 1 ? 0.5f : -0.5f, k & 2 ? 0.5f : -0.5f, k & 4 ? 0.5f : -0.5f));
    // Each face: its four corners counter-clockwise seen from outside.
    const std::vector<std::uint32_t> quads = {0, 2, 3, 1, 4, 5, 7, 6, 0, 1, 5, 4,
                                              2, 6, 7, 3, 0, 4, 6, 2, 1, 3, 7, 5};
    // Each face is four triangles around a vertex at its centre, so that every corner has
    // the same area on each of its three faces.
    std::vector<std::uint32_t> cubeFaces;
    std::vector<dvec3> centreNormals;
    for (std::size_t q = 0; q < quads.size(); q += 4) {
        const vec3 mid =
            0.25f * (cube[quads[q]] + cube[quads[q + 1]] + cube[quads[q + 2]] + cube[quads[q + 3]]);
        centreNormals.push_back(glm::normalize(dvec3(mid - centre)));
        const std::uint32_t c = std::uint32_t(cube.size());
        cube.push_back(mid);
        for (std::size_t k = 0; k < 4; ++k)
            cubeFaces.insert(cubeFaces.end(), {quads[q + k], quads[q + (k + 1) % 4], c});
    }
    ctx.addObject(cube, {}, cubeFaces);

    std::vector<dvec3> analytic(4, dvec3(0, 0, 1));
    analytic.insert(analytic.end(), 4, dvec3(0, 0, -1));
    for (int k = 0; k < 8; ++k) analytic.push_back(glm::normalize(dvec3(cube[k] - centre)));
    analytic.insert(analytic.end(), centreNormals.begin(), centreNormals.end());

    const Exports e = exportAll(ctx, "hand_made");
    for (const MeshFile* m : {&e.plyAscii, &e.plyBinary}) {
        ASSERT_EQ(m->normals.size(), analytic.size());
        for (std::size_t i = 0; i < analytic.size(); ++i)
            EXPECT_LT(glm::length(m->normals[i] - analytic[i]), 1e-6)
                << "vertex " << i << ": (" << m->normals[i].x << ", " << m->normals[i].y << ", "
                << m->normals[i].z << ")";
        const Agreement a = agreement(*m);
        EXPECT_EQ(a.pairsFacing, a.pairs);  // every face turns the same way as its normals
    }
    expectObjMatchesPly(e.obj, e.plyBinary);
}

// A grown bean: every vertex normal of both PLY encodings is its area-weighted sum of face
// normals, recomputed from the file (none points the other way), and the OBJ's agree.
TEST(ConformanceNormals, PlantNormalsFollowTheWindingInEveryFormat) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    arch.buildPlantInstanceFromLibrary(vec3(0.0f), 30.0f);
    const Exports e = exportAll(ctx, "bean");
    ASSERT_GT(e.plyBinary.positions.size(), 10000u);
    EXPECT_EQ(e.plyAscii.faces, e.plyBinary.faces);
    for (const MeshFile* m : {&e.plyAscii, &e.plyBinary}) {
        const Agreement a = agreement(*m);
        EXPECT_GT(a.checked, a.vertices * 9 / 10);
        EXPECT_EQ(a.opposite, 0u) << "vertex normals pointing against their faces";
        // Float arithmetic turns a normal from the exact sum by about 2e-5 rad at most (on
        // slivers), the ASCII file's 6 decimals by about 1e-6.
        EXPECT_LT(a.worstAngle, 1e-3);
        // Nearly every face around a vertex faces its normal's way (99.96 % of the corners of
        // this bean: at a sharp fold one face can turn past 90 degrees from the average).
        EXPECT_GT(double(a.pairsFacing), 0.99 * double(a.pairs));
    }
    expectObjMatchesPly(e.obj, e.plyBinary);
}

}  // namespace
