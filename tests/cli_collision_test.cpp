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

// Each bad collision option: exit status 2 and exactly this one line, naming the file and
// line, the option, the value and the valid range.
TEST(CliCollision, BadValuesAndFilesAreOneLineErrors) {
    const std::string wall = write("wall2.obj", kWall);
    const std::string bad = write("bad.csv", "0,0,1\n1,2\n");
    const std::string empty = write("empty.csv", "# nothing\n");
    const std::string d = dir(), o = " -o " + d + "/x.ply";
    const std::string cone = "(valid: half-angle,look-ahead,rays,inertia e.g. 80,0.1,256,0.4)";
    const std::pair<std::string, std::string> cases[] = {
        {"build bean --age 10 --cone 80,0.1,256,0.4" + o,
         "--cone = 80,0.1,256,0.4: the soft avoidance cone applies only with soft avoidance "
         "(valid: with --soft-collision)"},
        {"build bean --age 10 --soft-collision --cone 80,0.1,256" + o,
         "--cone = 80,0.1,256: expected 4 numbers separated by commas " + cone},
        {"build bean --age 10 --soft-collision --cone 200,0.1,256,0.4" + o,
         "--cone (view_half_angle_deg) = 200: collision option out of range (valid: > 0 and < "
         "180 degrees)"},
        {"build bean --age 10 --soft-collision --cone 80,-1,256,0.4" + o,
         "--cone (look_ahead_distance) = -1: collision option out of range (valid: > 0 and <= "
         "100 m)"},
        {"build bean --age 10 --soft-collision --cone 80,0.1,3,0.4" + o,
         "--cone (ray_count) = 80,0.1,3,0.4: ray count out of range (valid: a whole number "
         "from 8 to 16384)"},
        {"build bean --age 10 --soft-collision --cone 80,0.1,256,2" + o,
         "--cone (inertia) = 2: collision option out of range (valid: 0 to 1)"},
        {"build bean --age 10 --obstacle " + d + "/missing.obj" + o,
         d + "/missing.obj: --obstacle: cannot open obstacle file: No such file or directory"},
        {"build bean --age 10 --obstacle " + wall + " --avoid-distance -0.2" + o,
         "--avoid-distance (avoidance_distance) = -0.2: collision option out of range (valid: "
         "> 0 and <= 100 m)"},
        {"build bean --age 10 --obstacle " + wall + " --avoid-distance x" + o,
         "--avoid-distance = x: expected a number (valid: a distance in m, e.g. 0.2)"},
        {"build bean --age 10 --avoid-distance 0.2" + o,
         "--avoid-distance = 0.2: the avoidance distance applies only to obstacles (valid: "
         "with --obstacle FILE.obj)"},
        {"build bean --age 10 --fruit-adjustment" + o,
         "--fruit-adjustment: fruit adjustment applies only to obstacles (valid: with "
         "--obstacle FILE.obj)"},
        {"build bean --age 10 --attraction-points " + bad + o,
         bad +
             ":2: --attraction-points = 1,2: expected three finite numbers x,y,z (m) (valid: e.g. "
             "0.5,0,1.2)"},
        {"build bean --age 10 --attraction-points " + empty + o,
         empty + ": --attraction-points: attraction point file holds no points (valid: lines "
                 "of x,y,z)"},
        {"build bean --age 10 --attraction-points " + d + "/none.csv" + o,
         d + "/none.csv: --attraction-points: cannot open attraction point file: No such file or directory"},
        {"build bean --age 10 --attraction-points " + empty + " --attraction-cone 80,1" + o,
         "--attraction-cone = 80,1: expected 3 numbers separated by commas (valid: "
         "half-angle,look-ahead,inertia e.g. 80,0.1,0.4)"},
        {"build bean --age 10 --attraction-cone 80,0.1,0.4" + o,
         "--attraction-cone = 80,0.1,0.4: the attraction cone applies only with attraction "
         "points (valid: with --attraction-points FILE.csv)"},
        {"canopy bean --count 2x2 --age 10 --soft-collision --cone 80,0.1,256,x" + o,
         "--cone = 80,0.1,256,x: expected 4 numbers separated by commas " + cone},
    };
    for (const auto& [args, expected] : cases) {
        const CliResult r = run(args);
        EXPECT_EQ(r.status, 2) << args << "\n" << r.out;
        EXPECT_EQ(r.out, "plantarch: " + expected + "\n") << args;
        EXPECT_FALSE(std::filesystem::exists(d + "/x.ply")) << args;
    }
}
