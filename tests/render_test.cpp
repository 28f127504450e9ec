// Preview renderer: image size and content, label masks, shadows, textures, determinism,
// PNG output, option checks; and the `plantarch render` command.

#include "plantarch/Render.h"

#include <gtest/gtest.h>
#include <omp.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "plantarch/Context.h"
#include "plantarch/Error.h"
#include "render_scenes.h"

#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#endif
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

using namespace plantarch;
namespace fs = std::filesystem;

namespace {

using RGB = std::array<std::uint8_t, 3>;

/// A fresh empty directory under the system temp folder, removed at the end of the test.
class TempDir {
public:
    TempDir() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        path_ = fs::temp_directory_path() /
                (std::string("plantarch_render_") + info->test_suite_name() + "_" + info->name());
        fs::remove_all(path_);
        fs::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ignore;
        fs::remove_all(path_, ignore);
    }
    fs::path operator/(const std::string& name) const { return path_ / name; }
    const fs::path& path() const { return path_; }

private:
    fs::path path_;
};

/// A leaf quad standing over an internode box, on a marker at z = 0 (so the ground is at 0).
Context leafAndInternode() {
    Context ctx;
    test::addOrgan(ctx, test::boxMesh({-0.05f, -0.05f, 0.0f}, {0.05f, 0.05f, 0.6f}),
                   {0.4f, 0.3f, 0.2f}, "internode", 0);
    test::addOrgan(ctx,
                   test::quadMesh({-0.4f, -0.3f, 0.6f}, {0.4f, -0.3f, 0.6f}, {0.4f, 0.3f, 0.9f},
                                  {-0.4f, 0.3f, 0.9f}),
                   {0.2f, 0.6f, 0.1f}, "leaf", 0);
    return ctx;
}

RenderOptions small(int w = 160, int h = 120) {
    RenderOptions o;
    o.width = w;
    o.height = h;
    return o;
}

std::set<RGB> colours(const Image& img) {
    std::set<RGB> out;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) out.insert(img.pixel(x, y));
    return out;
}

float luminance(const Image& img, int cx, int cy, int r = 2) {
    float sum = 0.0f;
    int n = 0;
    for (int y = cy - r; y <= cy + r; ++y)
        for (int x = cx - r; x <= cx + r; ++x) {
            const RGB p = img.pixel(x, y);
            sum += 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
            ++n;
        }
    return sum / float(n);
}

}  // namespace

// ---- shaded images ---------------------------------------------------------------------

TEST(Render, ProducesImageOfRequestedSize) {
    const Image img = render(leafAndInternode(), small(123, 77));
    EXPECT_EQ(img.width, 123);
    EXPECT_EQ(img.height, 77);
    ASSERT_EQ(img.rgb.size(), std::size_t(123) * 77 * 3);
    EXPECT_GT(colours(img).size(), 10u);  // not a flat fill
}

TEST(Render, ObjectIsVisibleWhereItProjects) {
    const Context ctx = leafAndInternode();
    RenderScene scene(ctx);
    RenderOptions o = small();
    // Same camera for the scene and for an empty scene (the background alone).
    const CameraFrame cam = scene.camera(o);
    o.camera.autoFrame = false;
    o.camera.eye = cam.eye;
    o.camera.target = cam.target;
    o.camera.fovDeg = cam.fovDeg;
    o.groundPlane = false;
    const Image shaded = scene.render(o);
    const Image empty = render(Context(), o);
    RenderOptions lo = o;
    lo.mode = RenderMode::LabelObject;
    const Image mask = scene.render(lo);

    int covered = 0, differing = 0;
    for (int y = 0; y < o.height; ++y)
        for (int x = 0; x < o.width; ++x) {
            if (mask.pixel(x, y) == RGB{0, 0, 0}) {
                // Far from the object (no anti-aliased edge nearby) the background is intact.
                bool nearObject = false;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const int nx = std::clamp(x + dx, 0, o.width - 1);
                        const int ny = std::clamp(y + dy, 0, o.height - 1);
                        nearObject |= mask.pixel(nx, ny) != RGB{0, 0, 0};
                    }
                if (!nearObject) {
                    EXPECT_EQ(shaded.pixel(x, y), empty.pixel(x, y)) << x << "," << y;
                }
                continue;
            }
            ++covered;
            differing += shaded.pixel(x, y) != empty.pixel(x, y);
        }
    EXPECT_GT(covered, o.width * o.height / 10);  // auto-framing fills the frame
    EXPECT_GT(differing, covered * 9 / 10);
}

