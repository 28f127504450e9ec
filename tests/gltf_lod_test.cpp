// Levels of detail (MSFT_lod) and EXT_meshopt_compression of glTF files: each level keeps
// every object and its labels, no triangle mixes two objects, compression gives back the
// same bytes, the same scene gives the same file on any number of threads, and bad levels
// are one error.

#include <gtest/gtest.h>
#include <meshoptimizer.h>
#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "cli_run.h"
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
using plantarch::testing::parseGlb;
using plantarch::testing::readAll;
using plantarch::testing::tempPath;

namespace {

struct Plants {
    Context ctx;
    PlantArchitecture arch{&ctx};
    std::vector<GltfPlant> plants;

    explicit Plants(const char* species, float age = 40.0f) {
        arch.setSeed(5);
        arch.loadPlantModelFromLibrary(species);
        for (int i = 0; i < 2; ++i) {
            const unsigned id =
                arch.buildPlantInstanceFromLibrary(vec3(0.5f * float(i), 0, 0), age);
            plants.push_back({std::int32_t(id), species, arch.getPlantBasePosition(id),
                              arch.getPlantAge(id), 5});
        }
    }
};

std::string written(const Context& ctx, const std::string& name, const GltfOptions& o) {
    const fs::path path = tempPath(name);
    writeGLTF(ctx, path.string(), o);
    std::string bytes = readAll(path.string());
    fs::remove(path);
    return bytes;
}

// The triangles and object IDs under node `n`; every triangle's three vertices checked to
// belong to one object.
struct Tally {
    std::size_t triangles = 0, mixed = 0, mislabelled = 0;
    std::set<int> objects;
};
void tally(const Glb& g, std::size_t n, Tally& t) {
    const json& node = g.doc["nodes"][n];
    if (node.contains("mesh"))
        for (const json& p : g.doc["meshes"][node["mesh"].get<std::size_t>()]["primitives"]) {
            const auto ids = accessorValues<float>(g, p["attributes"]["_OBJECT_ID"].get<int>());
            // Each vertex's feature ID is the property table's row of its object.
            const json& table = g.doc["extensions"]["EXT_structural_metadata"]["propertyTables"][0];
            const auto rows = plantarch::testing::viewValues<std::uint32_t>(
                g, table["properties"]["object"]["values"].get<int>(),
                table["count"].get<std::size_t>());
            const auto features =
                accessorValues<float>(g, p["attributes"]["_FEATURE_ID_0"].get<int>());
            for (std::size_t k = 0; k < features.size(); ++k)
                if (rows.at(std::size_t(features[k])) != std::uint32_t(ids[k])) ++t.mislabelled;
            const auto idx = accessorValues<std::uint32_t>(g, p["indices"].get<int>());
            t.triangles += idx.size() / 3;
            for (std::size_t k = 0; k < idx.size(); k += 3) {
                t.objects.insert(int(ids[idx[k]]));
                if (ids[idx[k]] != ids[idx[k + 1]] || ids[idx[k]] != ids[idx[k + 2]]) ++t.mixed;
            }
        }
    for (const json& c : node.value("children", json::array())) tally(g, c.get<std::size_t>(), t);
}

// Triangles (32-bit indices) each turned to start at its lowest index, winding kept.
std::string firstCornerLowest(const std::string& bytes) {
    std::vector<std::uint32_t> idx(bytes.size() / 4);
    std::memcpy(idx.data(), bytes.data(), bytes.size());
    for (std::size_t k = 0; k + 2 < idx.size(); k += 3) {
        while (idx[k] > idx[k + 1] || idx[k] > idx[k + 2]) {
            const std::uint32_t a = idx[k];
            idx[k] = idx[k + 1];
            idx[k + 1] = idx[k + 2];
            idx[k + 2] = a;
        }
    }
    return std::string(reinterpret_cast<const char*>(idx.data()), bytes.size());
}

std::vector<std::array<float, 3>> sortedPositions(const Mesh& m) {
    std::vector<std::array<float, 3>> out;
    for (const vec3& p : m.positions) out.push_back({p.x, p.y, p.z});
    std::sort(out.begin(), out.end());
    return out;
}

}  // namespace

