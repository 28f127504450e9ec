// Output files of every command that writes, as a user meets them: each path is checked before
// any work (one line naming it and why), a command's files appear together or not at all, and
// nothing is left behind when it fails. Inputs that are directories are called directories.

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.h"
#include "folder_test.h"

namespace fs = std::filesystem;

namespace {

class CliOutputs : public FolderTest {
protected:
    CliOutputs() : FolderTest("plantarch-cli-outputs-") {}
};

// `plantarch ARGS` run by sh after `prefix` (shell commands such as ulimit).
cli::Result runAfter(const std::string& prefix, const std::string& args) {
    return cli::runShell("sh -c '" + prefix + "; exec " + std::string(PLANTARCH_CLI) + " " + args +
                         "' 2>&1");
}

int lines(const std::string& text) {
    return int(std::count(text.begin(), text.end(), '\n'));
}

}  // namespace

TEST_F(CliOutputs, AnUnwritableSecondOutputStopsTheCommandBeforeAnyFileIsWritten) {
    const cli::Result r = cli::run("build bean --age 10 -o " + at("good.obj") + " -o /proc/x.obj");
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.out,
              "plantarch: /proc/x.obj: cannot write in folder /proc: it does not take new "
              "files\n");
    EXPECT_EQ(names(), std::vector<std::string>{});
}

// A FIFO as output is refused before any work and stays a FIFO; so is one in the place of a
// side file (a textured USD file's texture image).
TEST_F(CliOutputs, AFifoAsOutputIsRefusedAndLeftAsItWas) {
    ASSERT_EQ(::mkfifo(at("p.glb").c_str(), 0600), 0);
    const cli::Result r = cli::run("build bean --age 10 --nodes organ -o " + at("p.glb"));
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.out, "plantarch: " + at("p.glb") +
                         ": cannot write: is a FIFO, not a file (plantarch writes whole files and "
                         "puts them in place)\n");
    EXPECT_TRUE(fs::is_fifo(at("p.glb")));
    ASSERT_EQ(::mkfifo(at("t_bark_0_basecolor.png").c_str(), 0600), 0);
    const cli::Result t =
        cli::run("build bean --age 10 --materials textured --texture-size 16 -o " + at("t.usda") +
                 " -o " + at("t.ply"));
    EXPECT_EQ(t.status, 2);
    EXPECT_NE(t.out.find("t_bark_0_basecolor.png: cannot write: is a FIFO"), std::string::npos)
        << t.out;
    EXPECT_EQ(names(), (std::vector<std::string>{"p.glb", "t_bark_0_basecolor.png"}));
    EXPECT_TRUE(fs::is_fifo(at("t_bark_0_basecolor.png")));
}

TEST_F(CliOutputs, ADirectoryAsOutputIsCalledADirectoryAndLeavesNoMaterialFile) {
    fs::create_directory(at("d.obj"));
    const cli::Result r = cli::run("build bean --age 10 -o " + at("d.obj"));
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.out, "plantarch: " + at("d.obj") + ": cannot write: is a directory, not a file\n");
    EXPECT_EQ(names(), std::vector<std::string>{"d.obj/"});
    // An OBJ's material library in the way is found before any work too.
    fs::create_directory(at("m.mtl"));
    const cli::Result m = cli::run("build bean --age 10 -o " + at("m.obj"));
    EXPECT_EQ(m.status, 2);
    EXPECT_NE(m.out.find("m.obj: cannot write its materials: "), std::string::npos) << m.out;
    EXPECT_EQ(names(), (std::vector<std::string>{"d.obj/", "m.mtl/"}));
}

TEST_F(CliOutputs, ExtensionsAreReadInAnyCase) {
    const cli::Result r =
        cli::run("build bean --age 10 -o " + at("out.OBJ") + " -o " + at("plant.Xml"));
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_EQ(names(), (std::vector<std::string>{"out.OBJ", "out.mtl", "plant.Xml"}));
    EXPECT_EQ(bytes(at("plant.Xml")).rfind("<?xml", 0), 0u);
}

