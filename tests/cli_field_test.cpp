// plantarch field as a user runs it: the whole field in one run, the same files from two shards
// and --index-only, --resume skipping finished tiles, docs/datasets.md's examples as written,
// and every bad option one line with exit status 2, leaving no index behind.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "cli_run.h"

namespace {

namespace fs = std::filesystem;
using cli::run;

const fs::path kSource = PLANTARCH_SOURCE_DIR;
const std::string kProject = (kSource / "examples" / "fields" / "bean_field.json").string();

std::string folder(const std::string& name) {
    const auto d = fs::temp_directory_path() / "plantarch-cli-field" / name;
    fs::remove_all(d);
    fs::create_directories(d.parent_path());
    return d.string();
}

std::map<std::string, std::string> filesIn(const std::string& dir) {
    std::map<std::string, std::string> all;
    for (const auto& e : fs::directory_iterator(dir)) {
        std::ifstream in(e.path(), std::ios::binary);
        std::ostringstream s;
        s << in.rdbuf();
        all[e.path().filename().string()] = s.str();
    }
    return all;
}

std::size_t lines(const std::string& text) {
    std::size_t n = 0;
    for (char c : text) n += c == '\n';
    return n;
}

}  // namespace

TEST(CliField, TwoShardsAndTheIndexGiveTheFilesOfOneRun) {
    const std::string whole = folder("whole"), sharded = folder("sharded");
    const auto one = run("field " + kProject + " --out " + whole + " --tile-size 0.6");
    ASSERT_EQ(one.status, 0) << one.out;
    EXPECT_NE(one.out.find("6 tiles of 0.6 m, 27 plants; 6 tiles built"), std::string::npos)
        << one.out;
    for (const char* shard : {"0/2", "1/2"}) {
        const auto r =
            run("field " + kProject + " --out " + sharded + " --tile-size 0.6 --shard " + shard);
        ASSERT_EQ(r.status, 0) << r.out;
        EXPECT_NE(r.out.find("3 tiles built (shard"), std::string::npos) << r.out;
    }
    EXPECT_FALSE(fs::exists(sharded + "/tileset.json"));
    const auto index =
        run("field " + kProject + " --out " + sharded + " --tile-size 0.6 --index-only");
    ASSERT_EQ(index.status, 0) << index.out;
    const auto a = filesIn(whole), b = filesIn(sharded);
    EXPECT_EQ(a.size(), 14u);
    EXPECT_EQ(a, b);
    // --resume builds nothing more; the index is written again, the same.
    const auto resumed =
        run("field " + kProject + " --out " + sharded + " --tile-size 0.6 --resume");
    ASSERT_EQ(resumed.status, 0) << resumed.out;
    EXPECT_NE(resumed.out.find("0 tiles built, 6 already there"), std::string::npos) << resumed.out;
    EXPECT_EQ(filesIn(sharded), a);
}

TEST(CliField, BadOptionsAreOneLineWithExitStatus2) {
    const std::string out = folder("bad");
    const std::string file = folder("a-file");
    std::ofstream(file) << "x";
    const std::string base = "field " + kProject + " --out " + out;
    const std::pair<std::string, std::string> cases[] = {
        {base + " --tile-size 0",
         "plantarch: --tile-size = 0: not a tile size (valid: > 0 and <= "
         "1000000 m)\n"},
        {base + " --tile-size -1", "--tile-size = -1: not a tile size"},
        {base + " --tile-size nan", "--tile-size = nan: not a tile size"},
        {base + " --tile-size 1e7", "--tile-size = 1e7: not a tile size"},
        {base + " --tile-size 1e-6",
         "tiles): too many tiles (valid: a size giving at most 1000000 tiles)\n"},
        {base + " --tile-size 1 --halo -1", "--halo = -1: not a halo width (valid: 0 to 1000 m)"},
        {base + " --tile-size 1 --shard 2/2",
         "plantarch: --shard = 2/2: not a shard (valid: K/N, whole numbers with 0 <= K < N <= "
         "1000000)\n"},
        {base + " --tile-size 1 --shard 1", "--shard = 1: not a shard"},
        {base + " --tile-size 1 --shard -1/2", "--shard = -1/2: not a shard"},
        {base + " --tile-size 1 --index-only --shard 0/2", "--index-only builds no tile"},
        {base + " --tile-size 1 --index-only",
         "tile_0_0.glb: tile missing: 2 of 2 tiles not built"},
        {"field " + kProject + " --out " + file + " --tile-size 1",
         "a-file: --out: not a folder (valid: a folder (made if missing))"},
        {"field /nonexistent.json --out " + out + " --tile-size 1", "nonexistent.json"},
        {"field " + kProject + " --out /dev/null/x --tile-size 1",
         "plantarch: /dev/null: --out: not a folder (valid: a folder (made if missing))\n"},
        {"field " + kProject + " --out '' --tile-size 1",
         "plantarch: --out: no output folder (valid: a folder (made if missing))\n"},
        {"field " + kProject + " --tile-size 1", "--out is required"},
    };
    for (const auto& [args, expected] : cases) {
        const auto r = run(args);
        EXPECT_EQ(r.status, 2) << args << "\n" << r.out;
        EXPECT_NE(r.out.find(expected), std::string::npos) << args << "\n" << r.out;
        EXPECT_EQ(lines(r.out), 1u) << args << "\n" << r.out;
        EXPECT_FALSE(fs::exists(out + "/tileset.json")) << args;
    }
}

// The field examples of docs/datasets.md run as written, from a folder where examples/ is the
// repository's, and write the folder they name.
TEST(CliField, TheDocsExamplesRun) {
    const fs::path dir = fs::temp_directory_path() / "plantarch-docs-field-examples";
    fs::remove_all(dir);
    fs::create_directories(dir / "out");
    fs::create_directory_symlink(kSource / "examples", dir / "examples");
    std::ifstream in(kSource / "docs" / "datasets.md");
    int ran = 0;
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("build/plantarch field ", 0) != 0) continue;
        const auto r = cli::runShell("cd '" + dir.string() + "' && " + PLANTARCH_CLI +
                                     line.substr(std::string("build/plantarch").size()) + " 2>&1");
        ASSERT_EQ(r.status, 0) << line << "\n" << r.out;
        ++ran;
    }
    EXPECT_GE(ran, 4);
    EXPECT_TRUE(fs::exists(dir / "out" / "field" / "tileset.json"));
    EXPECT_TRUE(fs::exists(dir / "out" / "field" / "plants.csv"));
    fs::remove_all(dir);
}
