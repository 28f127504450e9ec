// The collision options of `build` and `canopy` as a user runs them: geometry written,
// same bytes for any thread count, and one-line errors with exit status 2.

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "cli_run.h"
#include "plantarch/Export.h"

using namespace plantarch;

namespace {

using cli::run;
using CliResult = cli::Result;

std::string dir() {
    const auto d = std::filesystem::temp_directory_path() / "plantarch-cli-collision";
    std::filesystem::create_directories(d);
    return d.string();
}

std::string write(const std::string& name, const std::string& text) {
    const std::string path = dir() + "/" + name;
    std::ofstream(path) << text;
    return path;
}

std::string bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// A wall: the plane x = 0.12 from y = -1 to 1, z = 0 to 1.5.
const char* kWall = "v 0.12 -1 0\nv 0.12 1 0\nv 0.12 1 1.5\nv 0.12 -1 1.5\nf 1 2 3 4\n";

}  // namespace

TEST(CliCollision, ObstacleIsWrittenAndNeverCrossed) {
    const std::string wall = write("wall.obj", kWall);
    const std::string out = dir() + "/wall_bean.obj";
    const CliResult r =
        run("build bean --age 45 --obstacle " + wall + " --avoid-distance 0.2 -o " + out);
    ASSERT_EQ(r.status, 0) << r.out;
    Context ctx;
    readOBJ(ctx, out);
    float maxX = -1e30f;
    int walls = 0;
    ctx.forEachObject([&](const ObjectView& v) {
        const std::string name = ctx.objectDataString(v.id, "name").value_or("");
        if (name.find("obstacle") != std::string::npos) {
            ++walls;
            return;
        }
        for (const vec3& p : v.positions) maxX = std::max(maxX, p.x);
    });
    EXPECT_EQ(walls, 1);  // the wall is part of the scene written
    EXPECT_LE(maxX, 0.12f);
    EXPECT_GT(maxX, 0.05f);  // the plant did reach toward it
}

TEST(CliCollision, SoftCanopyIsTheSameForOneAndTwoThreads) {
    const std::string a = dir() + "/soft1.ply", b = dir() + "/soft2.ply", c = dir() + "/hard.ply";
    const std::string args = " canopy bean --count 2x2 --spacing 0.15x0.15 --age 25 ";
    ASSERT_EQ(run("--threads 1" + args + "--soft-collision --cone 70,0.12,128,0.3 -o " + a).status,
              0);
    ASSERT_EQ(run("--threads 2" + args + "--soft-collision --cone 70,0.12,128,0.3 -o " + b).status,
              0);
    ASSERT_EQ(run("--threads 2" + args + "-o " + c).status, 0);
    EXPECT_EQ(bytes(a), bytes(b));
    EXPECT_NE(bytes(a), bytes(c));  // and avoidance changed the plants
}

TEST(CliCollision, AttractionPointsFromACsvFile) {
    const std::string points =
        write("points.csv", "x,y,z  # header\n0.3,0,0.3\n0.3,0,0.35\n\n0.3,0,0.4\n");
    const std::string out = dir() + "/attracted.ply";
    const CliResult r = run("build bean --age 30 --attraction-points " + points +
                            " --attraction-cone 80,0.3,0.2 -o " + out);
    ASSERT_EQ(r.status, 0) << r.out;
    const CliResult plain = run("build bean --age 30 -o " + dir() + "/plain.ply");
    ASSERT_EQ(plain.status, 0);
    EXPECT_NE(bytes(out), bytes(dir() + "/plain.ply"));
}

TEST(CliCollision, BadValuesAndFilesAreOneLineErrors) {
    const std::string wall = write("wall2.obj", kWall);
    const std::string bad = write("bad.csv", "0,0,1\n1,2\n");
    const std::string empty = write("empty.csv", "# nothing\n");
    const std::string o = " -o " + dir() + "/x.ply";
    const std::pair<std::string, std::string> cases[] = {
        {"build bean --age 10 --cone 80,0.1,256,0.4" + o, "add --soft-collision"},
        {"build bean --age 10 --soft-collision --cone 80,0.1,256" + o, "expected 4 numbers"},
        {"build bean --age 10 --soft-collision --cone 200,0.1,256,0.4" + o, "view_half_angle_deg"},
        {"build bean --age 10 --soft-collision --cone 80,-1,256,0.4" + o, "look_ahead_distance"},
        {"build bean --age 10 --soft-collision --cone 80,0.1,3,0.4" + o, "8 to 16384"},
        {"build bean --age 10 --soft-collision --cone 80,0.1,256,2" + o, "inertia"},
        {"build bean --age 10 --obstacle " + dir() + "/missing.obj" + o,
         "cannot open obstacle file"},
        {"build bean --age 10 --obstacle " + wall + " --avoid-distance -0.2" + o,
         "avoidance_distance"},
        {"build bean --age 10 --obstacle " + wall + " --avoid-distance x" + o, "expected a number"},
        {"build bean --age 10 --avoid-distance 0.2" + o, "add --obstacle"},
        {"build bean --age 10 --fruit-adjustment" + o, "add --obstacle"},
        {"build bean --age 10 --attraction-points " + bad + o, "bad.csv:2"},
        {"build bean --age 10 --attraction-points " + empty + o, "holds no points"},
        {"build bean --age 10 --attraction-points " + dir() + "/none.csv" + o, "cannot open"},
        {"canopy bean --count 2x2 --age 10 --soft-collision --cone 80,0.1,256,x" + o, "--cone"},
    };
    for (const auto& [args, expected] : cases) {
        const CliResult r = run(args);
        EXPECT_EQ(r.status, 2) << args << "\n" << r.out;
        EXPECT_NE(r.out.find(expected), std::string::npos) << args << "\n" << r.out;
        EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
    }
}
