// plantarch compare as a user runs it: the two views side by side at one scale with their
// 10 cm bars, a reference picture above, and one-line errors.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_run.h"
#include "plantarch/Render.h"

using namespace plantarch;

namespace {

std::string dir() {
    const auto d = std::filesystem::temp_directory_path() / "plantarch-cli-compare";
    std::filesystem::create_directories(d);
    return d.string();
}

// Length in pixels of the dark horizontal run starting at (x, y).
int darkRun(const Image& im, int x, int y) {
    int n = 0;
    while (x + n < im.width && im.pixel(x + n, y)[0] < 60) ++n;
    return n;
}

}  // namespace

TEST(CliCompare, TwoViewsAtOneScaleWithTenCentimetreBars) {
    const std::string out = dir() + "/bean.png";
    const cli::Result r = cli::run("--seed 1 compare bean --age 30 --panel-size 200 -o " + out);
    ASSERT_EQ(r.status, 0) << r.out;
    const auto at = r.out.find("pixels per metre");
    ASSERT_NE(at, std::string::npos) << r.out;
    const double scale = std::stod(r.out.substr(r.out.rfind(';', at) + 2));
    const Image im = readImage(out);
    // A 44-pixel title strip (plantarch, species, age, height, triangles, seed) above the panels.
    constexpr int kTitle = 44;
    EXPECT_EQ(im.width, 2 * 200 + 2);
    EXPECT_EQ(im.height, kTitle + 200);
    std::size_t ink = 0;
    for (int y = 0; y < kTitle; ++y)
        for (int x = 0; x < im.width; ++x) ink += im.pixel(x, y)[0] < 60;
    EXPECT_GT(ink, 200u) << "the title is written";
    // Each panel's bar, at its bottom left, is 10 cm at the printed scale (within a pixel).
    for (int panel : {0, 1}) {
        const int x0 = panel * 202 + 30, y0 = kTitle + 200 - 25;
        EXPECT_NEAR(darkRun(im, x0, y0), 0.1 * scale + 1, 1.5) << "panel " << panel;
    }
    // The plant fills the larger view to 90 %: some plant pixels, mostly white elsewhere.
    std::size_t white = 0, plant = 0;
    for (int y = kTitle; y < im.height; ++y)
        for (int x = 0; x < 200; ++x) {
            const auto p = im.pixel(x, y);
            white += p[0] == 255 && p[1] == 255 && p[2] == 255;
            plant += p[1] > p[0] + 10;  // green
        }
    EXPECT_GT(plant, 2000u);
    EXPECT_GT(white, 20000u);
}

TEST(CliCompare, AReferencePictureGoesAbove) {
    const std::string d = dir();
    Image ref(300, 120);
    std::fill(ref.rgb.begin(), ref.rgb.end(), std::uint8_t(7));
    writePNG(ref, d + "/ref.png");
    const cli::Result r = cli::run("compare bean --age 20 --panel-size 100 --reference " + d +
                                   "/ref.png -o " + d + "/pair.png");
    ASSERT_EQ(r.status, 0) << r.out;
    const Image im = readImage(d + "/pair.png");
    EXPECT_EQ(im.width, 300);
    EXPECT_EQ(im.height, 120 + 2 + 44 + 100);
    EXPECT_EQ(im.pixel(299, 119), (std::array<std::uint8_t, 3>{7, 7, 7}));
}

// A scene drawn above in the same framing and at the same scale: the plant's own OBJ gives the
// same panels twice (only the titles differ) and the same printed scale as without it.
TEST(CliCompare, ASceneFileIsDrawnAboveAtTheSameScale) {
    const std::string d = dir();
    ASSERT_EQ(cli::run("--seed 1 build bean --age 30 -o " + d + "/bean.obj").status, 0);
    const cli::Result alone =
        cli::run("--seed 1 compare bean --age 30 --panel-size 160 -o " + d + "/alone.png");
    const cli::Result pair = cli::run("--seed 1 compare bean --age 30 --panel-size 160 --against " +
                                      d + "/bean.obj -o " + d + "/pair.png");
    ASSERT_EQ(alone.status, 0) << alone.out;
    ASSERT_EQ(pair.status, 0) << pair.out;
    const auto scaleOf = [](const std::string& out) {
        const auto at = out.find(" pixels per metre");
        if (at == std::string::npos) return std::string();
        const auto from = out.rfind(' ', at - 1) + 1;
        return out.substr(from, at - from);
    };
    EXPECT_FALSE(scaleOf(pair.out).empty()) << pair.out;
    EXPECT_EQ(scaleOf(alone.out), scaleOf(pair.out));
    const Image im = readImage(d + "/pair.png");
    constexpr int kTitle = 44, kPanel = 160;
    ASSERT_EQ(im.width, 2 * kPanel + 2);
    ASSERT_EQ(im.height, 2 * (kTitle + kPanel) + 2);
    std::size_t differ = 0, plant = 0;
    for (int y = kTitle; y < kTitle + kPanel; ++y)
        for (int x = 0; x < im.width; ++x) {
            const auto top = im.pixel(x, y), bottom = im.pixel(x, y + kTitle + kPanel + 2);
            plant += top[1] > top[0] + 10;
            int delta = 0;
            for (int c = 0; c < 3; ++c)
                delta = std::max(delta, std::abs(int(top[c]) - int(bottom[c])));
            differ += delta > 40;
        }
    EXPECT_GT(plant, 1000u);
    // OBJ's smooth normals and colours round to slightly different shades; the shapes agree.
    EXPECT_LT(double(differ), 0.02 * double(plant));
}

TEST(CliCompare, BadInputsAreOneLine) {
    const std::string d = dir();
    std::ofstream(d + "/empty.obj").flush();
    const std::pair<std::string, std::string> cases[] = {
        {"compare bean --age 20 -o " + d + "/x.obj",
         d + "/x.obj: '.obj': the comparison is a picture (valid: .png)"},
        {"compare bean --age 20 --reference " + d + "/none.png -o " + d + "/x.png",
         d + "/none.png: cannot open image file: No such file or directory"},
        {"compare bean --age 20 --panel-size 10 -o " + d + "/x.png",
         "--panel-size = 10: not a panel size (valid: 64 to 4096)"},
        {"compare bean --age 20 --against " + d + "/x.txt -o " + d + "/x.png",
         "--against = " + d + "/x.txt: not a scene file (valid: .obj, .ply, .glb or .gltf)"},
        {"compare bean --age 20 --against " + d + "/none.obj -o " + d + "/x.png",
         d + "/none.obj: cannot open OBJ file: No such file or directory"},
        {"compare bean --age 20 --against " + d + "/empty.obj -o " + d + "/x.png",
         d + "/empty.obj: OBJ file has no faces"},
        {"compare bean --age 20 --against " + d + "/a.obj --reference " + d + "/r.png -o " + d +
             "/x.png",
         "--reference excludes --against"},
    };
    for (const auto& [args, expected] : cases) {
        const cli::Result r = cli::run(args);
        EXPECT_EQ(r.status, 2) << args;
        EXPECT_EQ(r.out, "plantarch: " + expected + "\n") << args;
        EXPECT_FALSE(std::filesystem::exists(d + "/x.png")) << args;
    }
}
