// plantarch dataset, as a user runs it: a whole run equals the union of its shards byte for
// byte, --resume keeps what is made, --merge names what is missing, and every bad spec or
// option gets one line and exit status 2 with no sample left behind.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "cli_run.h"
#include "plant_geometry_bytes.h"

namespace {

namespace fs = std::filesystem;
using cli::run;

const std::string kTiny = std::string(PLANTARCH_SOURCE_DIR) + "/examples/datasets/tiny.json";

std::string dir(const std::string& name) {
    const auto d = fs::temp_directory_path() / "plantarch-cli-dataset" / name;
    fs::remove_all(d);
    fs::create_directories(d);
    return d.string();
}

std::string slurp(const fs::path& p) {
    return plantarch::testing::fileBytes(p.string());
}

// Every file under `root` (relative path -> bytes), manifests left out.
std::map<std::string, std::string> tree(const fs::path& root) {
    std::map<std::string, std::string> out;
    for (const auto& e : fs::recursive_directory_iterator(root)) {
        if (!e.is_regular_file()) continue;
        const std::string rel = fs::relative(e.path(), root).string();
        if (rel.rfind("manifest-", 0) == 0) continue;
        out[rel] = slurp(e.path());
    }
    return out;
}

std::size_t lines(const std::string& text) {
    std::size_t n = 0;
    for (char c : text) n += c == '\n';
    return n;
}

TEST(CliDataset, ShardsMadeInAnyOrderEqualOneWholeRun) {
    const std::string whole = dir("whole"), sharded = dir("sharded");
    const cli::Result w = run("dataset " + kTiny + " --out " + whole);
    ASSERT_EQ(w.status, 0) << w.out;
    EXPECT_NE(w.out.find("made 4 sample(s)"), std::string::npos) << w.out;
    for (const char* shard : {"2/3", "0/3", "1/3"}) {
        const cli::Result r = run("dataset " + kTiny + " --out " + sharded + " --shard " + shard);
        ASSERT_EQ(r.status, 0) << r.out;
        EXPECT_NE(r.out.find("merge with --merge"), std::string::npos) << r.out;
    }
    EXPECT_TRUE(fs::exists(fs::path(sharded) / "manifest-0-of-3.json"));
    EXPECT_FALSE(fs::exists(fs::path(sharded) / "dataset.json"));
    const cli::Result m = run("dataset " + kTiny + " --out " + sharded + " --merge");
    ASSERT_EQ(m.status, 0) << m.out;
    const auto a = tree(whole), b = tree(sharded);
    ASSERT_EQ(a.size(), b.size());
    for (const auto& [file, bytes] : a) {
        ASSERT_TRUE(b.count(file)) << file;
        EXPECT_TRUE(b.at(file) == bytes) << file;
    }
    EXPECT_TRUE(a.count("dataset.json"));
    EXPECT_TRUE(a.count("samples/000003/rgb.png"));
}

TEST(CliDataset, ResumeKeepsWhatIsMadeAndAnExistingSampleIsNotOverwritten) {
    const std::string out = dir("resume");
    ASSERT_EQ(run("dataset " + kTiny + " --out " + out + " --samples 2").status, 0);
    const std::string before = slurp(fs::path(out) / "samples/000001/metadata.json");
    const cli::Result again = run("dataset " + kTiny + " --out " + out + " --samples 2");
    EXPECT_EQ(again.status, 2) << again.out;
    EXPECT_EQ(lines(again.out), 1u) << again.out;
    EXPECT_NE(again.out.find("--resume"), std::string::npos) << again.out;
    const cli::Result resumed = run("dataset " + kTiny + " --out " + out + " --resume");
    ASSERT_EQ(resumed.status, 0) << resumed.out;
    EXPECT_NE(resumed.out.find("made 2 sample(s) (2 kept)"), std::string::npos) << resumed.out;
    EXPECT_EQ(slurp(fs::path(out) / "samples/000001/metadata.json"), before);
    EXPECT_TRUE(fs::exists(fs::path(out) / "samples/000003/rgb.png"));
}

TEST(CliDataset, MergeBeforeEveryShardIsDoneNamesTheMissingSamples) {
    const std::string out = dir("early-merge");
    ASSERT_EQ(run("dataset " + kTiny + " --out " + out + " --shard 1/2").status, 0);
    const cli::Result m = run("dataset " + kTiny + " --out " + out + " --merge");
    EXPECT_EQ(m.status, 2);
    EXPECT_EQ(lines(m.out), 1u) << m.out;
    EXPECT_NE(m.out.find("2 of 4 samples are missing (0, 2)"), std::string::npos) << m.out;
}

TEST(CliDataset, CheckShowsTheFirstSampleWithoutMakingOne) {
    const std::string out = dir("check");
    const cli::Result r = run("dataset " + kTiny + " --out " + out + "/x --check");
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("4 samples; sample 0:"), std::string::npos) << r.out;
    EXPECT_FALSE(fs::exists(fs::path(out) / "x"));
}

