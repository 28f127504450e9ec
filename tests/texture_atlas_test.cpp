// Texture atlases (src/scene_io/texture_atlas.h, material_textures.h): packing leaves no
// overlaps and keeps gutters and alignment, is deterministic and bounded; each material's
// transform maps its [0,1] square onto its rectangle, where the atlas holds the very texels of
// its own maps; tiling bark and stems stay separate; and the preview renderer draws the same
// picture with and without the atlas.

#include "scene_io/texture_atlas.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "builder/server/export_options.h"
#include "plantarch/Context.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/Render.h"
#include "scene_io/material_textures.h"

using namespace plantarch;
using namespace plantarch::io;

namespace {

struct Bean {
    Context ctx;
    PlantArchitecture arch{&ctx};
    explicit Bean(float age = 30.0f) {
        arch.setSeed(3);
        arch.loadPlantModelFromLibrary("bean");
        arch.buildPlantInstanceFromLibrary(vec3(0.0f), age);
    }
};

MaterialOptions textured(int size, bool atlas) {
    return {MaterialStyle::Textured, size, atlas};
}

bool overlap(const AtlasRect& a, const AtlasRect& b) {
    return a.x < b.x + b.width && b.x < a.x + a.width && a.y < b.y + b.height &&
           b.y < a.y + a.height;
}

AtlasRect withGutter(const AtlasRect& r, int g) {
    return {r.x - g, r.y - g, r.width + 2 * g, r.height + 2 * g};
}

// A quad leaf of one colour with texture coordinates `uv0` to `uv1`.
ObjectID addLeaf(Context& ctx, vec3 color, vec2 uv0, vec2 uv1, float x) {
    Mesh quad;
    quad.positions = {{x, 0, 0}, {x + 1, 0, 0}, {x + 1, 0.5f, 0}, {x, 0.5f, 0}};
    quad.uvs = {uv0, {uv1.x, uv0.y}, uv1, {uv0.x, uv1.y}};
    quad.indices = {0, 1, 2, 0, 2, 3};
    const ObjectID id = ctx.addObject(quad, Material{color, "", ""});
    ctx.setObjectData(id, "organ", std::string("leaf"));
    return id;
}

}  // namespace

TEST(TextureAtlas, PackingLeavesNoOverlapsKeepsGuttersAndAlignment) {
    const std::vector<std::array<int, 2>> sizes = {{64, 64},  {128, 32}, {16, 16},   {64, 64},
                                                   {200, 50}, {33, 17},  {512, 512}, {16, 300}};
    const AtlasLayout a = packAtlas(sizes);
    ASSERT_EQ(a.rects.size(), sizes.size());
    EXPECT_EQ(a.width % kAtlasAlign, 0);
    EXPECT_EQ(a.height % kAtlasAlign, 0);
    for (std::size_t i = 0; i < sizes.size(); ++i) {
        const AtlasRect& r = a.rects[i];
        EXPECT_EQ(r.width, sizes[i][0]);
        EXPECT_EQ(r.height, sizes[i][1]);
        EXPECT_EQ(r.x % kAtlasAlign, 0) << i;  // corners on the mip grid
        EXPECT_EQ(r.y % kAtlasAlign, 0) << i;
        const AtlasRect g = withGutter(r, kAtlasGutter);
        EXPECT_GE(g.x, 0);
        EXPECT_GE(g.y, 0);
        EXPECT_LE(g.x + g.width, a.width);
        EXPECT_LE(g.y + g.height, a.height);
        for (std::size_t j = 0; j < i; ++j)
            EXPECT_FALSE(overlap(g, withGutter(a.rects[j], kAtlasGutter))) << i << " " << j;
    }
    // Deterministic, and no larger than the rectangles need (their cells fill half of it).
    const AtlasLayout b = packAtlas(sizes);
    EXPECT_EQ(a.width, b.width);
    EXPECT_EQ(a.height, b.height);
    for (std::size_t i = 0; i < sizes.size(); ++i) {
        EXPECT_EQ(a.rects[i].x, b.rects[i].x);
        EXPECT_EQ(a.rects[i].y, b.rects[i].y);
    }
    double cells = 0.0;
    for (const auto& [w, h] : sizes)
        cells += double(w + 2 * kAtlasGutter) * double(h + 2 * kAtlasGutter);
    EXPECT_GT(cells, 0.5 * double(a.width) * double(a.height));
    // Equal squares make a near-square grid.
    const std::vector<std::array<int, 2>> four(4, {512, 512});
    const AtlasLayout grid = packAtlas(four);
    EXPECT_EQ(grid.width, 2 * (512 + 2 * kAtlasGutter));
    EXPECT_EQ(grid.height, 2 * (512 + 2 * kAtlasGutter));
}

