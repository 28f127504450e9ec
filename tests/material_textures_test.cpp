// Procedural textures (src/scene_io/procedural_textures.h, material_textures.h): leaf venation
// follows the leaf's texture space (midrib on v = 0.5), alpha is 0 outside the outline and
// opaque inside, bark repeats, the same scene gives the same bytes on any thread count, and a
// bad texture size is one clear error. With PLANTARCH_TEXTURE_DUMP=<folder> the maps of a bean
// are written there as PNGs, to look at.

#include "scene_io/material_textures.h"

#include <gtest/gtest.h>
#include <omp.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "plantarch/Context.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/PlantArchitecture.h"
#include "scene_io/procedural_textures.h"

using namespace plantarch;
using namespace plantarch::io;

namespace {

float luminance(const std::vector<std::uint8_t>& rgba, int n, int i, int j) {
    const std::uint8_t* p = &rgba[(std::size_t(j) * std::size_t(n) + std::size_t(i)) * 4];
    return 0.3f * p[0] + 0.59f * p[1] + 0.11f * p[2];
}

struct Bean {
    Context ctx;
    PlantArchitecture arch{&ctx};
    Bean() {
        arch.setSeed(3);
        arch.loadPlantModelFromLibrary("bean");
        arch.buildPlantInstanceFromLibrary(vec3(0.0f), 30);
    }
};

// An image per set of maps (the atlas has its own tests: texture_atlas_test.cpp).
MaterialOptions textured(int size) {
    return {MaterialStyle::Textured, size, false};
}

const MaterialMaps* mapsOfKind(const MaterialLooks& looks, SurfaceKind kind) {
    for (const MaterialMaps& m : looks.maps())
        if (m.kind == kind) return &m;
    return nullptr;
}

}  // namespace

TEST(MaterialTextures, MidribIsLighterThanTheBladeBesideIt) {
    LeafTextureInput in;
    in.size = 256;
    in.aspect = 0.6f;
    const TextureMaps maps = leafTextureMaps(in);
    ASSERT_EQ(maps.baseColor.size(), 256u * 256u * 4u);
    // Along the midline (v = 0.5: rows 127 and 128), from a tenth to 70 % of the length, the
    // midrib is lighter than the blade a sixth of the width away, on both sides.
    int lighter = 0, columns = 0;
    for (int i = 26; i < 180; i += 4, ++columns) {
        const float mid = 0.5f * (luminance(maps.baseColor, 256, i, 127) +
                                  luminance(maps.baseColor, 256, i, 128));
        const float above = luminance(maps.baseColor, 256, i, 128 - 43);
        const float below = luminance(maps.baseColor, 256, i, 128 + 43);
        if (mid > above + 4.0f && mid > below + 4.0f) ++lighter;
    }
    EXPECT_GE(lighter, columns * 9 / 10) << lighter << " of " << columns;
    EXPECT_FALSE(maps.hasAlpha);  // no outline given: opaque
}

TEST(MaterialTextures, NormalsDipIntoTheMidribGroove) {
    LeafTextureInput in;
    in.size = 256;
    const TextureMaps maps = leafTextureMaps(in);
    // The groove's walls face its middle: tangent-space y (along v) is negative above the
    // midline (v > 0.5) and positive below it.
    const auto ny = [&](int i, int j) {
        return int(maps.normal[(std::size_t(j) * 256 + std::size_t(i)) * 3 + 1]) - 128;
    };
    EXPECT_LT(ny(60, 125), -8);
    EXPECT_GT(ny(60, 130), 8);
}

