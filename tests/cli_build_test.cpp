// The build and demo subcommands as a user runs them: outputs, summaries, exit codes.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "cli_run.h"

namespace {

using cli::run;
using CliResult = cli::Result;

std::string tmp(const std::string& name) {
    const auto dir = std::filesystem::temp_directory_path() / "plantarch-cli-build";
    std::filesystem::remove_all(dir / name);
    return (dir / name).string();
}

int lines(const std::string& s) {
    return int(std::count(s.begin(), s.end(), '\n'));
}

}  // namespace

TEST(CliBuild, BuildsTheBeanWithASummary) {
    const std::string dir = tmp("bean");
    const CliResult r = run("build bean --age 30 -o " + dir + "/b.obj -o " + dir + "/b.ply");
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("bean at 30 days (seed 42)"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("leaves"), std::string::npos);
    EXPECT_GT(std::filesystem::file_size(dir + "/b.obj"), 10000u);
    EXPECT_GT(std::filesystem::file_size(dir + "/b.ply"), 10000u);
}

TEST(CliBuild, StatsIsOneJSONObjectAndSeedsDiffer) {
    const CliResult a = run("--seed 3 build bean --age 25 -o " + tmp("s1") + "/x.ply --stats");
    const CliResult b = run("--seed 3 build bean --age 25 -o " + tmp("s2") + "/x.ply --stats");
    const CliResult c = run("--seed 4 build bean --age 25 -o " + tmp("s3") + "/x.ply --stats");
    ASSERT_EQ(a.status, 0) << a.out;
    EXPECT_EQ(lines(a.out), 1);
    EXPECT_EQ(a.out.front(), '{');
    for (const char* key :
         {"\"species\": \"bean\"", "\"age\": 25", "\"seed\": 3", "\"height\"", "\"leaves\"",
          "\"leaf_area\"", "\"shoots\"", "\"flowers\"", "\"fruit\"", "\"triangles\""})
        EXPECT_NE(a.out.find(key), std::string::npos) << key;
    EXPECT_EQ(a.out, b.out);  // same seed, same plant
    EXPECT_NE(a.out, c.out);
}

TEST(CliBuild, StatsAloneWritesNoFile) {
    const CliResult b = run("--seed 3 build bean --age 10 --stats");
    ASSERT_EQ(b.status, 0) << b.out;
    EXPECT_EQ(lines(b.out), 1);
    EXPECT_EQ(b.out.rfind("{\"species\": \"bean\"", 0), 0u) << b.out;
    // The same statistics as a build that also writes a file, options after the command too.
    const CliResult w = run("build bean --age 10 --seed 3 --stats -o " + tmp("stats") + "/b.ply");
    EXPECT_EQ(b.out, w.out);
    const CliResult c = run("canopy bean --count 2x2 --age 10 --stats");
    ASSERT_EQ(c.status, 0) << c.out;
    EXPECT_EQ(lines(c.out), 4);
}

TEST(CliBuild, RepeatedOptionsTakeOneValueEach) {
    // -o before the species: the species is still the positional argument.
    const std::string dir = tmp("order");
    const CliResult r =
        run("build -o " + dir + "/a.ply bean --age 3 -o " + dir + "/a.obj --seed 2");
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_TRUE(std::filesystem::exists(dir + "/a.ply"));
    EXPECT_TRUE(std::filesystem::exists(dir + "/a.obj"));
}