TEST_F(CliOutputs, AnUnknownExtensionListsEveryFormatTheCommandWrites) {
    const cli::Result r = cli::run("build bean --age 10 -o " + at("x.foo"));
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.out,
              "plantarch: " + at("x.foo") +
                  ": '.foo': unknown output format (valid: .obj, .ply, .glb, .gltf, .usda, .usdz, "
                  ".png, .npz, .xml, .helios.xml, .txt, .csv, .skeleton.csv, .mtg)\n");
    const cli::Result none = cli::run("canopy bean --count 1x1 --age 5 -o " + at("noext"));
    EXPECT_NE(none.out.find("noext: unknown output format: the name has no extension (valid: .obj"),
              std::string::npos)
        << none.out;
    EXPECT_EQ(names(), std::vector<std::string>{});
}

TEST_F(CliOutputs, RenderRefusesAnOutputThatIsNotAPicture) {
    ASSERT_EQ(cli::run("build bean --age 10 -o " + at("in.obj")).status, 0);
    const cli::Result r = cli::run("render " + at("in.obj") + " -o " + at("out.obj"));
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.out, "plantarch: " + at("out.obj") +
                         ": '.obj': render writes a PNG picture (valid: .png)\n");
    const cli::Result depth =
        cli::run("render " + at("in.obj") + " --label depth -o " + at("out.ply"));
    EXPECT_NE(depth.out.find("(valid: .png, .npy)"), std::string::npos) << depth.out;
    EXPECT_EQ(cli::run("render " + at("in.obj") + " -o " + at("view.PNG")).status, 0);
    EXPECT_EQ(names(), (std::vector<std::string>{"in.mtl", "in.obj", "view.PNG"}));
}

// Every command that writes checks its outputs before any work and writes nothing when one
// of them cannot be written.
TEST_F(CliOutputs, EveryWritingCommandChecksEveryOutputFirst) {
    ASSERT_EQ(cli::run("build bean --age 10 -o " + at("in.xml") + " -o " + at("in.obj")).status, 0);
    const std::vector<std::string> before = names();
    const std::string in = at("in.xml"), obj = at("in.obj"), out = at("new/out");
    const std::vector<std::string> commands = {
        "build bean --age 10 -o " + out + ".ply -o /proc/x.obj",
        "build bean --frames 0:4:2 -o " + out + ".glb -o /proc/x.usda",
        "canopy bean --count 2x1 --age 10 -o " + out + ".obj -o /proc/x.ply",
        "canopy bean --count 2x1 --age 10 --separate -o /proc/x.obj",
        "grow " + in + " --days 2 -o " + out + ".xml -o /proc/x.txt",
        "convert " + in + " /proc/x.ply",
        "convert " + obj + " /proc/x.ply",
        "render " + obj + " -o " + out + ".png --coco /proc/x.json",
        "render " + obj + " -o /proc/x.png",
        "scan " + in + " --scanner 1,0,0.5 --resolution 2 -o " + out + ".ply -o /proc/x.npz",
        "compare bean --age 10 -o /proc/x.png",
        "demo -o /proc/x",
    };
    for (const std::string& args : commands) {
        const cli::Result r = cli::run(args);
        EXPECT_EQ(r.status, 2) << args << "\n" << r.out;
        EXPECT_EQ(lines(r.out), 1) << args << "\n" << r.out;
        EXPECT_NE(r.out.find("plantarch: /proc/x"), std::string::npos) << args << "\n" << r.out;
        EXPECT_EQ(names(), before) << args;  // nothing written, the folder made is gone again
    }
}