TEST(GltfLod, LevelsAreMsftLodAlternativesKeepingEveryObject) {
    Plants s("bean");
    GltfOptions o;
    o.plants = s.plants;
    o.levels = parseGltfLevels("reduced,cards");
    const Glb g = parseGlb(written(s.ctx, "levels.glb", o));
    EXPECT_NE(g.doc["extensionsUsed"].dump().find("MSFT_lod"), std::string::npos);
    const std::size_t world = g.doc["scenes"][0]["nodes"][0].get<std::size_t>();
    std::size_t plants = 0;
    for (const json& c : g.doc["nodes"][world]["children"]) {
        const json& node = g.doc["nodes"][c.get<std::size_t>()];
        ASSERT_TRUE(node.contains("extensions")) << node.dump();
        const json& ids = node["extensions"]["MSFT_lod"]["ids"];
        ASSERT_EQ(ids.size(), 2u);
        const json& coverage = node["extras"]["MSFT_screencoverage"];
        ASSERT_EQ(coverage.size(), 3u);
        EXPECT_GT(coverage[0].get<double>(), coverage[1].get<double>());
        EXPECT_GT(coverage[1].get<double>(), coverage[2].get<double>());
        Tally full;
        tally(g, c.get<std::size_t>(), full);
        EXPECT_EQ(full.mixed, 0u);
        EXPECT_EQ(full.mislabelled, 0u);
        std::size_t above = full.triangles;
        for (const json& id : ids) {
            const json& level = g.doc["nodes"][id.get<std::size_t>()];
            EXPECT_EQ(level["extras"]["plantID"], node["extras"]["plantID"]);  // the same plant
            EXPECT_EQ(level.value("translation", json()), node.value("translation", json()));
            Tally t;
            tally(g, id.get<std::size_t>(), t);
            EXPECT_EQ(t.mixed, 0u);              // no triangle mixes two organs
            EXPECT_EQ(t.mislabelled, 0u);        // every feature ID is its object's row
            EXPECT_EQ(t.objects, full.objects);  // every organ on every level
            EXPECT_LT(t.triangles, above);
            above = t.triangles;
        }
        // Reduced: about a quarter; cards: at most two quads an organ.
        Tally reduced, cards;
        tally(g, ids[0].get<std::size_t>(), reduced);
        tally(g, ids[1].get<std::size_t>(), cards);
        EXPECT_LE(reduced.triangles, full.triangles / 3);
        EXPECT_LE(cards.triangles, 4 * full.objects.size());
        EXPECT_LE(cards.triangles * 10, full.triangles);
        ++plants;
    }
    EXPECT_EQ(plants, 2u);
}

TEST(GltfLod, MeshoptCompressionGivesBackTheSameBytes) {
    Plants s("tomato", 60.0f);
    GltfOptions plainOptions;
    plainOptions.plants = s.plants;
    GltfOptions o = plainOptions;
    o.meshoptCompression = true;
    const std::string plainBytes = written(s.ctx, "plain.glb", plainOptions);
    const std::string packedBytes = written(s.ctx, "packed.glb", o);
    EXPECT_LT(packedBytes.size() * 2, plainBytes.size());
    const Glb plain = parseGlb(plainBytes), packed = parseGlb(packedBytes);
    const json required = packed.doc["extensionsRequired"];
    EXPECT_NE(required.dump().find("EXT_meshopt_compression"), std::string::npos);
    ASSERT_EQ(packed.doc["buffers"].size(), 2u);
    EXPECT_TRUE(packed.doc["buffers"][1]["extensions"]["EXT_meshopt_compression"]["fallback"]);
    // The same document but for the views' places.
    for (const char* key : {"accessors", "meshes", "nodes", "materials"})
        EXPECT_EQ(packed.doc[key], plain.doc[key]) << key;
    ASSERT_EQ(packed.doc["bufferViews"].size(), plain.doc["bufferViews"].size());
    std::size_t compressed = 0;
    for (std::size_t i = 0; i < plain.doc["bufferViews"].size(); ++i) {
        const json& pv = plain.doc["bufferViews"][i];
        const json& v = packed.doc["bufferViews"][i];
        const std::size_t length = pv["byteLength"].get<std::size_t>();
        ASSERT_EQ(v["byteLength"].get<std::size_t>(), length);
        std::string expected = plain.bin.substr(pv.value("byteOffset", std::size_t(0)), length);
        std::string got(length, '\0');
        if (v.contains("extensions")) {
            const json& e = v["extensions"]["EXT_meshopt_compression"];
            EXPECT_EQ(v["buffer"], 1);
            EXPECT_EQ(e["buffer"], 0);
            const auto* src = reinterpret_cast<const unsigned char*>(packed.bin.data()) +
                              e["byteOffset"].get<std::size_t>();
            const std::size_t size = e["byteLength"].get<std::size_t>();
            const std::size_t count = e["count"].get<std::size_t>();
            const std::size_t stride = e["byteStride"].get<std::size_t>();
            EXPECT_EQ(count * stride, length);
            const int rc = e["mode"] == "TRIANGLES"
                               ? meshopt_decodeIndexBuffer(got.data(), count, stride, src, size)
                               : meshopt_decodeVertexBuffer(got.data(), count, stride, src, size);
            EXPECT_EQ(rc, 0) << i;
            ++compressed;
        } else {
            EXPECT_EQ(v["buffer"], 0);
            got = packed.bin.substr(v["byteOffset"].get<std::size_t>(), length);
        }
        if (v.contains("extensions") &&
            v["extensions"]["EXT_meshopt_compression"]["mode"] == "TRIANGLES") {
            // The same triangles, in the same order and winding; each may start at another
            // of its corners (the codec turns them so).
            got = firstCornerLowest(got);
            expected = firstCornerLowest(expected);
        }
        EXPECT_TRUE(got == expected) << "view " << i;
    }
    EXPECT_GT(compressed, 0u);
}