TEST(CliBuild, BadInputIsOneLineAndStatus2) {
    // Each bad input: exit status 2 and exactly this one line, naming the parameter, the
    // value and the valid range.
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"build nosuch --age 10 -o /tmp/x.obj",
         "plantarch: species = nosuch: unknown species (valid: one of: almond, almond_aldrich, "
         "almond_wood_colony, apple, apple_fruitingwall, asparagus, bean, bindweed, "
         "bougainvillea, butterlettuce, capsicum, cheeseweed, cherrytomato, cowpea, "
         "easternredbud, grapevine_VSP, grapevine_Wye, groundcherryweed, maize, olive, "
         "pistachio, puncturevine, rice, sorghum, soybean, strawberry, sugarbeet, tomato, "
         "walnut, wheat)\n"},
        {"build bean --age -3 -o /tmp/x.obj",
         "plantarch: --age = -3: not a number of days (valid: 0 to 100000)\n"},
        {"build bean --age 10 -o /tmp/x.stl",
         "plantarch: /tmp/x.stl: '.stl': unknown output format (valid: .obj, .ply, .glb, .gltf, "
         ".usda, .usdz, .png, .npz, .xml, .helios.xml, .txt, .csv, .skeleton.csv, .mtg)\n"},
        {"build bean --age 10 -D foo -o /tmp/x.obj",
         "plantarch: -D = foo: a build parameter is written name=value (valid: name=value)\n"},
        {"build bean --age 10 -D trunk_height=1 -o /tmp/x.obj",
         "plantarch: trunk_height = 1: unknown build parameter of species 'bean' (valid: the "
         "species has no build parameters)\n"},
        {"build bean -o /tmp/x.obj",
         "plantarch: --age is required (or --frames for a growth animation)\n"},
        {"build bean --age 5",
         "plantarch: --output is required (or --stats for the statistics alone)\n"},
        {"canopy bean --age 5 --separate --stats",
         "plantarch: --separate: --separate writes files: give -o FILE\n"},
        {"build bean --frames 0:5 --stats",
         "plantarch: --frames writes an animation: give -o FILE (.glb, .gltf, .usda)\n"},
        {"build bean --age 10 -o /tmp/x.png --image-size 32",
         "plantarch: --image-size = 32: image size is WIDTHxHEIGHT in pixels (valid: 16x16 to "
         "16384x16384)\n"},
        {"build bean --age 10abc -o /tmp/x.obj",
         "plantarch: --age = 10abc: not a number of days (valid: 0 to 100000)\n"},
        {"build bean --age 10 --bogus -o /tmp/x.obj",
         "plantarch: build: unknown option '--bogus' (valid: the options in 'plantarch build "
         "--help')\n"},
        {"build bean --age 10 --stat",
         "plantarch: build: unknown option '--stat', did you mean '--stats'? (valid: the options "
         "in 'plantarch build --help')\n"},
        {"build bean tomato --age 10 -o /tmp/x.obj",
         "plantarch: build: unexpected argument 'tomato' (valid: the arguments in 'plantarch "
         "build --help')\n"},
        // Global options, before or after the command.
        {"--seed -1 build bean --age 10 -o /tmp/x.obj",
         "plantarch: --seed = -1: not a seed (valid: a whole number from 0 to "
         "18446744073709551615)\n"},
        {"build bean --age 10 --seed 18446744073709551616 -o /tmp/x.obj",
         "plantarch: --seed = 18446744073709551616: not a seed (valid: a whole number from 0 to "
         "18446744073709551615)\n"},
        {"--seed 1.5 build bean --age 10 -o /tmp/x.obj",
         "plantarch: --seed = 1.5: not a seed (valid: a whole number from 0 to "
         "18446744073709551615)\n"},
        {"build bean --age 10 --threads -1 -o /tmp/x.obj",
         "plantarch: --threads = -1: not a thread count (valid: 0 to 1024, 0 for every core)\n"},
        // Commands.
        {"bulid bean --age 10",
         "plantarch: 'bulid' is not a command, did you mean 'build'? (valid: demo, build, "
         "canopy, convert, project, grow, reconstruct, field, render, scan, light, compare, list, "
         "info, fit, validate, builder, dataset)\n"},
        {"nosuchcommand",
         "plantarch: 'nosuchcommand' is not a command (valid: demo, build, canopy, convert, "
         "project, grow, reconstruct, field, render, scan, light, compare, list, info, fit, "
         "validate, builder, dataset)\n"},
        {"",
         "plantarch: a command is required (valid: demo, build, canopy, convert, project, "
         "grow, reconstruct, field, render, scan, light, compare, list, info, fit, validate, "
         "builder, dataset; see plantarch --help)\n"},
        // Canopies.
        {"canopy bean --count 0x2 --age 10 -o /tmp/x.ply",
         "plantarch: --count = 0x2: expected two positive numbers joined by 'x' (valid: e.g. "
         "10x10 or 0.3x0.3)\n"},
        {"canopy bean --count 2x2 --spacing -1x1 --age 10 -o /tmp/x.ply",
         "plantarch: --spacing = -1x1: expected two positive numbers joined by 'x' (valid: e.g. "
         "10x10 or 0.3x0.3)\n"},
        {"canopy bean --count 2x2 --age 1e9 -o /tmp/x.ply",
         "plantarch: --age = 1e9: not a number of days (valid: 0 to 100000)\n"},
        {"canopy bean --count 2x2 --age 10 --germination 2 -o /tmp/x.ply",
         "plantarch: --germination = 2: not a probability (valid: 0 to 1)\n"},
        // Render, info, validate.
        {"render /tmp/x.obj -o /tmp/x.png --width 10.5",
         "plantarch: --width = 10.5: not a width in pixels (valid: 1 to 16384)\n"},
        {"render /tmp/x.obj -o /tmp/x.png --samples 0",
         "plantarch: --samples = 0: not a ray count (valid: 1 to 1024)\n"},
        {"render /tmp/x.obj -o /tmp/x.png --fov 180",
         "plantarch: --fov = 180: not a field of view (valid: 0.01 to 170 degrees)\n"},
        {"validate /nonexistent/species.xml",
         "plantarch: /nonexistent/species.xml: cannot open species file: No such file or "
         "directory\n"},
    };
    for (const auto& [args, message] : cases) {
        const CliResult r = run(args);
        EXPECT_EQ(r.status, 2) << args << ": " << r.out;
        EXPECT_EQ(r.out, message) << args;
    }
}