TEST(Render, AutoFrameKeepsWholeSceneInsideTheMargin) {
    Context ctx;
    test::addDemoScene(ctx);
    RenderOptions o = small(200, 150);
    o.mode = RenderMode::LabelOrgan;
    const Image mask = render(ctx, o);
    int minX = o.width, maxX = -1, minY = o.height, maxY = -1;
    for (int y = 0; y < o.height; ++y)
        for (int x = 0; x < o.width; ++x)
            if (mask.pixel(x, y) != RGB{0, 0, 0}) {
                minX = std::min(minX, x);
                maxX = std::max(maxX, x);
                minY = std::min(minY, y);
                maxY = std::max(maxY, y);
            }
    // Nothing touches the border; the scene spans most of one dimension.
    EXPECT_GT(minX, 0);
    EXPECT_GT(minY, 0);
    EXPECT_LT(maxX, o.width - 1);
    EXPECT_LT(maxY, o.height - 1);
    EXPECT_TRUE(maxX - minX > o.width * 8 / 10 || maxY - minY > o.height * 8 / 10);
}

TEST(Render, GroundUnderAQuadIsInShadow) {
    Context ctx;
    // A 1 m quad 1 m above the ground, and a marker cube that puts the ground at z = 0.
    ctx.addObject(test::quadMesh({-0.5f, -0.5f, 1.0f}, {0.5f, -0.5f, 1.0f}, {0.5f, 0.5f, 1.0f},
                                 {-0.5f, 0.5f, 1.0f}));
    ctx.addObject(test::boxMesh({2.9f, 2.9f, 0.0f}, {3.0f, 3.0f, 0.1f}));
    RenderOptions o = small(200, 200);
    // Straight down from 10 m: +x to the right, +y up the image, 3.64 m from centre to edge.
    o.camera.autoFrame = false;
    o.camera.eye = {0.0f, 0.0f, 10.0f};
    o.camera.target = {0.0f, 0.0f, 0.0f};
    o.camera.up = {0.0f, 1.0f, 0.0f};
    o.camera.fovDeg = 40.0f;
    o.sunDirection = {1.0f, 0.0f, 1.0f};  // the shadow falls 1 m toward -x: x in [-1.5, -0.5]
    auto column = [](float xMetres) { return int(100.0f + xMetres / 3.6397f * 100.0f); };
    const Image img = render(ctx, o);
    const float shadow = luminance(img, column(-1.0f), 100);
    const float lit = luminance(img, column(1.5f), 100);
    EXPECT_LT(shadow, 0.6f * lit) << "shadow " << shadow << " lit " << lit;

    // Without the quad the same spot is lit.
    ctx.deleteObject(0);
    const Image bare = render(ctx, o);
    EXPECT_GT(luminance(bare, column(-1.0f), 100), 0.9f * lit);
}

TEST(Render, HiddenObjectsAreNotDrawn) {
    Context ctx = leafAndInternode();
    RenderOptions o = small();
    o.mode = RenderMode::LabelOrgan;
    o.camera.autoFrame = false;
    o.camera.eye = {2.0f, -2.0f, 1.5f};
    o.camera.target = {0.0f, 0.0f, 0.4f};
    ctx.setObjectHidden(1, true);  // the leaf
    const auto c = colours(render(ctx, o));
    EXPECT_TRUE(c.count(organLabelColor("internode")));
    EXPECT_FALSE(c.count(organLabelColor("leaf")));
}

TEST(Render, EmptySceneGivesSkyAndGround) {
    const Image img = render(Context(), small());
    EXPECT_EQ(img.width, 160);
    EXPECT_GT(colours(img).size(), 2u);
    RenderOptions o = small();
    o.mode = RenderMode::LabelOrgan;
    EXPECT_EQ(colours(render(Context(), o)), (std::set<RGB>{{0, 0, 0}}));
}

// ---- label masks -------------------------------------------------------------------------

TEST(Render, OrganLabelsUseOnlyTableColours) {
    const Context ctx = leafAndInternode();
    RenderOptions o = small();
    o.mode = RenderMode::LabelOrgan;
    const Image mask = render(ctx, o);
    const std::set<RGB> expected = {
        {0, 0, 0}, organLabelColor("leaf"), organLabelColor("internode")};
    EXPECT_EQ(colours(mask), expected);  // exactly these: no blending at edges

    const Image shaded = render(ctx, small());
    EXPECT_NE(mask.rgb, shaded.rgb);
    int differ = 0;
    for (std::size_t i = 0; i < mask.rgb.size(); i += 3)
        differ += mask.rgb[i] != shaded.rgb[i] || mask.rgb[i + 1] != shaded.rgb[i + 1];
    EXPECT_GT(differ, int(mask.rgb.size() / 3 / 2));
}

