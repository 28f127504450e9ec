// The progress bar of the plantarch command: drawn on stderr only (with --progress always, as
// on a terminal), one bar per long stage of every command, wiped when the stage ends and
// before any message, never on stdout, never in the default mode when stderr is not a
// terminal, and never changing an output byte.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>
#include <vector>

#include "cli_run.h"

namespace fs = std::filesystem;

namespace {

class CliProgress : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("cli_progress_" +
                std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    cli::SplitResult run(const std::string& args) const {
        return cli::runSplit(args, path("scratch"));
    }

    fs::path dir_;
};

std::string readBytes(const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

bool has(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

// What a terminal shows for `text`: each '\r' returns to the start of the line, so later
// characters overwrite earlier ones; trailing blanks dropped.
std::vector<std::string> screen(const std::string& text) {
    std::vector<std::string> lines(1);
    std::size_t column = 0;
    for (char c : text) {
        if (c == '\n') {
            lines.emplace_back();
            column = 0;
        } else if (c == '\r') {
            column = 0;
        } else {
            std::string& line = lines.back();
            if (column < line.size())
                line[column] = c;
            else
                line += c;
            ++column;
        }
    }
    for (std::string& line : lines) line.erase(line.find_last_not_of(' ') + 1);
    return lines;
}

// A bar line as drawn: the stage, then "[", '#'s, blanks, "]" and a percentage.
bool drawsBar(const std::string& err, const std::string& stage) {
    return has(err, "\r" + stage) && has(err, "%");
}

}  // namespace

TEST_F(CliProgress, CanopyDrawsEachStageOnStderrAndKeepsStdoutJson) {
    const auto r = run("canopy bean --count 3x3 --age 40 --progress always --stats -o " +
                       path("a/s.obj") + " -o " + path("a/s.ply"));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(drawsBar(r.err, "building")) << r.err;
    EXPECT_TRUE(drawsBar(r.err, "writing OBJ")) << r.err;
    EXPECT_TRUE(drawsBar(r.err, "writing PLY")) << r.err;
    // The bar is wiped when each stage ends: nothing of it stays on screen.
    for (const std::string& line : screen(r.err)) EXPECT_EQ(line, "") << r.err;
    // stdout: the nine plants' JSON lines and nothing else.
    const std::vector<std::string> out = screen(r.out);
    ASSERT_EQ(out.size(), 10u) << r.out;
    for (std::size_t i = 0; i < 9; ++i)
        EXPECT_TRUE(out[i].front() == '{' && out[i].back() == '}') << out[i];
    EXPECT_EQ(out[9], "");
    EXPECT_FALSE(has(r.out, "\r") || has(r.out, "#") || has(r.out, "%")) << r.out;

    // The same command without a bar (stderr is a file, not a terminal: the default mode
    // draws nothing) prints the same and writes the same bytes.
    const auto quiet = run("canopy bean --count 3x3 --age 40 --stats -o " + path("b/s.obj") +
                           " -o " + path("b/s.ply"));
    ASSERT_EQ(quiet.status, 0) << quiet.err;
    EXPECT_EQ(quiet.err, "");
    EXPECT_EQ(quiet.out, r.out);
    EXPECT_TRUE(readBytes(path("a/s.obj")) == readBytes(path("b/s.obj")));
    EXPECT_TRUE(readBytes(path("a/s.mtl")) == readBytes(path("b/s.mtl")));
    EXPECT_TRUE(readBytes(path("a/s.ply")) == readBytes(path("b/s.ply")));
    EXPECT_GT(readBytes(path("a/s.obj")).size(), 1000000u);
    const auto never = run("canopy bean --count 3x3 --age 40 --progress never --stats");
    EXPECT_EQ(never.err, "");
    EXPECT_EQ(never.out, r.out);
}

TEST_F(CliProgress, MessagesStartOnALineOfTheirOwn) {
    const auto r = run("build bean --age 45 -v --progress always -o " + path("b.glb") + " -o " +
                       path("b.usda"));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(drawsBar(r.err, "growing")) << r.err;
    EXPECT_TRUE(drawsBar(r.err, "writing glTF")) << r.err;
    EXPECT_TRUE(drawsBar(r.err, "writing USD")) << r.err;
    std::vector<std::string> lines = screen(r.err);
    // -v's first line: how long loading and growing took (a time that varies).
    ASSERT_FALSE(lines.empty()) << r.err;
    EXPECT_TRUE(std::regex_match(
        lines.front(), std::regex(R"(plantarch: species loaded and grown in [0-9]+\.[0-9]{2} ms)")))
        << lines.front();
    lines.erase(lines.begin());
    EXPECT_EQ(lines,
              (std::vector<std::string>{"wrote " + path("b.glb"), "wrote " + path("b.usda"), ""}))
        << r.err;
    EXPECT_TRUE(has(r.out, "bean at 45 days")) << r.out;
    EXPECT_FALSE(has(r.out, "\r")) << r.out;
}

TEST_F(CliProgress, AnErrorIsPrintedOnAWipedLine) {
    // A directory where the second output should go: the first is written (with its bar),
    // then the second fails.
    fs::create_directories(path("taken.ply"));
    const auto r = run("build bean --age 40 --progress always -o " + path("ok.obj") + " -o " +
                       path("taken.ply"));
    EXPECT_EQ(r.status, 2) << r.err;
    const std::vector<std::string> lines = screen(r.err);
    ASSERT_EQ(lines.size(), 2u) << r.err;
    EXPECT_EQ(lines[0].rfind("plantarch: ", 0), 0u) << r.err;
    EXPECT_TRUE(has(lines[0], "taken.ply")) << r.err;
    EXPECT_EQ(r.out, "");
}

TEST_F(CliProgress, AnimationsShowOneBarOverTheFrames) {
    const auto r = run("build bean --frames 0:40:4 --progress always -o " + path("g.glb"));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(drawsBar(r.err, "growing")) << r.err;
    EXPECT_TRUE(drawsBar(r.err, "writing glTF")) << r.err;
    // One "growing" stage: its percentages never go back (no bar per frame).
    int last = -1;
    for (std::size_t at = r.err.find("\rgrowing"); at != std::string::npos;
         at = r.err.find("\rgrowing", at + 1)) {
        const int percent = std::stoi(r.err.substr(r.err.find(']', at) + 1));
        EXPECT_GT(percent, last) << r.err;
        last = percent;
    }
    for (const std::string& line : screen(r.err)) EXPECT_EQ(line, "") << r.err;
}

TEST_F(CliProgress, ReadingRenderingScanningAndConvertingShowBars) {
    ASSERT_EQ(
        run("canopy bean --count 2x2 --age 40 -o " + path("s.obj") + " -o " + path("s.xml")).status,
        0);
    const auto render = run("render " + path("s.obj") + " --width 200 --height 150 " +
                            "--progress always -o " + path("s.png"));
    ASSERT_EQ(render.status, 0) << render.err;
    EXPECT_TRUE(drawsBar(render.err, "reading OBJ")) << render.err;
    EXPECT_TRUE(drawsBar(render.err, "rendering")) << render.err;

    const auto convert =
        run("convert " + path("s.obj") + " " + path("c.glb") + " --progress always");
    ASSERT_EQ(convert.status, 0) << convert.err;
    EXPECT_TRUE(drawsBar(convert.err, "reading OBJ")) << convert.err;
    EXPECT_TRUE(drawsBar(convert.err, "writing glTF")) << convert.err;

    const auto scan = run("scan " + path("s.xml") + " --scanner 1,1,1.5 --resolution 0.5 " +
                          "--progress always -o " + path("scan.npz"));
    ASSERT_EQ(scan.status, 0) << scan.err;
    EXPECT_TRUE(drawsBar(scan.err, "scanning")) << scan.err;
    EXPECT_TRUE(drawsBar(scan.err, "writing NPZ")) << scan.err;
    EXPECT_FALSE(has(scan.out, "\r")) << scan.out;

    const auto grow = run("grow " + path("s.xml") + " --days 10 --progress always -o " +
                          path("g.ply") + " --points 300000");
    ASSERT_EQ(grow.status, 0) << grow.err;
    EXPECT_TRUE(drawsBar(grow.err, "growing")) << grow.err;
    EXPECT_TRUE(drawsBar(grow.err, "sampling points")) << grow.err;
    EXPECT_TRUE(drawsBar(grow.err, "writing PLY")) << grow.err;

    const auto separate = run("canopy bean --count 2x2 --age 20 --separate --progress always -o " +
                              path("sep/p.obj"));
    ASSERT_EQ(separate.status, 0) << separate.err;
    EXPECT_TRUE(drawsBar(separate.err, "writing files")) << separate.err;
    EXPECT_FALSE(has(separate.err, "writing OBJ")) << separate.err;  // one bar, not one a file
}

TEST_F(CliProgress, BadModeIsOneLine) {
    const auto r = run("build bean --age 5 --progress sometimes --stats");
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.out, "");
    EXPECT_TRUE(has(r.err, "--progress")) << r.err;
    EXPECT_TRUE(has(r.err, "sometimes")) << r.err;
    EXPECT_TRUE(has(r.err, "auto, always, never")) << r.err;
    EXPECT_EQ(screen(r.err).size(), 2u) << r.err;
}
