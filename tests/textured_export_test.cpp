// Textured exports (MaterialStyle::Textured): glTF PBR materials with embedded PNG maps whose
// leaf venation lines up with the leaves' UVs, USD UsdPreviewSurface networks with texture
// files beside the .usda or inside a .usdz (64-byte aligned), OBJ/MTL maps, the renderer's
// textured leaves, same bytes on any thread count, and failures that leave no file behind.

#include <gtest/gtest.h>
#include <omp.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "core/stb.h"
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

namespace {

struct Bean {
    Context ctx;
    PlantArchitecture arch{&ctx};
    Bean() {
        arch.setSeed(3);
        arch.loadPlantModelFromLibrary("bean");
        arch.buildPlantInstanceFromLibrary(vec3(0.0f), 25);
    }
};

// An image per set of maps (the atlas: texture_atlas_test.cpp,
// CliMaterials.TexturedBuildWritesAnAtlas).
const MaterialOptions kTextured{MaterialStyle::Textured, 128, false};

struct Folder {
    fs::path path;
    Folder() {
        path = fs::temp_directory_path() /
               ("plantarch_textured_" + std::to_string(::getpid()) + "_" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(path);
        fs::create_directories(path);
    }
    ~Folder() { fs::remove_all(path); }
    std::string operator/(const std::string& name) const { return (path / name).string(); }
    std::set<std::string> files() const {
        std::set<std::string> out;
        for (const auto& e : fs::directory_iterator(path)) out.insert(e.path().filename().string());
        return out;
    }
};

// An embedded image of a GLB, decoded to RGBA.
std::vector<std::uint8_t> glbImage(const Glb& g, int image, int& width, int& height) {
    const json& view = g.doc["bufferViews"][g.doc["images"][image]["bufferView"].get<int>()];
    const auto* data =
        reinterpret_cast<const std::uint8_t*>(g.bin.data()) + view["byteOffset"].get<std::size_t>();
    std::vector<std::uint8_t> pixels;
    int channels = 0;
    EXPECT_TRUE(core::stbDecodeImage(data, view["byteLength"].get<int>(), 4, width, height,
                                     channels, pixels));
    return pixels;
}

float luminance(const std::vector<std::uint8_t>& rgba, int width, int i, int j) {
    const std::uint8_t* p = &rgba[(std::size_t(j) * std::size_t(width) + std::size_t(i)) * 4];
    return 0.3f * p[0] + 0.59f * p[1] + 0.11f * p[2];
}

}  // namespace

TEST(TexturedExport, GlbLeafMaterialHasEmbeddedMapsAlignedWithItsUVs) {
    Bean bean;
    Folder dir;
    GltfOptions o;
    o.appearance = kTextured;
    writeGLTF(bean.ctx, dir / "bean.glb", o);
    const Glb g = parseGlb(readAll(dir / "bean.glb"));
    ASSERT_TRUE(g.doc.contains("images"));
    for (const json& image : g.doc["images"]) EXPECT_EQ(image["mimeType"], "image/png");
    EXPECT_EQ(g.doc["textures"].size(), g.doc["images"].size());
    // Every textured material has the three maps; the leaves' are cut out by their outline.
    int leaves = 0, barks = 0;
    for (const json& m : g.doc["materials"]) {
        const json& pbr = m["pbrMetallicRoughness"];
        if (!pbr.contains("baseColorTexture")) continue;
        EXPECT_TRUE(pbr.contains("metallicRoughnessTexture"));
        EXPECT_TRUE(m.contains("normalTexture"));
        EXPECT_TRUE(m.contains("occlusionTexture"));
        if (m["name"] == "leaf") {
            ++leaves;
            EXPECT_EQ(m["alphaMode"], "MASK");
            // glTF images start at v = 0: row j is v = (j + 0.5) / height. The midrib (v = 0.5)
            // is lighter than the blade a sixth of the width to either side, and the corners
            // of texture space are outside the leaf.
            int w = 0, h = 0;
            const auto rgba = glbImage(
                g,
                g.doc["textures"][pbr["baseColorTexture"]["index"].get<int>()]["source"].get<int>(),
                w, h);
            ASSERT_EQ(w, 128);
            int lighter = 0;
            for (int i = 16; i < 90; i += 4) {
                const float mid = 0.5f * (luminance(rgba, w, i, 63) + luminance(rgba, w, i, 64));
                if (mid > luminance(rgba, w, i, 64 - 21) + 3 &&
                    mid > luminance(rgba, w, i, 64 + 21) + 3)
                    ++lighter;
            }
            EXPECT_GE(lighter, 16);
            EXPECT_EQ(rgba[3], 0);                                       // corner (u 0, v 0)
            EXPECT_EQ(rgba[(std::size_t(64) * 128 + 40) * 4 + 3], 255);  // on the midrib
        }
        if (m["name"] == "bark") ++barks;
    }
    EXPECT_GE(leaves, 1);
    EXPECT_GE(barks, 1);
    // Primitives of textured materials carry texture coordinates.
    for (const json& mesh : g.doc["meshes"])
        for (const json& p : mesh["primitives"]) {
            const json& m = g.doc["materials"][p["material"].get<int>()];
            EXPECT_TRUE(!m["pbrMetallicRoughness"].contains("baseColorTexture") ||
                        p["attributes"].contains("TEXCOORD_0"));
        }
}

TEST(TexturedExport, FlatIsTheDefaultAndUnchanged) {
    Bean bean;
    Folder dir;
    writeGLTF(bean.ctx, dir / "flat.glb");
    GltfOptions o;
    o.appearance.style = MaterialStyle::Flat;
    o.appearance.textureSize = 2048;  // unused when flat
    writeGLTF(bean.ctx, dir / "flat2.glb", o);
    EXPECT_EQ(readAll(dir / "flat.glb"), readAll(dir / "flat2.glb"));
    EXPECT_FALSE(parseGlb(readAll(dir / "flat.glb")).doc.contains("images"));
}

TEST(TexturedExport, SameBytesOnAnyThreadCount) {
    Bean bean;
    Folder dir;
    GltfOptions o;
    o.appearance = kTextured;
    const int threads = omp_get_max_threads();
    omp_set_num_threads(1);
    writeGLTF(bean.ctx, dir / "one.glb", o);
    writeUSDA(bean.ctx, dir / "a.usdz", {.appearance = kTextured});
    omp_set_num_threads(std::max(3, threads));
    writeGLTF(bean.ctx, dir / "many.glb", o);
    writeUSDA(bean.ctx, dir / "b.usdz", {.appearance = kTextured});
    omp_set_num_threads(threads);
    EXPECT_TRUE(readAll(dir / "one.glb") == readAll(dir / "many.glb"));
    // The package names its root layer after itself (a.usda, b.usda); the rest is the same.
    std::string a = readAll(dir / "a.usdz");
    for (std::size_t at = a.find("a.usda"); at != std::string::npos; at = a.find("a.usda", at))
        a[at] = 'b';
    EXPECT_TRUE(a == readAll(dir / "b.usdz"));
}

TEST(TexturedExport, UsdaHasPreviewSurfacesAndTextureFilesBesideIt) {
    Bean bean;
    Folder dir;
    UsdOptions o;
    o.appearance = kTextured;
    writeUSDA(bean.ctx, dir / "bean.usda", o);
    const std::string text = readAll(dir / "bean.usda");
    EXPECT_NE(text.find("def Scope \"Looks\""), std::string::npos);
    EXPECT_NE(text.find("info:id = \"UsdPreviewSurface\""), std::string::npos);
    EXPECT_NE(text.find("info:id = \"UsdUVTexture\""), std::string::npos);
    EXPECT_NE(text.find("info:id = \"UsdPrimvarReader_float2\""), std::string::npos);
    EXPECT_NE(text.find("rel material:binding = </plantarch/Looks/"), std::string::npos);
    EXPECT_NE(text.find("inputs:opacityThreshold = 0.5"), std::string::npos);
    // Every texture the layer names is a PNG beside it, and nothing else was written.
    std::set<std::string> named;
    for (std::size_t at = text.find("@./"); at != std::string::npos; at = text.find("@./", at + 1))
        named.insert(text.substr(at + 3, text.find('@', at + 3) - at - 3));
    ASSERT_FALSE(named.empty());
    std::set<std::string> expected = named;
    expected.insert("bean.usda");
    EXPECT_EQ(dir.files(), expected);
    for (const std::string& name : named) {
        EXPECT_EQ(name.rfind("bean_", 0), 0u) << name;
        EXPECT_EQ(readAll(dir / name).substr(1, 3), "PNG") << name;
    }
}

TEST(TexturedExport, UsdzPackageIsStoredAlignedAndRootFirst) {
    Bean bean;
    Folder dir;
    writeUSDA(bean.ctx, dir / "bean.usdz", {.appearance = kTextured});
    EXPECT_EQ(dir.files(), std::set<std::string>{"bean.usdz"});
    const std::string zip = readAll(dir / "bean.usdz");
    std::vector<std::string> names;
    std::size_t at = 0;
    while (at + 30 <= zip.size()) {
        std::uint32_t signature = 0;
        std::memcpy(&signature, zip.data() + at, 4);
        if (signature != 0x04034b50u) break;
        std::uint16_t method = 0, nameLength = 0, extraLength = 0;
        std::uint32_t size = 0;
        std::memcpy(&method, zip.data() + at + 8, 2);
        std::memcpy(&size, zip.data() + at + 18, 4);
        std::memcpy(&nameLength, zip.data() + at + 26, 2);
        std::memcpy(&extraLength, zip.data() + at + 28, 2);
        EXPECT_EQ(method, 0);  // stored
        names.push_back(zip.substr(at + 30, nameLength));
        const std::size_t data = at + 30 + nameLength + extraLength;
        EXPECT_EQ(data % 64, 0u) << names.back();
        at = data + size;
    }
    ASSERT_GE(names.size(), 4u);
    EXPECT_EQ(names.front(), "bean.usda");
    EXPECT_NE(zip.find("@./leaf_0_basecolor.png@"), std::string::npos);
    EXPECT_NE(std::find(names.begin(), names.end(), "leaf_0_basecolor.png"), names.end());
}

TEST(TexturedExport, FailedUsdWriteLeavesNoFiles) {
    Bean bean;
    Folder dir;
    // A folder where a texture file would go: writing fails, and nothing is left behind.
    fs::create_directories(dir.path / "bean_leaf_0_normal.png");
    EXPECT_THROW(writeUSDA(bean.ctx, dir / "bean.usda", {.appearance = kTextured}), Error);
    EXPECT_EQ(dir.files(), std::set<std::string>{"bean_leaf_0_normal.png"});
    EXPECT_THROW(writeOBJ(bean.ctx, dir / "bean.obj", {.appearance = kTextured}), Error);
}

TEST(TexturedExport, ObjMaterialLibraryNamesItsMaps) {
    Bean bean;
    Folder dir;
    writeOBJ(bean.ctx, dir / "bean.obj", {.appearance = kTextured});
    const std::string mtl = readAll(dir / "bean.mtl");
    for (const char* key : {"map_Kd bean_leaf_0_basecolor.png", "map_d bean_leaf_0_alpha.png",
                            "norm bean_leaf_0_normal.png", "map_Pr bean_leaf_0_roughness.png",
                            "map_Kd bean_bark_0_basecolor.png", "Pr "})
        EXPECT_NE(mtl.find(key), std::string::npos) << key;
    const std::set<std::string> files = dir.files();
    for (const char* file : {"bean_leaf_0_basecolor.png", "bean_leaf_0_alpha.png",
                             "bean_leaf_0_normal.png", "bean_leaf_0_roughness.png"})
        EXPECT_TRUE(files.count(file)) << file;
    EXPECT_FALSE(files.count("bean_bark_0_alpha.png"));  // bark is opaque
}

TEST(TexturedExport, RendererDrawsTheSameLeafTexture) {
    Bean bean;
    RenderOptions o;
    o.width = 160;
    o.height = 120;
    o.mode = RenderMode::Shaded;
    const Image flat = render(bean.ctx, o);
    o.scene.appearance = kTextured;
    const Image textured = render(bean.ctx, o);
    ASSERT_EQ(flat.rgb.size(), textured.rgb.size());
    EXPECT_NE(flat.rgb, textured.rgb);
    EXPECT_EQ(textured.rgb, render(bean.ctx, o).rgb);  // deterministic
    o.scene.appearance.textureSize = 100;
    EXPECT_THROW(render(bean.ctx, o), Error);
}

TEST(TexturedExport, NormalMappedPrimitivesCarryTangentsInEveryLevel) {
    Bean bean;
    Folder dir;
    GltfOptions o;
    o.appearance = kTextured;
    o.levels = {{.kind = GltfLevel::Kind::Reduced, .share = 0.25f, .coverage = 0.3f},
                {.kind = GltfLevel::Kind::Cards, .share = 0.25f, .coverage = 0.1f}};
    writeGLTF(bean.ctx, dir / "lod.glb", o);
    const Glb g = parseGlb(readAll(dir / "lod.glb"));
    int mapped = 0;
    for (const json& mesh : g.doc["meshes"])
        for (const json& p : mesh["primitives"])
            if (g.doc["materials"][p["material"].get<int>()].contains("normalTexture")) {
                ++mapped;
                EXPECT_TRUE(p["attributes"].contains("TANGENT")) << mesh["name"];
            }
    EXPECT_GT(mapped, 4);
    // A node per organ keeps the normal maps: each normal-mapped organ mesh carries unit
    // tangents across its normals, w +-1, pointing along increasing u on its triangles.
    o.levels.clear();
    o.nodes = NodeLevel::Organ;
    writeGLTF(bean.ctx, dir / "organs.glb", o);
    const Glb organs = parseGlb(readAll(dir / "organs.glb"));
    int organMapped = 0, triangles = 0, alongU = 0;
    for (const json& mesh : organs.doc["meshes"]) {
        const json& p = mesh["primitives"][0];
        if (!organs.doc["materials"][p["material"].get<int>()].contains("normalTexture")) continue;
        ++organMapped;
        const json& a = p["attributes"];
        ASSERT_TRUE(a.contains("TANGENT")) << mesh["name"];
        const auto t = accessorValues<float>(organs, a["TANGENT"]);
        const auto n = accessorValues<float>(organs, a["NORMAL"]);
        const auto x = accessorValues<float>(organs, a["POSITION"]);
        const auto uv = accessorValues<float>(organs, a["TEXCOORD_0"]);
        const auto idx = accessorValues<std::uint32_t>(organs, p["indices"]);
        for (std::size_t v = 0; v < n.size() / 3; ++v) {
            const vec3 tv(t[4 * v], t[4 * v + 1], t[4 * v + 2]),
                nv(n[3 * v], n[3 * v + 1], n[3 * v + 2]);
            EXPECT_NEAR(glm::length(tv), 1.0f, 1e-4f);
            EXPECT_NEAR(glm::dot(tv, nv), 0.0f, 1e-3f);
            EXPECT_EQ(std::abs(t[4 * v + 3]), 1.0f);
        }
        for (std::size_t k = 0; k + 2 < idx.size(); k += 3) {
            const std::uint32_t i = idx[k], j = idx[k + 1], m = idx[k + 2];
            auto at = [&](std::uint32_t q) { return vec3(x[3 * q], x[3 * q + 1], x[3 * q + 2]); };
            const vec3 e1 = at(j) - at(i), e2 = at(m) - at(i);
            const float d1u = uv[2 * j] - uv[2 * i], d1v = uv[2 * j + 1] - uv[2 * i + 1];
            const float d2u = uv[2 * m] - uv[2 * i], d2v = uv[2 * m + 1] - uv[2 * i + 1];
            const float det = d1u * d2v - d2u * d1v;
            if (std::abs(det) < 1e-8f) continue;
            const vec3 dPdu = (e1 * d2v - e2 * d1v) / det;
            ++triangles;
            if (glm::dot(dPdu, vec3(t[4 * i], t[4 * i + 1], t[4 * i + 2])) > 0.0f) ++alongU;
        }
    }
    EXPECT_GT(organMapped, 4);
    EXPECT_GT(triangles, 100);
    EXPECT_GE(alongU, triangles * 99 / 100);  // averaged across a vertex's triangles
    // The same in a growth animation, whose organ meshes are written the same way.
    int animatedMapped = 0;
    Context young;
    PlantArchitecture arch(&young);
    arch.setSeed(3);
    arch.loadPlantModelFromLibrary("bean");
    arch.buildPlantInstanceFromLibrary(vec3(0.0f), 20);
    writeGLTF({{&young, 20.0}, {&bean.ctx, 25.0}}, dir / "growth.glb", o);
    const Glb growth = parseGlb(readAll(dir / "growth.glb"));
    for (const json& mesh : growth.doc["meshes"]) {
        const json& p = mesh["primitives"][0];
        if (!growth.doc["materials"][p["material"].get<int>()].contains("normalTexture")) continue;
        ++animatedMapped;
        EXPECT_TRUE(p["attributes"].contains("TANGENT")) << mesh["name"];
        for (const json& target : p.value("targets", json::array()))
            EXPECT_TRUE(target.contains("TANGENT"));
    }
    EXPECT_GT(animatedMapped, 4);
}