TEST(Render, OrganTableIsDistinctAndUnknownOrgansAreWhite) {
    std::set<RGB> seen = {{0, 0, 0}};
    for (const auto& entry : organLabelColors()) {
        EXPECT_TRUE(seen.insert(entry.rgb).second) << entry.organ;
        EXPECT_EQ(organLabelColor(entry.organ), entry.rgb);
    }
    EXPECT_EQ(organLabelColor("bud"), (RGB{255, 255, 255}));
    EXPECT_FALSE(seen.count({255, 255, 255}));

    Context ctx;
    ctx.addObject(test::boxMesh({0, 0, 0}, {1, 1, 1}));  // no organ data at all
    RenderOptions o = small();
    o.mode = RenderMode::LabelOrgan;
    EXPECT_EQ(colours(render(ctx, o)), (std::set<RGB>{{0, 0, 0}, {255, 255, 255}}));
}

TEST(Render, ObjectLabelsIdentifyObjects) {
    Context ctx;
    test::addDemoScene(ctx);
    RenderOptions o = small(240, 180);
    o.mode = RenderMode::LabelObject;
    const Image mask = render(ctx, o);
    std::set<ObjectID> ids;
    for (const RGB& c : colours(mask)) {
        const auto id = objectIDFromLabelColor(c);
        if (!id) continue;  // background
        ASSERT_TRUE(ctx.doesObjectExist(*id)) << int(c[0]) << "," << int(c[1]) << "," << int(c[2]);
        EXPECT_EQ(objectLabelColor(*id), c);
        ids.insert(*id);
    }
    EXPECT_GT(ids.size(), ctx.objectCount() / 2);  // most organs are visible
}

TEST(Render, ObjectLabelColoursAreABijection) {
    std::set<RGB> seen;
    for (ObjectID id = 0; id < 200000; ++id) {
        const RGB c = objectLabelColor(id);
        ASSERT_NE(c, (RGB{0, 0, 0}));
        ASSERT_TRUE(seen.insert(c).second) << id;
        ASSERT_EQ(objectIDFromLabelColor(c), id);
    }
    EXPECT_EQ(objectIDFromLabelColor({0, 0, 0}), std::nullopt);
    EXPECT_EQ(objectIDFromLabelColor(objectLabelColor(16777214)), 16777214u);
    EXPECT_THROW(objectLabelColor(16777215), Error);
}

// ---- textures ------------------------------------------------------------------------------

TEST(Render, TextureColourAndAlphaMask) {
    TempDir dir;
    // 4x4 RGBA: left half opaque red, right half transparent.
    std::vector<std::uint8_t> rgba(4 * 4 * 4, 0);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 2; ++x) {
            std::uint8_t* p = &rgba[(y * 4 + x) * 4];
            p[0] = 220;
            p[3] = 255;
        }
    const std::string texture = (dir / "mask.png").string();
    ASSERT_TRUE(stbi_write_png(texture.c_str(), 4, 4, 4, rgba.data(), 16));

    Context ctx;
    const ObjectID quad =
        ctx.addObject(test::quadMesh({-1, 0, 0}, {1, 0, 0}, {1, 0, 2}, {-1, 0, 2}),
                      Material{{0.1f, 0.9f, 0.1f}, texture, "masked"});
    RenderOptions o = small(200, 200);
    o.groundPlane = false;
    o.camera.autoFrame = false;
    o.camera.eye = {0, -5, 1};
    o.camera.target = {0, 0, 1};
    o.camera.fovDeg = 30;
    o.mode = RenderMode::LabelObject;
    const Image mask = render(ctx, o);
    // The left half of the quad (u < 0.5, x < 0) is there; the right half is cut out.
    EXPECT_EQ(mask.pixel(70, 100), objectLabelColor(quad));
    EXPECT_EQ(mask.pixel(130, 100), (RGB{0, 0, 0}));

    o.mode = RenderMode::Shaded;
    const Image shaded = render(ctx, o);
    const RGB red = shaded.pixel(70, 100);
    EXPECT_GT(red[0], 2 * red[1]);  // the texture's red, not the material's green
    EXPECT_GT(red[0], 2 * red[2]);

    // A missing texture is an error naming it, unless ignored.
    Context missing;
    missing.addObject(test::quadMesh({-1, 0, 0}, {1, 0, 0}, {1, 0, 2}, {-1, 0, 2}),
                      Material{{0.1f, 0.9f, 0.1f}, (dir / "nope.png").string(), ""});
    try {
        render(missing, o);
        FAIL() << "expected an Error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("nope.png"), std::string::npos) << e.what();
    }
    o.scene.ignoreMissingTextures = true;
    const Image fallback = render(missing, o);
    const RGB green = fallback.pixel(100, 100);
    EXPECT_GT(green[1], green[0]);
}

