// plantarch light: a clear day or a weather file on a plant, its series, leaves and pictures,
// and one line with exit 2 for every bad input.

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "cli_run.h"
#include "plantarch/Render.h"

namespace fs = std::filesystem;

namespace {

class CliLight : public ::testing::Test {
protected:
    fs::path dir = fs::temp_directory_path() / ("plantarch-light-" + std::to_string(::getpid()));
    void SetUp() override { fs::create_directories(dir); }
    void TearDown() override { fs::remove_all(dir); }
    std::string path(const std::string& name) const { return (dir / name).string(); }
    static std::vector<std::string> lines(const std::string& file) {
        std::ifstream in(file);
        std::vector<std::string> all;
        for (std::string l; std::getline(in, l);) all.push_back(l);
        return all;
    }
};

const std::string kPlant = "light bean --age 25 --rays 2,16,8 --location 38.54,-121.74";

}  // namespace

TEST_F(CliLight, AClearDayGivesAnHourlySeriesEveryLeafAndAPicture) {
    const auto r =
        cli::run(kPlant + " --date 2026-06-21 --series " + path("s.csv") + " --leaves " +
                 path("l.csv") + " -o " + path("light.png") + " -o " + path("light.ply"));
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("14.0 h of sun"), std::string::npos) << r.out;
    const auto series = lines(path("s.csv"));
    ASSERT_EQ(series.size(), 25u);  // header and 24 hours
    EXPECT_EQ(series[0].substr(0, 30), "time,sun_elevation,sun_azimuth");
    EXPECT_EQ(series[1].substr(0, 20), "2026-06-21T00:30:00Z");
    // Noon (about 20:00 UTC at 121.7 W): the leaves absorb something; midnight, nothing.
    const auto field = [](const std::string& line, int k) {
        std::stringstream ss(line);
        std::string v;
        for (int i = 0; i <= k; ++i) std::getline(ss, v, ',');
        return std::stod(v);
    };
    EXPECT_GT(field(series[21], 8), 0.0);
    EXPECT_GT(field(series[21], 11), 0.0);  // leaves fix carbon at noon
    EXPECT_LT(field(series[9], 11), 0.0);   // and respire at night
    EXPECT_EQ(field(series[9], 8), 0.0);
    EXPECT_GT(field(series[21], 1), 70.0);  // the sun's noon elevation at 38.5 N in June
    const auto leaves = lines(path("l.csv"));
    ASSERT_GT(leaves.size(), 20u);
    EXPECT_EQ(leaves[0],
              "object_id,plant_id,area,absorbed_par,absorbed_par_total,sunlit_fraction,"
              "net_assimilation_total");
    double most = 0.0;
    for (std::size_t k = 1; k < leaves.size(); ++k) most = std::max(most, field(leaves[k], 4));
    EXPECT_GT(most, 10.0);  // mol m-2 over a clear June day on a leaf in the sun
    EXPECT_LT(most, 70.0);
    const plantarch::Image image = plantarch::readImage(path("light.png"));
    EXPECT_EQ(image.width, 1024);
    EXPECT_TRUE(fs::exists(path("light.ply")));
    // Same seed, same bytes.
    const auto again = cli::run(kPlant + " --date 2026-06-21 --series " + path("s2.csv"));
    ASSERT_EQ(again.status, 0) << again.out;
    EXPECT_EQ(lines(path("s2.csv")), series);
}

TEST_F(CliLight, AWeatherFileGivesOneRowPerInterval) {
    std::ofstream(path("w.csv")) << "time,global_radiation,air_temperature\n"
                                    "2026-06-21T19:00Z,900,30\n2026-06-21T19:30Z,300,29\n";
    const auto r = cli::run(kPlant + " --weather " + path("w.csv") + " --series " + path("s.csv"));
    ASSERT_EQ(r.status, 0) << r.out;
    const auto series = lines(path("s.csv"));
    ASSERT_EQ(series.size(), 3u);
    EXPECT_EQ(series[2].substr(0, 20), "2026-06-21T19:30:00Z");
    EXPECT_NE(r.out.find("over 2 interval(s)"), std::string::npos) << r.out;
}

TEST_F(CliLight, BadInputsAreOneLineAndExit2) {
    std::ofstream(path("bad.csv")) << "time,air_temperature\n2026-01-01,5\n";
    ASSERT_EQ(::mkfifo(path("fifo.csv").c_str(), 0600), 0);
    const std::string out = " --series " + path("s.csv");
    const std::vector<std::pair<std::string, std::string>> cases{
        {kPlant + out, "give the day (--date) or a weather file (--weather)"},
        {kPlant + " --date 2026-06-21 --weather " + path("bad.csv") + out, "both name the light"},
        {"light bean --age 25 --location 91,0 --date 2026-06-21" + out, "latitude out of range"},
        {"light bean --age 25 --location north --date 2026-06-21" + out, "expected LAT,LON"},
        {kPlant + " --date 2026-06-31" + out, "day out of range"},
        {"light bean --age 25 --location 0,0 --date 2026-06-21 --rays 4,0,8" + out,
         "expected three ray counts"},
        {kPlant + " --date 2026-06-21 --clearness 2" + out, "--clearness"},
        {kPlant + " --date 2026-06-21 --temperature 30:10" + out, "air temperatures out of range"},
        {kPlant + " --date 2026-06-21", "nothing to write"},
        {kPlant + " --date 2026-06-21 --series " + path("s.txt"), "expected a .csv file"},
        {kPlant + " --date 2026-06-21 -o " + path("x.doc"), "unknown output format"},
        {kPlant + " --date 2026-06-21 -o " + path("x.npz"), "not point clouds"},
        {kPlant + " --date 2026-06-21 --label organ -o " + path("x.png"), "not with --label"},
        {kPlant + " --weather " + path("bad.csv") + out, "no light column"},
        {kPlant + " --weather " + path("fifo.csv") + out, "not a weather file"},
        {kPlant + " --weather " + path("none.csv") + out, "none.csv"},
        {"light bean --location 0,0 --date 2026-06-21" + out, "give the plants' age"},
        {"light bean --age 40 --count 3x3 --location 0,0 --date 2026-06-21 --rays 4,64,100000" +
             out,
         "more than half of this machine's memory"},
    };
    for (const auto& [args, why] : cases) {
        const auto r = cli::run(args);
        EXPECT_EQ(r.status, 2) << args << "\n" << r.out;
        EXPECT_NE(r.out.find(why), std::string::npos) << args << "\n" << r.out;
        EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
        EXPECT_FALSE(fs::exists(path("s.csv"))) << args;
    }
}