TEST(CliDataset, EveryBadSpecOrOptionGetsOneLineAndExitStatus2) {
    const std::string d = dir("bad");
    auto write = [&](const std::string& name, const std::string& text) {
        std::ofstream(fs::path(d) / name) << text;
        return (fs::path(d) / name).string();
    };
    const std::string fifo = (fs::path(d) / "fifo.json").string();
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const std::string file = write("a-file", "x");
    struct Case {
        std::string args, expect;
    };
    const std::vector<Case> cases = {
        {"dataset " + d + "/missing.json --out " + d + "/o", "missing.json"},
        {"dataset " + d + " --out " + d + "/o", "directory"},
        {"dataset " + fifo + " --out " + d + "/o", "is a FIFO, not a dataset spec"},
        {"dataset /dev/zero --out " + d + "/o", "/dev/zero"},
        {"dataset " + write("empty.json", "") + " --out " + d + "/o", "empty.json"},
        {"dataset " + write("nan.json", "{\"plantarch_dataset\": 1, \"samples\": NaN}") +
             " --out " + d + "/o",
         "nan.json"},
        {"dataset " + write("huge.json", "{\"plantarch_dataset\": 1, \"samples\": 1e999}") +
             " --out " + d + "/o",
         "samples"},
        {"dataset " +
             write("species.json",
                   "{\"plantarch_dataset\": 1, \"scene\": {\"species\": "
                   "[{\"species\": \"nope\"}]}}") +
             " --out " + d + "/o",
         "scene/species/0/species"},
        {"dataset " + kTiny + " --out " + file, "not a folder"},
        {"dataset " +
             write("rays.json",
                   "{\"plantarch_dataset\": 1, \"scene\": {\"species\": "
                   "[{\"species\": \"bean\"}]}, \"camera\": {\"width\": 8192, "
                   "\"height\": 8192, \"samples_per_pixel\": 256}}") +
             " --out " + d + "/o",
         "camera/samples_per_pixel"},
        {"dataset " +
             write("field.json",
                   "{\"plantarch_dataset\": 1, \"scene\": {\"species\": [{\"species\": "
                   "\"bean\", \"age\": 40}], \"layouts\": [{\"layout\": \"rows\", "
                   "\"rows\": 1000, \"plants_per_row\": 1000}]}}") +
             " --out " + d + "/o",
         "sample 000000: a canopy of 1000000 plants"},
        {"dataset " + kTiny + " --out " + d + "/o --shard 3/3", "--shard"},
        {"dataset " + kTiny + " --out " + d + "/o --shard 1", "--shard"},
        {"dataset " + kTiny + " --out " + d + "/o --shard -1/2", "--shard"},
        {"dataset " + kTiny + " --out " + d + "/o --shard 0/99999999999", "--shard"},
        {"dataset " + kTiny + " --out " + d + "/o --samples 0", "--samples"},
        {"dataset " + kTiny + " --out " + d + "/o --samples 100000000", "--samples"},
    };
    for (const Case& c : cases) {
        const cli::Result r = run(c.args);
        EXPECT_EQ(r.status, 2) << c.args << "\n" << r.out;
        EXPECT_EQ(lines(r.out), 1u) << c.args << "\n" << r.out;
        EXPECT_NE(r.out.find(c.expect), std::string::npos) << c.args << "\n" << r.out;
    }
    // A run that fails before its first sample leaves no folder it made.
    EXPECT_FALSE(fs::exists(fs::path(d) / "o"));
}

}  // namespace