TEST(GltfLod, SameBytesOnAnyNumberOfThreads) {
    Plants s("bean");
    GltfOptions o;
    o.plants = s.plants;
    o.levels = parseGltfLevels("reduced:0.3,cards");
    o.meshoptCompression = true;
    const int before = omp_get_max_threads();
    omp_set_num_threads(1);
    const std::string one = written(s.ctx, "one.glb", o);
    omp_set_num_threads(std::max(2, before));
    const std::string many = written(s.ctx, "many.glb", o);
    omp_set_num_threads(before);
    EXPECT_EQ(one, many);
}

TEST(GltfLod, BadLevelsAreOneError) {
    for (const char* bad :
         {"reduced:0", "reduced:1", "reduced:-0.5", "reduced:nan", "cards@2",
          "reduced@0.1,cards@0.2", "cards@0", "bogus", "reduced,", ",cards", "cards@"}) {
        SCOPED_TRACE(bad);
        EXPECT_THROW(parseGltfLevels(bad), Error);
    }
    EXPECT_TRUE(parseGltfLevels("none").empty());
    EXPECT_TRUE(parseGltfLevels("").empty());
    const auto levels = parseGltfLevels("reduced:0.1@0.3,cards");
    ASSERT_EQ(levels.size(), 2u);
    EXPECT_FLOAT_EQ(levels[0].share, 0.1f);
    EXPECT_FLOAT_EQ(levels[0].coverage, 0.3f);
    EXPECT_EQ(levels[1].kind, GltfLevel::Kind::Cards);
    EXPECT_FLOAT_EQ(gltfLevelCoverage(levels, 1), 0.4f / 3.0f);  // the default of level 1
    // Levels made in C++ with their defaults are valid as they are.
    const std::vector<GltfLevel> defaults = {GltfLevel{}, {.kind = GltfLevel::Kind::Cards}};
    EXPECT_NO_THROW(checkGltfLevels(defaults));
    EXPECT_FLOAT_EQ(gltfLevelCoverage(defaults, 0), 0.4f);

    const fs::path out = tempPath("cli");
    fs::create_directories(out);
    const std::string o = (out / "x").string();
    for (const std::string& args : {"build bean --age 10 --lod bogus -o " + o + ".glb",
                                    "build bean --age 10 --lod reduced:2 -o " + o + ".glb",
                                    "build bean --age 10 --lod cards -o " + o + ".obj",
                                    "build bean --age 10 --meshopt -o " + o + ".ply",
                                    "build bean --frames 0:10:5 --lod cards -o " + o + ".glb"}) {
        SCOPED_TRACE(args);
        const cli::Result r = cli::run(args);
        EXPECT_EQ(r.status, 2) << r.out;
        EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
    }
    EXPECT_TRUE(fs::is_empty(out));  // nothing written, nothing left
    fs::remove_all(out);
}

// plantarch reads its compressed files back (render, compare, convert): the same triangles
// and labels as the plain file; a view whose data does not decode is one error.
TEST(GltfLod, CompressedFilesReadBackAsThePlainOnes) {
    Plants s("tomato", 60.0f);
    GltfOptions o;
    o.plants = s.plants;
    const fs::path plainPath = tempPath("read_plain.glb"), packedPath = tempPath("read_packed.glb");
    writeGLTF(s.ctx, plainPath.string(), o);
    o.meshoptCompression = true;
    writeGLTF(s.ctx, packedPath.string(), o);
    Context plain, packed;
    const auto plainIDs = readGLTF(plain, plainPath.string());
    const auto packedIDs = readGLTF(packed, packedPath.string());
    ASSERT_EQ(plainIDs.size(), packedIDs.size());
    EXPECT_EQ(plain.triangleCount(), packed.triangleCount());
    for (std::size_t i = 0; i < plainIDs.size(); ++i) {
        // The same vertices and triangles (a triangle may start at another corner, so the
        // reader may meet the vertices in another order).
        const Mesh a = plain.objectMesh(plainIDs[i]), b = packed.objectMesh(packedIDs[i]);
        EXPECT_EQ(a.triangleCount(), b.triangleCount());
        EXPECT_EQ(sortedPositions(a), sortedPositions(b));
        EXPECT_NEAR(a.area(), b.area(), 1e-9 * a.area());
        EXPECT_EQ(plain.objectDataInt(plainIDs[i], "plantID"),
                  packed.objectDataInt(packedIDs[i], "plantID"));
        EXPECT_EQ(plain.objectDataString(plainIDs[i], "organ"),
                  packed.objectDataString(packedIDs[i], "organ"));
    }
    // Corrupt the compressed data: one error naming the file.
    std::string bytes = readAll(packedPath.string());
    const Glb g = parseGlb(bytes);
    const std::size_t binAt = bytes.size() - g.bin.size();
    for (std::size_t k = 0; k < 64 && k < g.bin.size(); ++k) bytes[binAt + k] = char(0xFF);
    std::ofstream(packedPath, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
    Context bad;
    try {
        readGLTF(bad, packedPath.string());
        ADD_FAILURE() << "a corrupt file was read";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(packedPath.string()), std::string::npos) << e.what();
    }
    fs::remove(plainPath);
    fs::remove(packedPath);
}