TEST(CliBuild, DemoWritesObjAndPng) {
    const std::string dir = tmp("demo");
    const CliResult r = run("demo -o " + dir);
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_TRUE(std::filesystem::exists(dir + "/demo.obj"));
    EXPECT_TRUE(std::filesystem::exists(dir + "/demo.png"));
    EXPECT_NE(r.out.find("Demo plant"), std::string::npos);
}

TEST(CliBuild, VersionAndHelp) {
    const CliResult v = run("--version");
    EXPECT_EQ(v.status, 0);
    EXPECT_NE(v.out.find("plantarch 0.1.0"), std::string::npos);
    const CliResult h = run("--help");
    EXPECT_EQ(h.status, 0);
    for (const char* sub : {"demo", "build", "render", "list", "info", "validate"})
        EXPECT_NE(h.out.find(sub), std::string::npos) << sub;
}

TEST(CliBuild, CanopyCommand) {
    const std::string dir = tmp("canopy");
    const CliResult r =
        run("canopy bean --count 3x2 --spacing 0.3x0.4 --age 15 -o " + dir + "/c.ply --stats");
    ASSERT_EQ(r.status, 0) << r.out;
    // One JSON object per plant, in plant order.
    EXPECT_EQ(lines(r.out), 6) << r.out;
    for (int p = 0; p < 6; ++p)
        EXPECT_NE(r.out.find("\"plant\": " + std::to_string(p) + ", \"age\": 15"),
                  std::string::npos)
            << r.out;
    EXPECT_TRUE(std::filesystem::exists(dir + "/c.ply"));
    // Build parameters reach every plant of a canopy, and are checked.
    const CliResult trees =
        run("canopy almond --count 2x1 --spacing 3x3 --age 0 -D trunk_height=1.2 -o " + dir +
            "/a.obj --stats");
    ASSERT_EQ(trees.status, 0) << trees.out;
    EXPECT_EQ(lines(trees.out), 2) << trees.out;
    const CliResult bad =
        run("canopy almond --count 2x1 --age 0 -D trunk_height=9 -o " + dir + "/a.obj");
    EXPECT_EQ(bad.status, 2) << bad.out;
    EXPECT_NE(bad.out.find("trunk_height"), std::string::npos) << bad.out;
    for (const std::string args :
         {"canopy bean --count 3 --age 5 -o /tmp/c.ply",
          "canopy bean --count 2x2 --spacing 0x1 --age 5 -o /tmp/c.ply",
          "canopy bean --count 2x2 --germination 2 --age 5 -o /tmp/c.ply"}) {
        const CliResult bad = run(args);
        EXPECT_EQ(bad.status, 2) << args << ": " << bad.out;
        EXPECT_EQ(lines(bad.out), 1) << args << ": " << bad.out;
    }
}
