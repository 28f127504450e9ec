// Simulated LiDAR scans: first hits only (occlusion), exact ranges without noise and Gaussian
// ones with it, labels of the object hit, the same points whatever the thread count, the PLY
// and NPZ files, the scan command, and one-line errors.

#include "plantarch/Scan.h"

#include <gtest/gtest.h>
#include <omp.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_run.h"
#include "error_of.h"
#include "plantarch/PlantArchitecture.h"

using namespace plantarch;
using plantarch::testing::errorOf;
namespace fs = std::filesystem;

namespace {

ObjectID addSquare(Context& ctx, float side, float z, const char* organ, int plant) {
    Mesh m;
    const float h = side / 2;
    m.positions = {{-h, -h, z}, {h, -h, z}, {h, h, z}, {-h, h, z}};
    m.indices = {0, 1, 2, 0, 2, 3};
    const ObjectID id = ctx.addObject(m, Material{});
    ctx.setObjectData(id, "organ", std::string(organ));
    ctx.setObjectData(id, "plantID", plant);
    return id;
}

// A scanner 1 m above the origin looking down over a cone of 30 degrees.
ScanOptions downward(float resolution = 1.0f) {
    ScanOptions o;
    Scanner s;
    s.origin = {0.0f, 0.0f, 1.0f};
    s.zenithMin = 150.0f;
    s.zenithMax = 180.0f;
    s.resolution = resolution;
    o.scanners.push_back(s);
    return o;
}

std::string readAll(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

}  // namespace

TEST(Scan, RaysOnTheAngleGrid) {
    Scanner s;  // 30..150 by 0.1: 1201 rows; a full turn: 3600 columns
    EXPECT_EQ(scanRayCount(s), 1201u * 3600u);
    s.azimuthMin = 0;
    s.azimuthMax = 90;
    s.resolution = 1;
    s.zenithMin = s.zenithMax = 90;
    EXPECT_EQ(scanRayCount(s), 91u);  // both ends of a part turn
}

TEST(Scan, FirstHitsOnlyWithExactRangesAndLabels) {
    Context ctx;
    const ObjectID floor = addSquare(ctx, 2.0f, 0.0f, "ground", -1);
    const ObjectID leaf = addSquare(ctx, 0.2f, 0.5f, "leaf", 4);
    const PointCloud c = scan(ctx, downward());
    ASSERT_GT(c.positions.size(), 100u);
    ASSERT_EQ(c.range.size(), c.positions.size());
    std::size_t onLeaf = 0;
    for (std::size_t i = 0; i < c.positions.size(); ++i) {
        const vec3 p = c.positions[i];
        EXPECT_NEAR(glm::length(p - vec3(0, 0, 1)), c.range[i], 1e-5f);
        EXPECT_EQ(c.scanner[i], 0);
        EXPECT_GT(c.normals[i].z, 0.999f);  // turned toward the scanner above
        if (c.objectID[i] == leaf) {
            ++onLeaf;
            EXPECT_NEAR(p.z, 0.5f, 1e-5f);
            EXPECT_EQ(c.plantID[i], 4);
            EXPECT_EQ(c.organ[i], 3);  // leaf
        } else {
            EXPECT_EQ(c.objectID[i], floor);
            EXPECT_NEAR(p.z, 0.0f, 1e-5f);
            EXPECT_EQ(c.organ[i], 8);  // ground
            // Occlusion: nothing on the floor in the leaf's shadow from the scanner.
            EXPECT_FALSE(std::abs(p.x) < 0.19f && std::abs(p.y) < 0.19f) << p.x << "," << p.y;
        }
    }
    EXPECT_GT(onLeaf, 10u);
    // Beyond the maximum range nothing comes back.
    ScanOptions near = downward();
    near.maxRange = 0.7f;
    for (ObjectID id : scan(ctx, near).objectID) EXPECT_EQ(id, leaf);
}

TEST(Scan, SamePointsOnAnyThreadCountAndNoiseIsGaussianAlongTheRay) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    arch.buildPlantInstanceFromLibrary(vec3(0.0f), 30);
    ScanOptions o;
    Scanner s;
    s.origin = {0.8f, -0.4f, 0.5f};
    s.resolution = 0.3f;
    o.scanners = {s, s};
    o.scanners[1].origin = {-0.7f, 0.5f, 0.6f};
    o.rangeNoise = 0.01f;
    o.seed = 9;
    const int threads = omp_get_max_threads();
    omp_set_num_threads(1);
    const PointCloud one = scan(ctx, o);
    omp_set_num_threads(2);
    const PointCloud two = scan(ctx, o);
    omp_set_num_threads(threads);
    ASSERT_GT(one.positions.size(), 1000u);
    EXPECT_EQ(one.positions, two.positions);
    EXPECT_EQ(one.range, two.range);
    EXPECT_EQ(one.objectID, two.objectID);
    std::size_t fromSecond = 0;
    for (auto k : one.scanner) fromSecond += k == 1;
    EXPECT_GT(fromSecond, 100u);

