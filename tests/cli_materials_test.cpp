// The command line's --materials and --texture-size: textured outputs of build (glTF, USD,
// OBJ, pictures), and every bad value refused with one line and status 2, before any file is
// written.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "cli_run.h"

namespace fs = std::filesystem;
using cli::run;

namespace {

fs::path scratch(const std::string& name) {
    const fs::path p = fs::temp_directory_path() /
                       ("plantarch_cli_materials_" + std::to_string(::getpid()) + "_" + name);
    fs::remove_all(p);
    fs::create_directories(p);
    return p;
}

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

}  // namespace

TEST(CliMaterials, TexturedBuildWritesEveryFormat) {
    const fs::path dir = scratch("formats");
    const std::string d = dir.string();
    const auto r =
        run("--seed 3 build bean --age 20 --materials textured --texture-size 64 "
            "--no-texture-atlas -o " +
            d + "/b.glb -o " + d + "/b.usda -o " + d + "/b.usdz -o " + d +
            "/b.obj --image-size 64x48 -o " + d + "/b.png 2>&1");
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NE(slurp(dir / "b.glb").find("\"baseColorTexture\""), std::string::npos);
    EXPECT_NE(slurp(dir / "b.usda").find("UsdPreviewSurface"), std::string::npos);
    EXPECT_TRUE(fs::exists(dir / "b_leaf_0_basecolor.png"));  // beside the .usda and the .mtl
    EXPECT_NE(slurp(dir / "b.mtl").find("map_Kd b_leaf_0_basecolor.png"), std::string::npos);
    EXPECT_EQ(slurp(dir / "b.usdz").substr(0, 2), "PK");
    EXPECT_TRUE(fs::exists(dir / "b.png"));
    fs::remove_all(dir);
}

// By default the bean's two leaf colours share an atlas, each reading its part through a
// transform; bark and stems keep their own maps.
TEST(CliMaterials, TexturedBuildWritesAnAtlas) {
    const fs::path dir = scratch("atlas");
    const std::string d = dir.string();
    const auto r = run("--seed 3 build bean --age 20 --materials textured --texture-size 64 -o " +
                       d + "/b.glb -o " + d + "/b.usda -o " + d + "/b.obj 2>&1");
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NE(slurp(dir / "b.glb").find("\"extensionsRequired\":[\"KHR_texture_transform\"]"),
              std::string::npos);
    EXPECT_NE(slurp(dir / "b.usda").find("UsdTransform2d"), std::string::npos);
    EXPECT_NE(slurp(dir / "b.mtl").find("map_Kd -o "), std::string::npos);
    EXPECT_TRUE(fs::exists(dir / "b_atlas_basecolor.png"));
    EXPECT_TRUE(fs::exists(dir / "b_bark_0_basecolor.png"));
    EXPECT_FALSE(fs::exists(dir / "b_leaf_0_basecolor.png"));
    fs::remove_all(dir);
}

TEST(CliMaterials, FlatByDefault) {
    const fs::path dir = scratch("flat");
    const std::string d = dir.string();
    ASSERT_EQ(run("--seed 3 build bean --age 10 -o " + d + "/a.glb -o " + d + "/a.obj").status, 0);
    ASSERT_EQ(run("--seed 3 build bean --age 10 --materials flat -o " + d + "/b.glb").status, 0);
    EXPECT_EQ(slurp(dir / "a.glb"), slurp(dir / "b.glb"));
    EXPECT_EQ(slurp(dir / "a.glb").find("\"images\""), std::string::npos);
    EXPECT_EQ(slurp(dir / "a.mtl").find("map_"), std::string::npos);
    fs::remove_all(dir);
}

TEST(CliMaterials, BadValuesAreOneLineAndStatus2) {
    const fs::path dir = scratch("bad");
    for (const std::string value : {"0", "-8", "100", "8", "8192", "nan", "1e9", "abc",
                                    "99999999999999999999", "2147483648"}) {
        const auto r = run("build bean --age 5 --materials textured --texture-size=" + value +
                           " -o " + (dir / "x.glb").string() + " 2>&1");
        EXPECT_EQ(r.status, 2) << value << ": " << r.out;
        EXPECT_NE(r.out.find("--texture-size = " + value), std::string::npos) << r.out;
        EXPECT_NE(r.out.find("a power of two from 16 to 4096"), std::string::npos) << r.out;
        EXPECT_EQ(r.out.find('\n'), r.out.size() - 1) << r.out;  // one line
    }
    const auto r =
        run("build bean --age 5 --materials shiny -o " + (dir / "x.glb").string() + " 2>&1");
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.out.find("--materials = shiny"), std::string::npos) << r.out;
    EXPECT_TRUE(fs::is_empty(dir));
    fs::remove_all(dir);
}

// Texture options without textured materials, and textured materials with no output that
// holds them, are refused before any work instead of being ignored.
TEST(CliMaterials, OptionsThatWouldBeIgnoredAreRefused) {
    const fs::path dir = scratch("ignored");
    const std::string glb = " -o " + (dir / "x.glb").string(),
                      ply = " -o " + (dir / "x.ply").string();
    const std::pair<std::string, std::string> cases[] = {
        {"build bean --age 5 --texture-size 64" + glb,
         "plantarch: --texture-size: needs textured materials (valid: with --materials "
         "textured)\n"},
        {"build bean --age 5 --no-texture-atlas" + glb,
         "plantarch: --no-texture-atlas: needs textured materials (valid: with --materials "
         "textured)\n"},
        {"build bean --age 5 --materials textured" + ply,
         "plantarch: --materials = textured: no output holds textured materials (valid: with an "
         ".obj, .glb, .gltf, .usda, .usdz or .png output)\n"},
        {"canopy bean --age 5 --count 2x1 --materials textured" + ply,
         "plantarch: --materials = textured: no output holds textured materials (valid: with an "
         ".obj, .glb, .gltf, .usda, .usdz or .png output)\n"},
    };
    for (const auto& [args, message] : cases) {
        const auto r = run(args + " 2>&1");
        EXPECT_EQ(r.status, 2) << args;
        EXPECT_EQ(r.out, message) << args;
    }
    EXPECT_TRUE(fs::is_empty(dir));
    // Textured with one output that holds materials beside one that does not is fine.
    const auto ok = run("build bean --age 5 --materials textured --texture-size 16" + ply + glb);
    EXPECT_EQ(ok.status, 0) << ok.out;
    fs::remove_all(dir);
}

TEST(CliMaterials, HelpListsTheOptions) {
    const auto r = run("build --help");
    EXPECT_NE(r.out.find("--materials"), std::string::npos);
    EXPECT_NE(r.out.find("--texture-size"), std::string::npos);
    EXPECT_NE(r.out.find("--no-texture-atlas"), std::string::npos);
    EXPECT_NE(run("render --help").out.find("--materials"), std::string::npos);
}