namespace {

// The dataset examples of docs/datasets.md run as written, from a folder where examples/ is
// the repository's.
TEST(CliDataset, TheDocsExamplesRun) {
    const fs::path d = dir("docs-examples");
    fs::create_directories(d / "out");
    fs::create_directory_symlink(fs::path(PLANTARCH_SOURCE_DIR) / "examples", d / "examples");
    std::ifstream in(fs::path(PLANTARCH_SOURCE_DIR) / "docs" / "datasets.md");
    int ran = 0;
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("build/plantarch dataset ", 0) != 0) continue;
        const auto r = cli::runShell("cd '" + d.string() + "' && " + PLANTARCH_CLI +
                                     line.substr(std::string("build/plantarch").size()) + " 2>&1");
        ASSERT_EQ(r.status, 0) << line << "\n" << r.out;
        ++ran;
    }
    EXPECT_EQ(ran, 4);
    EXPECT_TRUE(fs::exists(d / "out" / "tiny" / "dataset.json"));
    EXPECT_TRUE(fs::exists(d / "out" / "beans" / "samples" / "000007" / "rgb.png"));
}

}  // namespace

namespace {

// Runs `plantarch --progress always dataset bean_rows.json --out OUT --samples 20`, waits until
// stderr shows `until`, sends SIGINT and returns the waitpid status.
int interruptDataset(const std::string& out, const std::string& until) {
    const std::string spec =
        std::string(PLANTARCH_SOURCE_DIR) + "/examples/datasets/bean_rows.json";
    int fds[2];
    if (::pipe(fds) != 0) return -1;
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::dup2(fds[1], 2);
        ::close(fds[0]);
        ::close(fds[1]);
        const int devnull = ::open("/dev/null", O_WRONLY);
        ::dup2(devnull, 1);
        ::execl(PLANTARCH_CLI, PLANTARCH_CLI, "--progress", "always", "dataset", spec.c_str(),
                "--out", out.c_str(), "--samples", "20", static_cast<char*>(nullptr));
        ::_exit(127);
    }
    ::close(fds[1]);
    std::string seen;
    char buf[4096];
    bool found = false;
    while (!found) {
        const ::ssize_t n = ::read(fds[0], buf, sizeof buf);
        if (n <= 0) break;
        seen.append(buf, std::size_t(n));
        found = seen.find(until) != std::string::npos;
    }
    ::kill(pid, found ? SIGINT : SIGKILL);
    while (::read(fds[0], buf, sizeof buf) > 0) {
    }
    ::close(fds[0]);
    int status = 0;
    ::waitpid(pid, &status, 0);
    return found ? status : -1;
}

TEST(CliDataset, AnInterruptedRunKeepsWholeSamplesAndNothingElse) {
    // Stopped while its first sample is built: the folders it made go too.
    const std::string first = dir("interrupt-first") + "/made/here";
    const int a = interruptDataset(first, "sample 1/20 ");
    ASSERT_NE(a, -1) << "the run ended before it was interrupted";
    EXPECT_TRUE(WIFSIGNALED(a) && WTERMSIG(a) == SIGINT);
    EXPECT_FALSE(fs::exists(fs::path(first).parent_path()));
    // Stopped while its third is built: the first two stay whole, nothing half made.
    const std::string third = dir("interrupt-third");
    const int b = interruptDataset(third, "sample 3/20 ");
    ASSERT_NE(b, -1) << "the run ended before it was interrupted";
    EXPECT_TRUE(WIFSIGNALED(b) && WTERMSIG(b) == SIGINT);
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(third)) names.push_back(e.path().filename());
    EXPECT_EQ(names, std::vector<std::string>{"samples"});
    std::size_t samples = 0;
    for (const auto& e : fs::directory_iterator(fs::path(third) / "samples")) {
        ++samples;
        EXPECT_TRUE(fs::exists(e.path() / "metadata.json")) << e.path();
    }
    EXPECT_GE(samples, 2u);
    // Resumed, it makes the rest.
    const cli::Result r =
        run("dataset " + std::string(PLANTARCH_SOURCE_DIR) +
            "/examples/datasets/bean_rows.json --out " + third + " --samples 3 --resume");
    EXPECT_EQ(r.status, 0) << r.out;
}

}  // namespace
