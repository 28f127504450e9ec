// plantarch reconstruct, skeleton inputs of convert and grow, and .mtg / .skeleton.csv
// outputs, as a user runs them: a plant written as a skeleton comes back with its shoots;
// every bad skeleton gets one line and exit status 2, leaving no file behind.

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.h"
#include "plant_geometry_bytes.h"

namespace {

using cli::run;
using plantarch::testing::fileBytes;

std::string dir(const std::string& name) {
    const auto d = std::filesystem::temp_directory_path() / "plantarch-cli-reconstruct" / name;
    std::filesystem::remove_all(d);
    std::filesystem::create_directories(d);
    return d.string();
}

std::size_t lines(const std::string& text) {
    std::size_t n = 0;
    for (char c : text) n += c == '\n';
    return n;
}

// The nodes of a skeleton table: point, radius, link and shoot type (ids left out).
struct Row {
    double x, y, z, radius;
    std::string link, type;
};
std::vector<Row> nodeRows(const std::string& csv) {
    std::vector<Row> rows;
    std::istringstream in(csv);
    std::string line;
    std::getline(in, line);  // the header
    while (std::getline(in, line)) {
        std::vector<std::string> cells;
        std::stringstream cs(line);
        for (std::string c; std::getline(cs, c, ',');) cells.push_back(c);
        cells.resize(9);
        rows.push_back({std::stod(cells[2]), std::stod(cells[3]), std::stod(cells[4]),
                        std::stod(cells[5]), cells[6], cells[7]});
    }
    return rows;
}
// Whether every row of `a` has its own row in `b` within 10 µm (and the other way round).
bool sameNodes(const std::vector<Row>& a, const std::vector<Row>& b) {
    if (a.size() != b.size()) return false;
    std::vector<bool> used(b.size(), false);
    for (const Row& r : a) {
        bool found = false;
        for (std::size_t i = 0; i < b.size() && !found; ++i)
            if (!used[i] && std::abs(r.x - b[i].x) < 1e-5 && std::abs(r.y - b[i].y) < 1e-5 &&
                std::abs(r.z - b[i].z) < 1e-5 && std::abs(r.radius - b[i].radius) < 1e-7 &&
                r.link == b[i].link && r.type == b[i].type)
                used[i] = found = true;
        if (!found) return false;
    }
    return true;
}

}  // namespace

TEST(CliReconstruct, PlantWrittenAsSkeletonAndMtgComesBack) {
    const std::string d = dir("roundtrip");
    cli::Result r = run("build bean --age 30 -o " + d + "/b.xml -o " + d + "/b.skeleton.csv -o " +
                        d + "/b.mtg");
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_EQ(fileBytes(d + "/b.mtg").rfind("CODE:\tFORM-A", 0), 0u);
    EXPECT_EQ(fileBytes(d + "/b.skeleton.csv").rfind("id,parent,x,y,z,radius", 0), 0u);
    r = run("reconstruct " + d + "/b.skeleton.csv --species bean --age 30 -o " + d +
            "/from_csv.xml");
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("1 plant(s) rebuilt on"), std::string::npos) << r.out;
    r = run("reconstruct " + d + "/b.mtg --species bean --age 30 -o " + d + "/from_mtg.xml");
    ASSERT_EQ(r.status, 0) << r.out;
    // The same nodes, radii and axes, through either file.
    r = run("convert " + d + "/from_csv.xml " + d + "/from_csv.skeleton.csv");
    ASSERT_EQ(r.status, 0) << r.out;
    r = run("convert " + d + "/from_mtg.xml " + d + "/from_mtg.skeleton.csv");
    ASSERT_EQ(r.status, 0) << r.out;
    const std::vector<Row> original = nodeRows(fileBytes(d + "/b.skeleton.csv"));
    EXPECT_GT(original.size(), 20u);
    EXPECT_TRUE(sameNodes(nodeRows(fileBytes(d + "/from_csv.skeleton.csv")), original));
    EXPECT_TRUE(sameNodes(nodeRows(fileBytes(d + "/from_mtg.skeleton.csv")), original));
    // convert and grow read skeletons too.
    r = run("convert " + d + "/b.mtg " + d + "/b.glb --species bean");
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_GT(std::filesystem::file_size(d + "/b.glb"), 10000u);
    r = run("grow " + d + "/b.skeleton.csv --species bean --days 10 -o " + d + "/g.xml");
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NE(fileBytes(d + "/g.xml").find("<measured>"), std::string::npos);
}

TEST(CliReconstruct, BadSkeletonsGetOneLineAndLeaveNoFile) {
    const std::string d = dir("bad");
    auto refused = [&](const std::string& args, const std::string& expect) {
        const cli::Result r = run(args);
        EXPECT_EQ(r.status, 2) << args << "\n" << r.out;
        EXPECT_EQ(lines(r.out), 1u) << r.out;
        EXPECT_NE(r.out.find(expect), std::string::npos) << r.out;
        EXPECT_FALSE(std::filesystem::exists(d + "/out.glb")) << args;
    };
    std::ofstream(d + "/ok.csv") << "id,parent,x,y,z\n0,,0,0,0\n1,0,0,0,0.05\n2,1,0,0,0.1\n";
    std::ofstream(d + "/typo.csv") << "id,parent,x,y,z,radios\n";
    refused("reconstruct " + d + "/typo.csv --species bean -o " + d + "/out.glb",
            "did you mean 'radius'");
    std::ofstream(d + "/nan.csv") << "id,parent,x,y,z\n0,,0,0,0\n1,0,0,0,nan\n";
    refused("reconstruct " + d + "/nan.csv --species bean -o " + d + "/out.glb", ":3");
    std::ofstream(d + "/far.csv") << "id,parent,x,y,z\n0,,0,0,0\n1,0,0,0,1e9\n";
    refused("reconstruct " + d + "/far.csv --species bean -o " + d + "/out.glb",
            "-100000 to 100000");
    std::ofstream(d + "/b.mtg") << "CODE:\tFORM-B\n";
    refused("reconstruct " + d + "/b.mtg --species bean -o " + d + "/out.glb", "FORM-B");
    refused("reconstruct " + d + "/none.csv --species bean -o " + d + "/out.glb", "none.csv");
    refused("reconstruct " + d + "/ok.csv --species no_such_species -o " + d + "/out.glb",
            "no_such_species");
    refused("reconstruct " + d + "/ok.csv --species bean --unit inch -o " + d + "/out.glb",
            "--unit");
    refused("convert " + d + "/nan.csv " + d + "/out.glb", "--species");
    std::filesystem::create_directories(d + "/dir.csv");
    refused("reconstruct " + d + "/dir.csv --species bean -o " + d + "/out.glb", "dir.csv");
    ASSERT_EQ(mkfifo((d + "/fifo.csv").c_str(), 0600), 0);
    refused("reconstruct " + d + "/fifo.csv --species bean -o " + d + "/out.glb", "fifo.csv");
    refused("reconstruct " + d + "/ok.csv --species bean --leaf-scale 0 -o " + d + "/out.glb",
            "leaf_scale");
    const cli::Result r = run("reconstruct " + d + "/ok.csv --species bean -o " + d + "/out.glb");
    EXPECT_EQ(r.status, 0) << r.out;
}