TEST(MaterialTextures, BeanLeafAlphaFollowsItsOutline) {
    Bean bean;
    const Context* contexts[] = {&bean.ctx};
    const MaterialLooks looks(contexts, textured(128), false, true, {.keepPixels = true});
    const MaterialMaps* leaf = mapsOfKind(looks, SurfaceKind::Leaf);
    ASSERT_NE(leaf, nullptr);
    ASSERT_TRUE(leaf->hasAlpha);
    const std::vector<std::uint8_t>& rgba = leaf->pixels.baseColor;
    const auto alpha = [&](int i, int j) { return rgba[(std::size_t(j) * 128 + i) * 4 + 3]; };
    // The blade's corners of texture space lie outside its outline; its middle inside.
    EXPECT_EQ(alpha(0, 0), 0);
    EXPECT_EQ(alpha(127, 0), 0);
    EXPECT_EQ(alpha(0, 127), 0);
    EXPECT_EQ(alpha(127, 127), 0);
    EXPECT_EQ(alpha(64, 64), 255);
    EXPECT_EQ(alpha(30, 64), 255);
    // Every texel a triangle of a leaf of this material covers is opaque (no holes in a leaf).
    std::vector<std::uint8_t> mask;
    for (const ObjectID id : bean.ctx.objectIDs()) {
        const ObjectView o = bean.ctx.object(id);
        if (looks.look(bean.ctx.material(o.material)).maps != int(leaf - looks.maps().data()))
            continue;
        rasterizeUVTriangles(o.uvs, o.indices, 128, mask);
    }
    for (std::size_t k = 0; k < mask.size(); ++k) {
        if (mask[k] == 0) continue;
        ASSERT_EQ(rgba[k * 4 + 3], 255) << "texel " << k;
    }
    // Bark and stems are textured too, and opaque.
    const MaterialMaps* bark = mapsOfKind(looks, SurfaceKind::Bark);
    ASSERT_NE(bark, nullptr);
    EXPECT_FALSE(bark->hasAlpha);
}

TEST(MaterialTextures, BarkRepeatsAcrossItsEdges) {
    const TextureMaps maps = barkTextureMaps(vec3(0.4f, 0.3f, 0.2f), 7, 128, false);
    // The left and right columns, and the top and bottom rows, continue each other: they
    // differ no more than neighbouring columns inside do.
    const auto diff = [&](int i0, int j0, int i1, int j1) {
        double sum = 0.0;
        for (int t = 0; t < 128; ++t) {
            const int a = i0 < 0 ? t : i0, b = j0 < 0 ? t : j0;
            const int c = i1 < 0 ? t : i1, d = j1 < 0 ? t : j1;
            sum += std::abs(luminance(maps.baseColor, 128, a, b) -
                            luminance(maps.baseColor, 128, c, d));
        }
        return sum / 128.0;
    };
    const double inside = 0.5 * (diff(63, -1, 64, -1) + diff(-1, 63, -1, 64));
    EXPECT_LT(diff(0, -1, 127, -1), 3.0 * inside + 4.0);
    EXPECT_LT(diff(-1, 0, -1, 127), 3.0 * inside + 4.0);
}

TEST(MaterialTextures, SameSceneSameBytesAnyThreadCount) {
    Bean bean;
    const Context* contexts[] = {&bean.ctx};
    const MapRequest request{{MapKind::BaseColor, MapKind::Normal, MapKind::ORM}, true, false};
    const int threads = omp_get_max_threads();
    omp_set_num_threads(1);
    const MaterialLooks one(contexts, textured(64), false, true, request);
    omp_set_num_threads(std::max(threads, 3));
    const MaterialLooks many(contexts, textured(64), false, true, request);
    omp_set_num_threads(threads);
    ASSERT_EQ(one.maps().size(), many.maps().size());
    ASSERT_GE(one.maps().size(), 2u);
    for (std::size_t m = 0; m < one.maps().size(); ++m)
        for (std::size_t k = 0; k < kMapKinds; ++k)
            EXPECT_EQ(one.maps()[m].png[k], many.maps()[m].png[k]);
    // A PNG for each kind asked for, none for the others.
    EXPECT_FALSE(one.maps()[0].png[std::size_t(MapKind::ORM)].empty());
    EXPECT_TRUE(one.maps()[0].png[std::size_t(MapKind::Alpha)].empty());
}

TEST(MaterialTextures, FlatStyleDrawsNothing) {
    Bean bean;
    const Context* contexts[] = {&bean.ctx};
    const MaterialLooks looks(contexts, MaterialOptions{}, false, true, {});
    EXPECT_FALSE(looks.textured());
    EXPECT_TRUE(looks.maps().empty());
}