TEST(TextureAtlas, TooLargeOrEmptyIsNoAtlas) {
    const std::vector<std::array<int, 2>> two(2, {4096, 4096});  // 8224 texels: over 8192
    EXPECT_EQ(packAtlas(two).width, 0);
    EXPECT_TRUE(packAtlas(two).rects.empty());
    const std::vector<std::array<int, 2>> nine(9, {2048, 2048});  // 3 x 2064 = 6192
    EXPECT_EQ(packAtlas(nine).width, 3 * 2064);
    EXPECT_LE(packAtlas(std::vector<std::array<int, 2>>(16, {2048, 2048})).width, 0);
    EXPECT_EQ(packAtlas({}).width, 0);
    const std::vector<std::array<int, 2>> bad = {{64, 64}, {0, 64}};
    EXPECT_EQ(packAtlas(bad).width, 0);
}

TEST(TextureAtlas, TransformMapsTheUnitSquareOntoItsRectangle) {
    const std::vector<std::array<int, 2>> sizes = {{64, 64}, {128, 32}, {16, 16}, {64, 64}};
    const AtlasLayout a = packAtlas(sizes);
    for (const AtlasRect& r : a.rects) {
        const UVTransform t = atlasTransform(a, r);
        // v = 1 is the rectangle's top row (row 0 at v = 1 in the atlas too).
        const vec2 topLeft = t.apply(vec2(0.0f, 1.0f)), bottomRight = t.apply(vec2(1.0f, 0.0f));
        EXPECT_NEAR(topLeft.x * float(a.width), float(r.x), 1e-3f);
        EXPECT_NEAR((1.0f - topLeft.y) * float(a.height), float(r.y), 1e-3f);
        EXPECT_NEAR(bottomRight.x * float(a.width), float(r.x + r.width), 1e-3f);
        EXPECT_NEAR((1.0f - bottomRight.y) * float(a.height), float(r.y + r.height), 1e-3f);
    }
}

TEST(TextureAtlas, GutterRepeatsTheEdgeTexels) {
    const int w = 4, h = 3, g = 2, W = 12, H = 10;
    std::vector<std::uint8_t> tile(std::size_t(w * h));
    for (int k = 0; k < w * h; ++k) tile[std::size_t(k)] = std::uint8_t(10 + k);
    std::vector<std::uint8_t> atlas(std::size_t(W * H), 0);
    const AtlasRect r{4, 3, w, h};
    blitWithGutter(tile.data(), 1, r, g, atlas.data(), W, H);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const bool near = x >= r.x - g && x < r.x + w + g && y >= r.y - g && y < r.y + h + g;
            const int tx = std::clamp(x - r.x, 0, w - 1), ty = std::clamp(y - r.y, 0, h - 1);
            EXPECT_EQ(atlas[std::size_t(y * W + x)], near ? tile[std::size_t(ty * w + tx)] : 0)
                << x << "," << y;
        }
}

