// build and grow with --carbon and --nitrogen: the plant grows through clear days or a
// weather file with its budgets, the records go to --series, bad options get one line.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.h"

namespace fs = std::filesystem;

namespace {

class CliPhysiology : public ::testing::Test {
protected:
    fs::path dir =
        fs::temp_directory_path() / ("plantarch-physiology-" + std::to_string(::getpid()));
    void SetUp() override { fs::create_directories(dir); }
    void TearDown() override { fs::remove_all(dir); }
    std::string path(const std::string& name) const { return (dir / name).string(); }
    static std::vector<std::string> lines(const std::string& file) {
        std::ifstream in(file);
        std::vector<std::string> all;
        for (std::string l; std::getline(in, l);) all.push_back(l);
        return all;
    }
    static double field(const std::string& line, int k) {
        std::stringstream ss(line);
        std::string v;
        for (int i = 0; i <= k; ++i) std::getline(ss, v, ',');
        return std::stod(v);
    }
};

const std::string kWhere = " --location 38.54,-121.74 --light-every 4";

}  // namespace

TEST_F(CliPhysiology, BuildGrowsThroughClearDaysAndWritesTheRecords) {
    const auto r =
        cli::run("build bean --from 15 --age 25 --carbon --nitrogen --fertilise 15:1" + kWhere +
                 " --start 2026-06-01 --series " + path("s.csv") + " -o " + path("bean.xml"));
    ASSERT_EQ(r.status, 0) << r.out;
    const auto rows = lines(path("s.csv"));
    ASSERT_EQ(rows.size(), 11u);  // header and 10 days
    EXPECT_EQ(rows[0].substr(0, 30), "plant,age,days,leaf_area,absor");
    EXPECT_EQ(field(rows[1], 1), 16.0);
    EXPECT_EQ(field(rows[10], 1), 25.0);
    for (std::size_t k = 1; k < rows.size(); ++k) {
        EXPECT_GT(field(rows[k], 4), 0.0);  // absorbed PAR
        EXPECT_GT(field(rows[k], 6), 0.0);  // net input
    }
    // The state carries the pools: the plant file grows on with them.
    std::ifstream xml(path("bean.xml"));
    std::stringstream text;
    text << xml.rdbuf();
    EXPECT_NE(text.str().find("<carbohydrates>"), std::string::npos);
    EXPECT_NE(text.str().find("<sugar>"), std::string::npos);
    EXPECT_NE(text.str().find("<nitrogen>"), std::string::npos);
    const auto g =
        cli::run("grow " + path("bean.xml") + " --days 3 --carbon" + kWhere +
                 " --start 2026-06-11 --series " + path("g.csv") + " -o " + path("on.xml"));
    ASSERT_EQ(g.status, 0) << g.out;
    EXPECT_EQ(lines(path("g.csv")).size(), 4u);
    EXPECT_EQ(field(lines(path("g.csv"))[3], 1), 28.0);
    // Same seed, same bytes.
    const auto again = cli::run(
        "build bean --from 15 --age 25 --carbon --nitrogen --fertilise "
        "15:1" +
        kWhere + " --start 2026-06-01 --series " + path("s2.csv"));
    ASSERT_EQ(again.status, 0) << again.out;
    EXPECT_EQ(lines(path("s.csv")), lines(path("s2.csv")));
}

TEST_F(CliPhysiology, AWeatherFileGivesADayPerDate) {
    std::ofstream w(path("w.csv"));
    w << "time,par,air_temperature\n";
    for (int d = 1; d <= 2; ++d)
        for (int h = 0; h < 24; ++h)
            w << "2026-07-0" << d << "T" << (h < 10 ? "0" : "") << h << ":30,"
              << (h >= 14 && h <= 26 ? 1200 : 0) << ",25\n";
    w.close();
    const auto r = cli::run("build bean --from 20 --age 22 --carbon" + kWhere + " --weather " +
                            path("w.csv") + " --series " + path("s.csv"));
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_EQ(lines(path("s.csv")).size(), 3u);
    const auto short_ = cli::run("build bean --from 20 --age 25 --carbon" + kWhere + " --weather " +
                                 path("w.csv") + " --series " + path("t.csv"));
    EXPECT_EQ(short_.status, 2);
    EXPECT_NE(short_.out.find("2 date(s) for 5 days of growth"), std::string::npos) << short_.out;
    EXPECT_FALSE(fs::exists(path("t.csv")));
}

TEST_F(CliPhysiology, ACanopyGrowsWithItsBudgetsPlantByPlant) {
    const auto r = cli::run(
        "canopy bean --count 2x1 --spacing 0.3x0.3 --from 20 --age 22 "
        "--carbon --nitrogen --fertilise 20:0.5" +
        kWhere + " --start 2026-06-01 --series " + path("c.csv") + " -o " + path("c.xml"));
    ASSERT_EQ(r.status, 0) << r.out;
    const auto rows = lines(path("c.csv"));
    ASSERT_EQ(rows.size(), 5u);  // header, 2 days x 2 plants
    for (std::size_t k = 1; k < rows.size(); ++k) {
        EXPECT_GT(field(rows[k], 4), 0.0);   // absorbed PAR
        EXPECT_GT(field(rows[k], 16), 0.0);  // nitrogen available after fertilising
    }
    EXPECT_EQ(field(rows[1], 0), field(rows[3], 0));  // day by day, plant by plant
    EXPECT_NE(field(rows[1], 0), field(rows[2], 0));
    std::ifstream xml(path("c.xml"));
    std::stringstream text;
    text << xml.rdbuf();
    EXPECT_NE(text.str().find("<carbohydrates>"), std::string::npos);
}