TEST(MaterialTextures, BadTextureSizesAreOneClearError) {
    for (const int size : {0, -4, 8, 100, 513, 8192, 1 << 30}) {
        try {
            checkMaterialOptions({MaterialStyle::Textured, size});
            ADD_FAILURE() << size << " accepted";
        } catch (const Error& e) {
            EXPECT_EQ(e.parameter(), "texture_size");
            EXPECT_EQ(e.value(), std::to_string(size));
            EXPECT_EQ(e.validRange(), "a power of two from 16 to 4096");
            EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
        }
    }
    for (const int size : {16, 64, 512, 4096})
        checkMaterialOptions({MaterialStyle::Textured, size});
    EXPECT_EQ(materialStyleFromName("textured"), MaterialStyle::Textured);
    EXPECT_EQ(materialStyleFromName("flat"), MaterialStyle::Flat);
    EXPECT_FALSE(materialStyleFromName("Textured"));
}

TEST(MaterialTextures, DumpForLooking) {
    const char* folder = std::getenv("PLANTARCH_TEXTURE_DUMP");
    if (!folder) GTEST_SKIP() << "set PLANTARCH_TEXTURE_DUMP to a folder to write the maps";
    Bean bean;
    const Context* contexts[] = {&bean.ctx};
    const MaterialLooks looks(contexts, textured(512), false, true,
                              {{MapKind::BaseColor, MapKind::Normal, MapKind::ORM}, false, false});
    for (const MaterialMaps& m : looks.maps())
        for (const MapKind k : {MapKind::BaseColor, MapKind::Normal, MapKind::ORM}) {
            std::ofstream out(std::string(folder) + "/" + mapFileName("", m, k), std::ios::binary);
            out << m.png[std::size_t(k)];
        }
}

TEST(MaterialTextures, AMaterialSharedByLeavesAndStemsStaysAColour) {
    // As a file read without materials gives: every object the default material.
    Context ctx;
    Mesh quad;
    quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    quad.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    quad.indices = {0, 1, 2, 0, 2, 3};
    const ObjectID leaf = ctx.addObject(quad, Material{});
    const ObjectID stem = ctx.addObject(quad, Material{});
    ctx.setObjectData(leaf, "organ", std::string("leaf"));
    ctx.setObjectData(stem, "organ", std::string("internode"));
    const Context* contexts[] = {&ctx};
    const MaterialLooks looks(contexts, textured(32), false, true, {});
    EXPECT_EQ(looks.look(Material{}).kind, SurfaceKind::Other);
    EXPECT_EQ(looks.look(Material{}).maps, -1);
    EXPECT_TRUE(looks.maps().empty());
    // One organ alone gets its maps.
    ctx.deleteObject(stem);
    const MaterialLooks leafOnly(contexts, textured(32), false, true, {});
    EXPECT_EQ(leafOnly.look(Material{}).kind, SurfaceKind::Leaf);
    EXPECT_EQ(leafOnly.maps().size(), 1u);
}

TEST(MaterialTextures, TexturesTooLargeForThisMachineAreRefusedBeforeDrawing) {
    // Enough stems of different colours that their 4096-texel maps need more than half the
    // memory: refused at once, naming the size this machine allows.
    const double half = 0.5 * double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGESIZE));
    const std::size_t count = std::size_t(half / (4096.0 * 4096.0 * 2.5)) + 10;
    Context ctx;
    Mesh quad;
    quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    quad.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    quad.indices = {0, 1, 2, 0, 2, 3};
    for (std::size_t i = 0; i < count; ++i) {
        const float c = float(i) / float(count);
        const ObjectID id = ctx.addObject(quad, Material{vec3(0.3f, 0.4f, c), "", ""});
        ctx.setObjectData(id, "organ", std::string("internode"));
    }
    const Context* contexts[] = {&ctx};
    try {
        const MaterialLooks looks(contexts, textured(4096), false, true, {{MapKind::BaseColor}});
        ADD_FAILURE() << count << " materials at 4096 accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.parameter(), "texture_size");
        EXPECT_EQ(e.value(), "4096");
        EXPECT_EQ(e.validRange().rfind("at most ", 0), 0u) << e.validRange();
        EXPECT_NE(std::string(e.what()).find("more than half of this machine's memory"),
                  std::string::npos);
    }
}
