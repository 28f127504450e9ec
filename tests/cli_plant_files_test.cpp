// The convert and grow subcommands and .xml/.txt outputs of build and canopy, as a user
// runs them: saved plants grow on exactly as if never saved; conversions; clear errors.

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

#include "cli_run.h"
#include "plant_geometry_bytes.h"

namespace {

using cli::run;
using CliResult = cli::Result;

std::string dir(const std::string& name) {
    const auto d = std::filesystem::temp_directory_path() / "plantarch-cli-plant-files" / name;
    std::filesystem::remove_all(d);
    std::filesystem::create_directories(d);
    return d.string();
}

using plantarch::testing::fileBytes;
using plantarch::testing::firstDifference;

}  // namespace

TEST(CliPlantFiles, SavedPlantGrowsOnAsIfNeverSaved) {
    const std::string d = dir("grow");
    CliResult r = run("build bean --age 35 -o " + d + "/b35.xml");
    ASSERT_EQ(r.status, 0) << r.out;
    r = run("grow " + d + "/b35.xml --days 15 -o " + d + "/b50.xml -o " + d + "/b50.ply");
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("1 plant(s) grown 15 days"), std::string::npos) << r.out;
    r = run("build bean --age 50 -o " + d + "/direct.xml");
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_EQ(firstDifference(fileBytes(d + "/b50.xml"), fileBytes(d + "/direct.xml")), "");
    EXPECT_GT(std::filesystem::file_size(d + "/b50.ply"), 100000u);
}

// A trellis plant's file holds its wires (attraction points): grown on, it follows them.
TEST(CliPlantFiles, SavedTrellisPlantGrowsOnAsIfNeverSaved) {
    const std::string d = dir("trellis");
    CliResult r = run("build apple_fruitingwall --age 200 -o " + d + "/a200.xml");
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NE(fileBytes(d + "/a200.xml").find("<attraction_points>"), std::string::npos);
    r = run("grow " + d + "/a200.xml --days 100 -o " + d + "/a300.xml");
    ASSERT_EQ(r.status, 0) << r.out;
    r = run("build apple_fruitingwall --age 300 -o " + d + "/direct.xml");
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_EQ(firstDifference(fileBytes(d + "/a300.xml"), fileBytes(d + "/direct.xml")), "");
}

TEST(CliPlantFiles, ConvertsBetweenFormats) {
    const std::string d = dir("convert");
    ASSERT_EQ(
        run("canopy cowpea --count 2x1 --age 20 -o " + d + "/c.xml -o " + d + "/c.txt").status, 0);
    // Two plant strings, one per line.
    const std::string strings = fileBytes(d + "/c.txt");
    EXPECT_EQ(std::count(strings.begin(), strings.end(), '\n'), 2);
    EXPECT_EQ(strings.rfind("@cowpea(", 0), 0u);

    CliResult r = run("convert " + d + "/c.xml " + d + "/c.obj");
    ASSERT_EQ(r.status, 0) << r.out;
    r = run("convert " + d + "/c.xml " + d + "/c.png --image-size 64x48");
    ASSERT_EQ(r.status, 0) << r.out;
    r = run("convert " + d + "/c.obj " + d + "/c.ply");  // geometry only
    ASSERT_EQ(r.status, 0) << r.out;
    r = run("convert " + d + "/c.xml " + d + "/again.xml");
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_EQ(firstDifference(fileBytes(d + "/again.xml"), fileBytes(d + "/c.xml")), "");
    // Plant strings read back with their species and write the same strings.
    r = run("convert " + d + "/c.txt " + d + "/again.txt --species cowpea");
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_EQ(fileBytes(d + "/again.txt"), strings);
    for (const char* f : {"c.obj", "c.mtl", "c.png", "c.ply"})
        EXPECT_GT(std::filesystem::file_size(d + "/" + f), 100u) << f;
}

// Each bad input of convert, grow and the plant outputs: exit status 2 and exactly this line.
TEST(CliPlantFiles, BadInputsExitWithOneLine) {
    const std::string d = dir("errors");
    ASSERT_EQ(run("build bean --age 10 -o " + d + "/b.xml -o " + d + "/b.obj").status, 0);
    const std::pair<std::string, std::string> cases[] = {
        {"convert " + d + "/b.obj " + d + "/x.xml",
         d + "/x.xml: '.xml': an OBJ file holds geometry only, not the plant structure (valid: "
             ".obj, .ply, .glb, .gltf, .usda, .usdz, .png, .npz)"},
        {"convert " + d + "/b.xml " + d + "/x.usdc",
         d + "/x.usdc: '.usdc': unknown output format (valid: .obj, .ply, .glb, .gltf, .usda, "
             ".usdz, .png, .npz, .xml, .helios.xml, .txt, .csv, .skeleton.csv, .mtg)"},
        {"convert " + d + "/missing.xml " + d + "/x.obj",
         d + "/missing.xml: cannot open plant structure file: No such file or directory"},
        {"convert " + d + "/b.xml", "output is required"},
        {"grow " + d + "/b.xml --days -3 -o " + d + "/x.xml",
         "--days = -3: not a number of days (valid: 0 to 100000)"},
        {"grow " + d + "/b.xml --days 3d -o " + d + "/x.xml",
         "--days = 3d: not a number of days (valid: 0 to 100000)"},
        {"grow " + d + "/b.xml -o " + d + "/x.xml",
         "--days is required (or --frames for a growth animation)"},
        {"grow " + d + "/missing.xml --days 3 -o " + d + "/x.xml",
         d + "/missing.xml: cannot open plant structure file: No such file or directory"},
        {"build bean --age 10 --digits 9 -o " + d + "/x.txt",
         "--digits = 9: not a digit count (valid: 1 to 6, or 0 for exact values)"},
    };
    for (const auto& [args, expected] : cases) {
        const CliResult r = run(args);
        EXPECT_EQ(r.status, 2) << args << "\n" << r.out;
        EXPECT_EQ(r.out, "plantarch: " + expected + "\n") << args;
        for (const char* name : {"/x.xml", "/x.obj", "/x.txt", "/x.usdc"})
            EXPECT_FALSE(std::filesystem::exists(d + name)) << args << ": " << name;
    }
}