    ScanOptions exact = o;
    exact.rangeNoise = 0.0f;
    const PointCloud clean = scan(ctx, exact);
    ASSERT_EQ(clean.positions.size(), one.positions.size());  // noise moves points, adds none
    double sum = 0.0, squares = 0.0;
    for (std::size_t i = 0; i < one.range.size(); ++i) {
        const double d = double(one.range[i]) - double(clean.range[i]);
        sum += d;
        squares += d * d;
        EXPECT_EQ(one.objectID[i], clean.objectID[i]);
    }
    const double n = double(one.range.size());
    EXPECT_NEAR(sum / n, 0.0, 0.001);
    EXPECT_NEAR(std::sqrt(squares / n), 0.01, 0.001);
    ScanOptions other = o;
    other.seed = 10;
    EXPECT_NE(scan(ctx, other).range, one.range);
}

TEST(Scan, PlyAndNpzFilesHoldEveryPoint) {
    Context ctx;
    addSquare(ctx, 1.0f, 0.0f, "leaf", 2);
    const PointCloud c = scan(ctx, downward(2.0f));
    const fs::path dir = fs::temp_directory_path() / ("scan_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    writePointCloudPLY(c, (dir / "s.ply").string());
    const std::string ply = readAll(dir / "s.ply");
    const std::size_t end = ply.find("end_header\n") + 11;
    EXPECT_NE(ply.find("element vertex " + std::to_string(c.positions.size()) + "\n"),
              std::string::npos);
    EXPECT_NE(ply.find("property float range\nproperty ushort scanner\nend_header"),
              std::string::npos);
    ASSERT_EQ(ply.size() - end, c.positions.size() * 55);
    float range = 0.0f;
    std::memcpy(&range, ply.data() + end + 49, 4);
    EXPECT_EQ(range, c.range[0]);

    writePointCloudNPZ(c, (dir / "s.npz").string());
    const std::string npz = readAll(dir / "s.npz");
    EXPECT_EQ(npz.substr(0, 4), std::string("PK\x03\x04", 4));
    for (const char* name : {"positions.npy", "normals.npy", "plant_id.npy", "object_id.npy",
                             "organ.npy", "leaf_id.npy", "shoot_id.npy", "rank.npy", "age.npy",
                             "organ_labels.npy", "range.npy", "scanner.npy"})
        EXPECT_NE(npz.find(name), std::string::npos) << name;
    // The ranges, as stored.
    const std::size_t at = npz.find("'descr': '<f4', 'fortran_order': False, 'shape': (" +
                                        std::to_string(c.positions.size()) + ",), }",
                                    npz.find("range.npy"));
    ASSERT_NE(at, std::string::npos);
    const std::size_t data = npz.find('\n', at) + 1;
    EXPECT_EQ(std::memcmp(npz.data() + data, c.range.data(), c.range.size() * 4), 0);

    PointCloud broken = c;
    broken.scanner.pop_back();
    EXPECT_EQ(
        std::string(errorOf([&] { writePointCloudNPZ(broken, (dir / "b.npz").string()); }).what()),
        (dir / "b.npz").string() + ": the point cloud's arrays differ in length");
    EXPECT_FALSE(fs::exists(dir / "b.npz"));
    fs::remove_all(dir);
}

TEST(Scan, BadOptionsAreOneLineErrors) {
    Context ctx;
    auto message = [&](ScanOptions o) {
        return std::string(errorOf([&] { scan(ctx, o); }).what());
    };
    EXPECT_EQ(message({}), "scanners = 0: a scan needs 1 to 65535 scanners");
    ScanOptions o = downward();
    o.scanners[0].resolution = 0.0f;
    EXPECT_EQ(message(o), "resolution = 0: out of range (valid: 0.001 to 10 degrees)");
    o = downward();
    o.scanners[0].zenithMax = 100.0f;
    EXPECT_EQ(message(o), "zenith maximum = 100: out of range (valid: 150 to 180 degrees)");
    o = downward();
    o.scanners[0].azimuthMax = 400.0f;
    EXPECT_EQ(message(o), "azimuth maximum = 400: out of range (valid: 0 to 360 degrees)");
    o = downward();
    o.rangeNoise = -1.0f;
    EXPECT_EQ(message(o), "range noise = -1: out of range (valid: 0 to 1 m)");
    o = downward();
    o.scanners[0].origin.x = std::nanf("");
    EXPECT_EQ(message(o), "origin = nan: out of range (valid: finite coordinates)");
    o = downward();
    o.scanners[0].resolution = 0.001f;
    o.scanners[0].zenithMin = 0.0f;
    o.scanners[0].azimuthMax = 360.0f;
    EXPECT_EQ(message(o),
              "resolution: too many rays (64800360000) (valid: at most 2147483648 rays in all)");
}

TEST(Scan, CommandScansPlantFilesAndObjScenes) {
    const fs::path dir = fs::temp_directory_path() / ("scan_cli_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    const std::string xml = (dir / "bean.xml").string(), obj = (dir / "bean.obj").string();
    ASSERT_EQ(cli::run("--seed 2 build bean --age 25 -o " + xml + " -o " + obj).status, 0);
    const std::string args = " --scanner 0.8,0,0.4 --scanner -0.8,0.2,0.4 --resolution 0.5 ";
    cli::Result r = cli::run("--seed 2 scan " + xml + args + "-o " + (dir / "a.ply").string() +
                             " -o " + (dir / "a.npz").string());
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find(" points from 2 scanner(s) of 173520 rays each"), std::string::npos)
        << r.out;
    r = cli::run("--seed 2 scan " + obj + args + "-o " + (dir / "b.ply").string());
    ASSERT_EQ(r.status, 0) << r.out;
    // The OBJ holds the same geometry: the same points (labels from the OBJ's groups aside).
    const std::string a = readAll(dir / "a.ply"), b = readAll(dir / "b.ply");
    const auto vertices = [](const std::string& ply) {
        const std::size_t at = ply.find("element vertex ") + 15;
        return ply.substr(at, ply.find('\n', at) - at);
    };
    EXPECT_EQ(vertices(a), vertices(b));

    const std::vector<std::pair<std::string, std::string>> bad = {
        {"scan " + xml + " --scanner 1,2 -o " + (dir / "x.ply").string(),
         "--scanner = 1,2: not a vector (valid: three numbers x,y,z)"},
        {"scan " + xml + " --scanner 1,0,0 -o " + (dir / "x.obj").string(),
         (dir / "x.obj").string() +
             ": '.obj': a scan is written as a point cloud (valid: .ply, .npz)"},
        {"scan " + xml + " --scanner 1,0,0 --zenith 30 -o " + (dir / "x.ply").string(),
         "--zenith = 30: expected two angles in degrees joined by ':' (valid: e.g. 30:150)"},
        {"scan " + xml + " --scanner 1,0,0 --zenith 100:50 -o " + (dir / "x.ply").string(),
         "zenith maximum = 50: out of range (valid: 100 to 180 degrees)"},
        {"scan " + xml + " --scanner 1,0,0 --noise 2 -o " + (dir / "x.ply").string(),
         "--noise = 2: not a distance (valid: 0 to 1 m)"},
        {"scan " + (dir / "none.xml").string() + " --scanner 1,0,0 -o " + (dir / "x.ply").string(),
         (dir / "none.xml").string() + ": cannot open plant structure file: No such file or directory"},
    };
    for (const auto& [line, message] : bad) {
        r = cli::run(line);
        EXPECT_EQ(r.status, 2) << line;
        EXPECT_EQ(r.out, "plantarch: " + message + "\n") << line;
    }
    EXPECT_FALSE(fs::exists(dir / "x.ply"));
    EXPECT_FALSE(fs::exists(dir / "x.obj"));
    fs::remove_all(dir);
}

TEST(Scan, SurfaceSamplesAsNpzFromTheCommandLine) {
    const fs::path dir = fs::temp_directory_path() / ("npz_cli_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    const std::string npz = (dir / "points.npz").string();
    cli::Result r = cli::run("--points 500 build bean --age 20 -o " + npz);
    ASSERT_EQ(r.status, 0) << r.out;
    const std::string bytes = readAll(npz);
    EXPECT_NE(bytes.find("'shape': (500, 3)"), std::string::npos);
    EXPECT_EQ(bytes.find("range.npy"), std::string::npos);  // samples have no range
    r = cli::run("build bean --age 20 -o " + (dir / "none.npz").string());
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.out, "plantarch: " + (dir / "none.npz").string() +
                         ": --points: an .npz output is a point cloud: give --points N (valid: 1 "
                         "to 2147483648)\n");
    EXPECT_FALSE(fs::exists(dir / "none.npz"));
    fs::remove_all(dir);
}