// A failure in the middle of writing (here the file size limit, hit by the second, larger
// output, over 500 KB) leaves no output at all: neither a new file nor a replaced one.
TEST_F(CliOutputs, AFailedWriteLeavesEveryTargetAsItWas) {
    put(at("a.txt"), "old plant strings");
    const cli::Result r =
        runAfter("trap \"\" XFSZ; ulimit -f 1000", "build bean --age 30 -o " + at("a.txt") +
                                                       " -o " + at("b.xml") + " -o " + at("c.obj"));
    EXPECT_EQ(r.status, 2) << r.out;
    EXPECT_NE(r.out.find("c.obj: cannot write: File too large"), std::string::npos) << r.out;
    EXPECT_EQ(lines(r.out), 1) << r.out;
    EXPECT_EQ(names(), std::vector<std::string>{"a.txt"});
    EXPECT_EQ(bytes(at("a.txt")), "old plant strings");
    // The same command within the limit replaces a.txt and writes the others, together.
    ASSERT_EQ(cli::run("build bean --age 30 -o " + at("a.txt") + " -o " + at("b.xml")).status, 0);
    EXPECT_EQ(names(), (std::vector<std::string>{"a.txt", "b.xml"}));
    EXPECT_NE(bytes(at("a.txt")), "old plant strings");
}

TEST_F(CliOutputs, MissingFoldersAreMadeAndRemovedAgainWhenTheCommandFails) {
    const cli::Result ok = cli::run("build bean --age 5 -o " + at("a/b/plant.ply"));
    ASSERT_EQ(ok.status, 0) << ok.out;
    EXPECT_EQ(names(), (std::vector<std::string>{"a/", "a/b/", "a/b/plant.ply"}));
    // A bad species is found after the folders were made: they go again, a/ stays (not new).
    const cli::Result bad = cli::run("build nosuchspecies --age 5 -o " + at("a/c/d/plant.ply"));
    EXPECT_EQ(bad.status, 2);
    EXPECT_EQ(names(), (std::vector<std::string>{"a/", "a/b/", "a/b/plant.ply"}));
}

TEST_F(CliOutputs, ADirectoryGivenAsAnInputFileIsCalledADirectory) {
    fs::create_directory(at("dir.xml"));
    fs::create_directory(at("dir.obj"));
    fs::create_directory(at("dir.txt"));
    fs::create_directory(at("dir.csv"));
    const std::string x = at("dir.xml"), o = at("dir.obj");
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"build " + x + " --age 3 --stats", x + ": is a directory, not a species file"},
        {"validate " + x, x + ": is a directory, not a species file"},
        {"grow " + x + " --days 3 -o " + at("x.obj"),
         x + ": is a directory, not a plant structure file"},
        {"grow " + at("dir.txt") + " --species bean --days 3 -o " + at("x.obj"),
         at("dir.txt") + ": is a directory, not a plant string file"},
        {"convert " + o + " " + at("x.ply"), o + ": is a directory, not an OBJ file"},
        {"render " + o + " -o " + at("x.png"), o + ": is a directory, not a scene file"},
        {"scan " + o + " --scanner 1,0,0 -o " + at("x.ply"),
         o + ": is a directory, not an OBJ file"},
        {"build bean --age 3 --stats --obstacle " + o,
         o + ": --obstacle: is a directory, not an obstacle file"},
        {"build bean --age 3 --stats --attraction-points " + at("dir.csv"),
         at("dir.csv") + ": --attraction-points: is a directory, not an attraction point file"},
        {"compare bean --age 3 --reference " + o + " -o " + at("x.png"),
         o + ": is a directory, not an image file"},
    };
    for (const auto& [args, message] : cases) {
        const cli::Result r = cli::run(args);
        EXPECT_EQ(r.status, 2) << args;
        EXPECT_EQ(r.out, "plantarch: " + message + "\n") << args;
    }
    EXPECT_EQ(names(), (std::vector<std::string>{"dir.csv/", "dir.obj/", "dir.txt/", "dir.xml/"}));
}