// ---- determinism ---------------------------------------------------------------------------

TEST(Render, SameBytesEveryTimeAndForAnyThreadCount) {
    Context ctx;
    test::addDemoScene(ctx);
    RenderOptions o = small(160, 120);
    const int before = omp_get_max_threads();
    omp_set_num_threads(1);
    const Image one = render(ctx, o);
    omp_set_num_threads(2);
    const Image two = render(ctx, o);
    const Image again = render(ctx, o);
    omp_set_num_threads(before);
    EXPECT_EQ(one.rgb, two.rgb);
    EXPECT_EQ(two.rgb, again.rgb);

    o.seed = 99;  // another sample pattern: noise differs, image does not change much
    const Image other = render(ctx, o);
    EXPECT_NE(other.rgb, one.rgb);
}

TEST(Render, SceneRendersSeveralViews) {
    Context ctx;
    test::addDemoScene(ctx);
    RenderScene scene(ctx);
    EXPECT_EQ(scene.triangleCount(), ctx.triangleCount());
    RenderOptions a = small(), b = small();
    b.camera.azimuthDeg = 30.0f;
    EXPECT_NE(scene.render(a).rgb, scene.render(b).rgb);
    EXPECT_EQ(scene.render(a).rgb, render(ctx, a).rgb);
}

// ---- options -------------------------------------------------------------------------------

TEST(Render, InvalidOptionsAreErrors) {
    const Context ctx = leafAndInternode();
    auto expectError = [&](RenderOptions o, const std::string& parameter) {
        try {
            render(ctx, o);
            ADD_FAILURE() << "expected an Error for " << parameter;
        } catch (const Error& e) {
            EXPECT_EQ(e.parameter(), parameter) << e.what();
        }
    };
    RenderOptions o = small();
    o.width = 0;
    expectError(o, "width");
    o = small();
    o.height = 100000;
    expectError(o, "height");
    o = small();
    o.camera.fovDeg = 180.0f;
    expectError(o, "camera.fovDeg");
    o = small();
    o.samplesPerPixel = 0;
    expectError(o, "samplesPerPixel");
    o = small();
    o.camera.autoFrame = false;
    o.camera.eye = o.camera.target = {1, 1, 1};
    expectError(o, "camera.eye");
    o = small();
    o.sunDirection = {0, 0, 0};
    expectError(o, "sunDirection");
}

// ---- PNG -----------------------------------------------------------------------------------

TEST(RenderPNG, WrittenAndReadBack) {
    TempDir dir;
    const Image img = render(leafAndInternode(), small(64, 48));
    const std::string path = (dir / "out.png").string();
    writePNG(img, path);
    int w = 0, h = 0, n = 0;
    std::uint8_t* data = stbi_load(path.c_str(), &w, &h, &n, 3);
    ASSERT_NE(data, nullptr);
    EXPECT_EQ(w, 64);
    EXPECT_EQ(h, 48);
    EXPECT_EQ(n, 3);
    EXPECT_TRUE(std::equal(img.rgb.begin(), img.rgb.end(), data));
    stbi_image_free(data);
    EXPECT_EQ(readImage(path).rgb, img.rgb);
    // Only the PNG is left: the temporary file was renamed.
    EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 1);
}

TEST(RenderPNG, OverwritesExistingFile) {
    TempDir dir;
    const std::string path = (dir / "out.png").string();
    { std::ofstream(path) << "old"; }
    writePNG(Image(8, 8), path);
    EXPECT_EQ(readImage(path).width, 8);
}

