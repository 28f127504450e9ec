// Depth images: the distance along the view axis to what each pixel sees, 0 where nothing is
// hit; the .npy file numpy reads; the picture; and the render command's depth output.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_run.h"
#include "plantarch/Context.h"
#include "plantarch/Export.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/Render.h"

using namespace plantarch;
namespace fs = std::filesystem;

namespace {

// A horizontal square of side `side` at height z, centred on the origin.
void addSquare(Context& ctx, float side, float z) {
    Mesh m;
    const float h = side / 2;
    m.positions = {{-h, -h, z}, {h, -h, z}, {h, h, z}, {-h, h, z}};
    m.indices = {0, 1, 2, 0, 2, 3};
    ctx.addObject(m, Material{});
}

RenderOptions lookingDown(float height) {
    RenderOptions o;
    o.width = 64;
    o.height = 48;
    o.groundPlane = false;
    o.camera.autoFrame = false;
    o.camera.eye = {0.0f, 0.0f, height};
    o.camera.target = {0.0f, 0.0f, 0.0f};
    o.camera.up = {0.0f, 1.0f, 0.0f};
    o.camera.fovDeg = 40.0f;
    return o;
}

std::string readAll(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

}  // namespace

TEST(Depth, APlaneFacingTheCameraIsAtOneDepthAndTheSkyAtZero) {
    Context ctx;
    addSquare(ctx, 0.5f, 0.25f);  // 1.75 m below an eye at 2 m, seen in the middle only
    const DepthImage d = renderDepth(ctx, lookingDown(2.0f));
    ASSERT_EQ(d.width, 64);
    ASSERT_EQ(d.depth.size(), 64u * 48u);
    std::size_t hits = 0;
    for (int y = 0; y < d.height; ++y)
        for (int x = 0; x < d.width; ++x) {
            const float v = d.at(x, y);
            if (v == 0.0f) continue;
            ++hits;
            // Along the view axis, not along the ray: the same over the whole plane.
            EXPECT_NEAR(v, 1.75f, 1e-5f) << x << "," << y;
        }
    EXPECT_GT(hits, 100u);
    EXPECT_LT(hits, 64u * 48u);  // the corners see nothing
    EXPECT_EQ(d.at(0, 0), 0.0f);
    EXPECT_NEAR(d.at(32, 24), 1.75f, 1e-5f);

    // The nearer of two surfaces; the ground plane, when on, fills the rest.
    addSquare(ctx, 0.2f, 1.0f);
    RenderOptions o = lookingDown(2.0f);
    o.groundPlane = true;
    const DepthImage two = renderDepth(ctx, o);
    EXPECT_NEAR(two.at(32, 24), 1.0f, 1e-5f);
    for (float v : two.depth) EXPECT_GT(v, 0.0f);
}

TEST(Depth, NpyFileIsWhatNumpyReadsAndThePictureIsGreyByDistance) {
    Context ctx;
    addSquare(ctx, 0.5f, 0.25f);
    addSquare(ctx, 0.2f, 1.0f);
    const DepthImage d = renderDepth(ctx, lookingDown(2.0f));
    const fs::path path =
        fs::temp_directory_path() / ("depth_" + std::to_string(::getpid()) + ".npy");
    writeDepthNPY(d, path.string());
    const std::string bytes = readAll(path);
    fs::remove(path);
    ASSERT_EQ(bytes.substr(0, 8), std::string("\x93NUMPY\x01\x00", 8));
    const std::size_t headerLength = std::uint8_t(bytes[8]) | std::size_t(std::uint8_t(bytes[9]))
                                                                  << 8;
    EXPECT_EQ((10 + headerLength) % 64, 0u);
    const std::string header = bytes.substr(10, headerLength);
    EXPECT_EQ(header.rfind("{'descr': '<f4', 'fortran_order': False, 'shape': (48, 64), }", 0), 0u)
        << header;
    EXPECT_EQ(header.back(), '\n');
    ASSERT_EQ(bytes.size(), 10 + headerLength + d.depth.size() * 4);
    EXPECT_EQ(std::memcmp(bytes.data() + 10 + headerLength, d.depth.data(), d.depth.size() * 4), 0);

    const Image picture = depthPicture(d);
    EXPECT_EQ(picture.pixel(32, 24), (std::array<std::uint8_t, 3>{255, 255, 255}));  // nearest
    EXPECT_EQ(picture.pixel(0, 0), (std::array<std::uint8_t, 3>{0, 0, 0}));          // nothing
    // The farther square, seen beside the near one, is the darkest grey.
    EXPECT_EQ(picture.pixel(32, 24 + 8), (std::array<std::uint8_t, 3>{60, 60, 60}));
}

TEST(Depth, RenderCommandWritesDistancesOrAPicture) {
    const fs::path dir = fs::temp_directory_path() / ("depth_cli_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const std::string obj = (dir / "bean.obj").string();
    ASSERT_EQ(cli::run("build bean --age 20 -o " + obj).status, 0);
    cli::Result r = cli::run("render " + obj + " --label depth --width 80 --height 60 -o " +
                             (dir / "d.npy").string());
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_EQ(fs::file_size(dir / "d.npy"), 128u + 80u * 60u * 4u);
    r = cli::run("render " + obj + " --label depth --width 80 --height 60 -o " +
                 (dir / "d.png").string());
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_EQ(readImage((dir / "d.png").string()).width, 80);
    const std::pair<std::string, std::string> bad[] = {
        {"render " + obj + " --label depth -o " + (dir / "d.obj").string(),
         (dir / "d.obj").string() +
             ": '.obj': a depth image is written as .npy (distances) or .png (a picture) "
             "(valid: .png, .npy)"},
        {"render " + obj + " -o " + (dir / "x.npy").string(),
         (dir / "x.npy").string() + ": '.npy': render writes a PNG picture (valid: .png)"},
        {"render " + obj + " --label height -o " + (dir / "x.png").string(),
         "--label = height: unknown label mode (valid: organ, object, depth)"},
    };
    for (const auto& [args, message] : bad) {
        r = cli::run(args);
        EXPECT_EQ(r.status, 2) << args;
        EXPECT_EQ(r.out, "plantarch: " + message + "\n");
    }
    EXPECT_FALSE(fs::exists(dir / "d.obj"));
    fs::remove_all(dir);
}