TEST(TextureAtlas, BeanLeavesShareOneAtlasHoldingTheirOwnTexels) {
    Bean bean;
    const Context* contexts[] = {&bean.ctx};
    const int n = 64;
    const MaterialLooks separate(contexts, textured(n, false), false, true, {.keepPixels = true});
    const MaterialLooks atlas(contexts, textured(n, true), false, true, {.keepPixels = true});
    // One atlas of the leaf sets; bark and stem keep their own (they repeat along the tubes).
    std::size_t atlases = 0, leafSets = 0;
    for (const MaterialMaps& m : atlas.maps()) {
        atlases += m.atlas;
        if (!m.atlas) {
            EXPECT_NE(m.kind, SurfaceKind::Leaf);
        }
    }
    for (const MaterialMaps& m : separate.maps()) leafSets += m.kind == SurfaceKind::Leaf;
    ASSERT_GE(leafSets, 2u);
    ASSERT_EQ(atlases, 1u);
    EXPECT_EQ(atlas.maps().size(), separate.maps().size() - leafSets + 1);
    std::size_t checked = 0;
    for (MaterialID id = 0; id < bean.ctx.materialCount(); ++id) {
        const Material& mat = bean.ctx.material(id);
        const MaterialLook& was = separate.look(mat);
        const MaterialLook& is = atlas.look(mat);
        if (was.maps < 0) continue;
        const MaterialMaps& own = separate.maps()[std::size_t(was.maps)];
        const MaterialMaps& now = atlas.maps()[std::size_t(is.maps)];
        EXPECT_EQ(is.inAtlas, own.kind == SurfaceKind::Leaf);
        if (!is.inAtlas) {
            EXPECT_EQ(now.pixels.baseColor, own.pixels.baseColor);
            continue;
        }
        ++checked;
        const int W = now.pixels.size, H = now.pixels.rows();
        // Each texel centre of the material's own maps lands on the same texel of the atlas.
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const vec2 uv((float(i) + 0.5f) / float(n), 1.0f - (float(j) + 0.5f) / float(n));
                const vec2 at = is.transform.apply(uv);
                const int x = int(std::floor(at.x * float(W)));
                const int y = int(std::floor((1.0f - at.y) * float(H)));
                ASSERT_TRUE(x >= 0 && x < W && y >= 0 && y < H);
                const std::size_t a = std::size_t(y) * std::size_t(W) + std::size_t(x);
                const std::size_t o = std::size_t(j) * std::size_t(n) + std::size_t(i);
                for (int c = 0; c < 4; ++c)
                    ASSERT_EQ(now.pixels.baseColor[a * 4 + c], own.pixels.baseColor[o * 4 + c]);
                for (int c = 0; c < 3; ++c) {
                    ASSERT_EQ(now.pixels.normal[a * 3 + c], own.pixels.normal[o * 3 + c]);
                    ASSERT_EQ(now.pixels.orm[a * 3 + c], own.pixels.orm[o * 3 + c]);
                }
            }
    }
    EXPECT_GE(checked, 2u);
}

TEST(TextureAtlas, SameSceneSameBytesAnyThreadCount) {
    Bean bean;
    const Context* contexts[] = {&bean.ctx};
    const MapRequest request{{MapKind::BaseColor, MapKind::Normal, MapKind::ORM}, true, false};
    const int threads = omp_get_max_threads();
    omp_set_num_threads(1);
    const MaterialLooks one(contexts, textured(64, true), false, true, request);
    omp_set_num_threads(std::max(threads, 3));
    const MaterialLooks many(contexts, textured(64, true), false, true, request);
    omp_set_num_threads(threads);
    ASSERT_EQ(one.maps().size(), many.maps().size());
    for (std::size_t m = 0; m < one.maps().size(); ++m)
        for (std::size_t k = 0; k < kMapKinds; ++k)
            EXPECT_EQ(one.maps()[m].png[k], many.maps()[m].png[k]);
}