TEST(RenderPNG, UnwritablePathIsAnErrorAndLeavesNothing) {
    TempDir dir;
    const Image img(8, 8);
    const std::string missingDir = (dir / "no" / "such" / "dir" / "x.png").string();
    try {
        writePNG(img, missingDir);
        FAIL() << "expected an Error";
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), missingDir);
    }
    // A directory where the file should go: the rename fails, the temporary is removed.
    fs::create_directory(dir / "taken.png");
    EXPECT_THROW(writePNG(img, (dir / "taken.png").string()), Error);
    EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 1);
    EXPECT_THROW(writePNG(Image(), (dir / "empty.png").string()), Error);
    EXPECT_THROW(readImage((dir / "missing.png").string()), Error);
}

// ---- the plantarch render command -----------------------------------------------------------

namespace {

struct CommandResult {
    int status = -1;
    std::string stderrText;
};

CommandResult runCli(const std::string& args, const fs::path& dir) {
    const fs::path err = dir / "stderr.txt";
    const std::string cmd =
        std::string("\"") + PLANTARCH_CLI + "\" " + args + " 2> \"" + err.string() + "\"";
    const int raw = std::system(cmd.c_str());
    CommandResult r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    std::ifstream in(err);
    r.stderrText.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    return r;
}

/// A box "internode" under a quad "leaf", with group names as plantarch's OBJ writer makes them
/// (obj<ID>_plant<P>_<organ>, and obj<ID>_<organ> for an object of no plant), without the
/// label comments.
void writeSmallObj(const fs::path& path) {
    std::ofstream out(path);
    out << "# two organs\n"
           "g obj0_plant2_internode\n"
           "v -0.05 -0.05 0\nv 0.05 -0.05 0\nv 0.05 0.05 0\nv -0.05 0.05 0\n"
           "v -0.05 -0.05 0.6\nv 0.05 -0.05 0.6\nv 0.05 0.05 0.6\nv -0.05 0.05 0.6\n"
           "f 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\nf 5 6 7 8\n"
           "g obj1_leaf\n"
           "v -0.4 -0.3 0.6\nv 0.4 -0.3 0.6\nv 0.4 0.3 0.9\nv -0.4 0.3 0.9\n"
           "f 9 10 11 12\n";
}

}  // namespace

TEST(RenderCli, RendersAnObjFile) {
    TempDir dir;
    writeSmallObj(dir / "in.obj");
    const fs::path png = dir / "out.png";
    const auto r = runCli("render \"" + (dir / "in.obj").string() + "\" -o \"" + png.string() +
                              "\" --width 96 --height 64",
                          dir.path());
    ASSERT_EQ(r.status, 0) << r.stderrText;
    const Image img = readImage(png.string());
    EXPECT_EQ(img.width, 96);
    EXPECT_EQ(img.height, 64);
    EXPECT_GT(colours(img).size(), 10u);
}

TEST(RenderCli, LabelMaskAndExplicitCamera) {
    TempDir dir;
    writeSmallObj(dir / "in.obj");
    const fs::path png = dir / "mask.png";
    const auto r = runCli("render \"" + (dir / "in.obj").string() + "\" -o \"" + png.string() +
                              "\" --width 80 --height 60 --label organ --no-ground"
                              " --eye 2,-2,1.5 --target 0,0,0.4 --fov 40",
                          dir.path());
    ASSERT_EQ(r.status, 0) << r.stderrText;
    // Organ labels come back from the group names obj<ID>[_plant<P>]_<organ>.
    const std::set<RGB> expected = {
        {0, 0, 0}, organLabelColor("leaf"), organLabelColor("internode")};
    EXPECT_EQ(colours(readImage(png.string())), expected);
}