TEST_F(CliPhysiology, AProjectWithAPhysiologySectionGrowsItsLastDaysWithIt) {
    std::ofstream(path("p.json")) << R"({"plantarch_project": 1, "seed": 4,
      "blocks": [{"species": "bean", "count": [2, 1], "age": 23}],
      "physiology": {"carbon": true, "nitrogen": true, "location": [38.54, -121.74],
                     "start": "2026-06-01", "light_every": 4, "days": 3,
                     "fertilise": [[20, 0.5]]}})";
    const auto r = cli::run("project run " + path("p.json") + " --series " + path("p.csv") +
                            " -o " + path("p.xml"));
    ASSERT_EQ(r.status, 0) << r.out;
    const auto rows = lines(path("p.csv"));
    ASSERT_EQ(rows.size(), 7u);  // header, 3 days x 2 plants
    EXPECT_EQ(field(rows[1], 1), 21.0);
    EXPECT_EQ(field(rows[6], 1), 23.0);
    // The same season through canopy gives the same records: a project is no other model.
    const auto c = cli::run(
        "--seed 4 canopy bean --count 2x1 --from 20 --age 23 --carbon --nitrogen --fertilise "
        "20:0.5" +
        kWhere + " --start 2026-06-01 --series " + path("c.csv"));
    ASSERT_EQ(c.status, 0) << c.out;
    EXPECT_EQ(lines(path("c.csv")), rows);
    // A project without the section has no records to write; one whose blocks are younger
    // than its days is refused before anything is built.
    std::ofstream(path("q.json")) << R"({"plantarch_project": 1,
      "blocks": [{"species": "bean", "count": [1, 1], "age": 2}],
      "physiology": {"carbon": true, "location": [38.54, -121.74], "start": "2026-06-01",
                     "days": 3}})";
    const auto young = cli::run("project run " + path("q.json") + " --series " + path("q.csv"));
    EXPECT_EQ(young.status, 2);
    EXPECT_NE(young.out.find("blocks/0/age = 2: younger than the physiology's days"),
              std::string::npos)
        << young.out;
    EXPECT_EQ(std::count(young.out.begin(), young.out.end(), '\n'), 1) << young.out;
    EXPECT_FALSE(fs::exists(path("q.csv")));
    std::ofstream(path("n.json")) << R"({"plantarch_project": 1,
      "blocks": [{"species": "bean", "count": [1, 1], "age": 2}]})";
    const auto none = cli::run("project run " + path("n.json") + " --series " + path("n.csv"));
    EXPECT_EQ(none.status, 2);
    EXPECT_NE(none.out.find("the project has no physiology"), std::string::npos) << none.out;
    EXPECT_FALSE(fs::exists(path("n.csv")));
}

TEST_F(CliPhysiology, BadOptionsGetOneLineAndExit2) {
    const std::string o = " -o " + path("x.png");
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"build bean --age 20 --carbon" + o, "need --location"},
        {"build bean --age 20 --series a.csv" + o, "need --carbon or --nitrogen"},
        {"build bean --age 20 --carbon --location 1,2" + o, "either --weather FILE or --start"},
        {"build bean --age 20.5 --carbon --location 1,2 --start 2026-01-01" + o, "whole days"},
        {"build bean --age 20 --from 30 --carbon --location 1,2 --start 2026-01-01" + o,
         "--from <= --age"},
        {"build bean --age 20 --carbon --location 1,2 --start 2026-13-01" + o,
         "month out of range"},
        {"build bean --age 20 --carbon --location 100,2 --start 2026-01-01" + o, "latitude"},
        {"build bean --age 20 --carbon --fertilise 3:1 --location 1,2 --start 2026-01-01" + o,
         "--fertilise needs --nitrogen"},
        {"build bean --age 20 --nitrogen --fertilise 3:-1 --location 1,2 --start 2026-01-01" + o,
         "the grams > 0"},
        {"build bean --age 20 --nitrogen --fertilise nan:1 --location 1,2 --start 2026-01-01" + o,
         "--fertilise"},
        {"build bean --age 20 --carbon --light-every 0 --location 1,2 --start 2026-01-01" + o,
         "--light-every"},
        {"build bean --age 20 --carbon --location 1,2 --weather /dev/zero" + o, "/dev/zero"},
        {"canopy bean --count 2x2 --age 20 --carbon --from 25 --location 1,2 --start "
         "2026-01-01" +
             o,
         "--from <= --age"},
        {"canopy bean --count 2x2 --age 20 --nitrogen --fertilise x --location 1,2 --start "
         "2026-01-01" +
             o,
         "--fertilise"},
    };
    for (const auto& [args, message] : cases) {
        const auto r = cli::run(args);
        EXPECT_EQ(r.status, 2) << args << "\n" << r.out;
        EXPECT_NE(r.out.find(message), std::string::npos) << args << "\n" << r.out;
        EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << args << "\n" << r.out;
    }
    EXPECT_FALSE(fs::exists(path("x.png")));
}