TEST(TextureAtlas, LeavesOutsideTheUnitSquareOrAloneKeepTheirImages) {
    Context ctx;
    const ObjectID a = addLeaf(ctx, vec3(0.2f, 0.5f, 0.1f), vec2(0.0f), vec2(1.0f), 0.0f);
    const ObjectID b = addLeaf(ctx, vec3(0.3f, 0.5f, 0.1f), vec2(0.0f), vec2(1.0f), 2.0f);
    const ObjectID c =  // repeats in u
        addLeaf(ctx, vec3(0.4f, 0.5f, 0.1f), vec2(0.0f), vec2(2.0f, 1.0f), 4.0f);
    const Context* contexts[] = {&ctx};
    const auto look = [&](const MaterialLooks& l, ObjectID id) {
        return l.look(ctx.material(ctx.objectMaterial(id)));
    };
    const MaterialLooks looks(contexts, textured(32, true), false, true, {});
    ASSERT_EQ(looks.maps().size(), 2u);  // the atlas of two, and the repeating leaf's own
    EXPECT_TRUE(look(looks, a).inAtlas);
    EXPECT_TRUE(look(looks, b).inAtlas);
    EXPECT_FALSE(look(looks, c).inAtlas);
    EXPECT_NE(look(looks, a).transform.offset, look(looks, b).transform.offset);
    // One packable leaf alone: its own image, no transform.
    ctx.deleteObject(b);
    const MaterialLooks alone(contexts, textured(32, true), false, true, {});
    EXPECT_EQ(alone.maps().size(), 2u);
    for (const MaterialMaps& m : alone.maps()) EXPECT_FALSE(m.atlas);
}

TEST(TextureAtlas, RendererDrawsTheSamePictureWithTheAtlas) {
    Bean bean(40.0f);
    RenderOptions o;
    o.width = 160;
    o.height = 160;
    o.samplesPerPixel = 1;
    o.camera.autoFrame = false;
    const AABB box = bean.ctx.boundingBox();
    // Close over the upper leaves, where texels are larger than pixels.
    o.camera.target = box.center() + vec3(0.0f, 0.0f, 0.3f * box.extent().z);
    o.camera.eye = o.camera.target + vec3(0.25f, -0.35f, 0.45f) * std::max(box.extent().z, 0.3f);
    o.camera.fovDeg = 32.0f;
    o.scene.appearance = textured(512, false);
    const Image before = render(bean.ctx, o);
    o.scene.appearance = textured(512, true);
    const Image after = render(bean.ctx, o);
    o.scene.appearance = {};
    const Image flat = render(bean.ctx, o);
    ASSERT_EQ(before.rgb.size(), after.rgb.size());
    double sum = 0.0, sumFlat = 0.0;
    std::size_t far = 0;
    for (std::size_t k = 0; k < before.rgb.size(); ++k) {
        const int d = std::abs(int(before.rgb[k]) - int(after.rgb[k]));
        sum += d;
        sumFlat += std::abs(int(before.rgb[k]) - int(flat.rgb[k]));
        far += d > 8;
    }
    const double mean = sum / double(before.rgb.size());
    // Texel rounding at most: far below what the textures themselves change.
    EXPECT_LT(mean, 0.5) << "flat vs textured: " << sumFlat / double(before.rgb.size());
    EXPECT_LT(double(far), 0.002 * double(before.rgb.size()));
    EXPECT_GT(sumFlat / double(before.rgb.size()), 5.0 * mean + 1.0);
}

TEST(TextureAtlas, BuilderVariantTakesTheAtlasFlag) {
    using plantarch::builder::exportVariant;
    using plantarch::builder::json;
    const json on = {{"materials", "textured"}};
    EXPECT_TRUE(exportVariant(on, "glb").appearance.atlas);
    const json off = {{"materials", "textured"}, {"atlas", false}};
    EXPECT_FALSE(exportVariant(off, "glb").appearance.atlas);
    for (const json& bad : {json("no"), json(0), json::array()}) {
        try {
            exportVariant(json{{"materials", "textured"}, {"atlas", bad}}, "usda");
            ADD_FAILURE() << bad.dump() << " accepted";
        } catch (const Error& e) {
            EXPECT_EQ(e.parameter(), "atlas");
            EXPECT_EQ(e.validRange(), "true, false");
        }
    }
}