// A PLY or GLB plantarch wrote renders with its organ labels, as the OBJ of the same scene does;
// --orbit turns the auto-framed view.
TEST(RenderCli, RendersPlyAndGlbFilesWithTheirLabelsAndAnOrbitView) {
    TempDir dir;
    Context ctx;
    writeSmallObj(dir / "in.obj");
    const std::vector<ObjectID> ids = readOBJ(ctx, (dir / "in.obj").string());
    ASSERT_EQ(ids.size(), 2u);  // the organs its group names give
    ctx.setObjectData(ids[0], "organ", std::string("internode"));
    ctx.setObjectData(ids[1], "organ", std::string("leaf"));
    writePLY(ctx, (dir / "in.ply").string());
    const std::string common = " --width 80 --height 60 --label organ --no-ground";
    const auto fromPly = runCli("render \"" + (dir / "in.ply").string() + "\" -o \"" +
                                    (dir / "ply.png").string() + "\"" + common,
                                dir.path());
    ASSERT_EQ(fromPly.status, 0) << fromPly.stderrText;
    const auto fromObj = runCli("render \"" + (dir / "in.obj").string() + "\" -o \"" +
                                    (dir / "obj.png").string() + "\"" + common,
                                dir.path());
    ASSERT_EQ(fromObj.status, 0) << fromObj.stderrText;
    writeGLTF(ctx, (dir / "in.glb").string());
    const auto fromGlb = runCli("render \"" + (dir / "in.glb").string() + "\" -o \"" +
                                    (dir / "glb.png").string() + "\"" + common,
                                dir.path());
    ASSERT_EQ(fromGlb.status, 0) << fromGlb.stderrText;
    const Image ply = readImage((dir / "ply.png").string());
    EXPECT_EQ(ply.rgb, readImage((dir / "obj.png").string()).rgb);
    EXPECT_EQ(readImage((dir / "glb.png").string()).rgb, ply.rgb);
    EXPECT_TRUE(colours(ply).count(organLabelColor("leaf")));
    const auto turned = runCli("render \"" + (dir / "in.ply").string() + "\" -o \"" +
                                   (dir / "top.png").string() + "\"" + common + " --orbit 0,89",
                               dir.path());
    ASSERT_EQ(turned.status, 0) << turned.stderrText;
    EXPECT_NE(readImage((dir / "top.png").string()).rgb, ply.rgb);
}

TEST(RenderCli, BadInputExitsWithStatus2AndOneLine) {
    TempDir dir;
    writeSmallObj(dir / "in.obj");
    std::ofstream(dir / "in.stl") << "solid x\n";
    const std::string in = "\"" + (dir / "in.obj").string() + "\"";
    const std::string out = " -o \"" + (dir / "out.png").string() + "\"";
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"render \"" + (dir / "missing.obj").string() + "\"" + out, "missing.obj"},
        {"render " + in + out + " --eye 1,2", "--eye"},
        {"render " + in + out + " --eye 1,2,3 --target a,b,c", "--target"},
        {"render " + in + out + " --label leaves", "--label"},
        {"render " + in + out + " --orbit 10,95", "--orbit"},
        {"render " + in + out + " --orbit 10", "--orbit"},
        {"render " + in + out + " --orbit 10,20 --eye 1,1,1", "--orbit"},
        {"render \"" + (dir / "in.stl").string() + "\"" + out, "valid: .obj, .ply, .glb or .gltf"},
        {"render " + in + " -o /proc/x.png", "/proc/x.png: cannot write in folder /proc"},
        {"render " + in + " -o \"" + (dir / "out.obj").string() + "\"",
         "out.obj: '.obj': render writes a PNG picture (valid: .png)"},
        {"render \"" + dir.path().string() + "\"" + out, "is a directory, not a scene file"},
    };
    for (const auto& [args, mentions] : cases) {
        const auto r = runCli(args, dir.path());
        EXPECT_EQ(r.status, 2) << args << "\n" << r.stderrText;
        EXPECT_EQ(std::count(r.stderrText.begin(), r.stderrText.end(), '\n'), 1) << r.stderrText;
        EXPECT_NE(r.stderrText.find(mentions), std::string::npos) << r.stderrText;
    }
    EXPECT_FALSE(fs::exists(dir / "out.png"));
    EXPECT_FALSE(fs::exists(dir / "out.obj"));
}

// ---- docs images -----------------------------------------------------------------------------

// Regenerates docs/images/render-demo.png (shaded) and render-demo-organs.png (organ mask)
// when PLANTARCH_WRITE_DOCS_IMAGES is set; otherwise renders the same scene small as a check.
TEST(RenderDocs, DemoImages) {
    Context ctx;
    test::addDemoScene(ctx);
    const bool write = std::getenv("PLANTARCH_WRITE_DOCS_IMAGES") != nullptr;
    RenderOptions o;
    if (write) {
        o.samplesPerPixel = 16;
    } else {
        o.width = 128;
        o.height = 96;
    }
    RenderScene scene(ctx);
    const Image shaded = scene.render(o);
    o.mode = RenderMode::LabelOrgan;
    const Image organs = scene.render(o);
    EXPECT_NE(shaded.rgb, organs.rgb);
    if (!write) return;
    const fs::path dir = fs::path(PLANTARCH_SOURCE_DIR) / "docs" / "images";
    fs::create_directories(dir);
    writePNG(shaded, (dir / "render-demo.png").string());
    writePNG(organs, (dir / "render-demo-organs.png").string());
}
