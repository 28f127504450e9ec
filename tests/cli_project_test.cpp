// `plantarch project run` and `project check` as a user runs them, and `plantarch builder`
// started as a command: the same bytes for any thread count, a one-block project equal to the
// canopy command's scene, one-line errors, and a server that stops cleanly on Ctrl-C.

#include <gtest/gtest.h>
#include <httplib.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <thread>

#include "cli_run.h"
#include "folder_test.h"

namespace {

class CliProject : public FolderTest {
protected:
    CliProject() : FolderTest("plantarch-cli-project-") {}
};

const char* kProject = R"({"plantarch_project": 1, "name": "trial", "seed": 11,
  "ground": {"size": [3, 3]},
  "blocks": [
    {"name": "A", "species": "bean", "count": [3, 2], "spacing": [0.3, 0.3], "age": 25},
    {"name": "B", "species": "tomato", "layout": "scatter", "origin": [1.5, 0, 0],
     "area": [1, 1], "count": 3, "age": 15, "seed": 2},
    {"name": "C", "species": "strawberry", "layout": "single", "origin": [0, 1.5, 0], "age": 20}
  ]})";

}  // namespace

TEST_F(CliProject, RunWritesTheSameBytesForAnyThreadCount) {
    put(at("p.json"), kProject);
    for (const char* threads : {"1", "2"}) {
        const auto r = cli::run(std::string("--threads ") + threads + " project run " +
                                at("p.json") + " -o " + at(std::string("t") + threads + ".glb") +
                                " -o " + at(std::string("t") + threads + ".ply"));
        ASSERT_EQ(r.status, 0) << r.out;
        EXPECT_NE(r.out.find("project trial: 3 blocks, 10 plants"), std::string::npos) << r.out;
    }
    EXPECT_GT(bytes(at("t1.glb")).size(), 100000u);
    EXPECT_TRUE(existingBytes(at("t1.glb")) == existingBytes(at("t2.glb")));
    EXPECT_TRUE(existingBytes(at("t1.ply")) == existingBytes(at("t2.ply")));
}

TEST_F(CliProject, AOneBlockProjectIsTheCanopyCommandsScene) {
    put(at("p.json"), R"({"plantarch_project": 1, "seed": 6, "blocks": [
      {"species": "bean", "count": [3, 2], "spacing": [0.3, 0.25], "germination": 0.7,
       "age": 30, "parameters": {}}]})");
    const auto p =
        cli::run("project run " + at("p.json") + " -o " + at("p.ply") + " -o " + at("p.xml"));
    ASSERT_EQ(p.status, 0) << p.out;
    const auto c = cli::run(
        "canopy bean --count 3x2 --spacing 0.3x0.25 --germination 0.7 --age 30 "
        "--seed 6 -o " +
        at("c.ply") + " -o " + at("c.xml"));
    ASSERT_EQ(c.status, 0) << c.out;
    EXPECT_TRUE(existingBytes(at("p.ply")) == existingBytes(at("c.ply")));
    EXPECT_TRUE(existingBytes(at("p.xml")) == existingBytes(at("c.xml")));
}

TEST_F(CliProject, SeparateFilesAndStats) {
    put(at("p.json"), kProject);
    const auto r = cli::run("project run " + at("p.json") + " --separate -o " + at("f/x.obj"));
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_TRUE(std::filesystem::exists(at("f/x_0009.obj")));
    const std::string index = bytes(at("f/x_index.json"));
    EXPECT_NE(index.find("\"species\": \"bean, tomato, strawberry\""), std::string::npos) << index;
    const auto s = cli::run("project run " + at("p.json") + " --stats");
    ASSERT_EQ(s.status, 0) << s.out;
    EXPECT_EQ(s.out.rfind("{\"project\": \"trial\", \"plants\": 10, \"triangles\": ", 0), 0u)
        << s.out;
}

TEST_F(CliProject, CheckNamesTheFieldOfABadValue) {
    put(at("p.json"), kProject);
    const auto ok = cli::run("project check " + at("p.json"));
    EXPECT_EQ(ok.status, 0) << ok.out;
    EXPECT_NE(ok.out.find("a project of 3 blocks (1 grid), fine."), std::string::npos) << ok.out;
    put(at("bad.json"), R"({"plantarch_project": 1, "blocks": [{"species": "bean", "age": 1e6}]})");
    const auto bad = cli::run("project check " + at("bad.json"));
    EXPECT_EQ(bad.status, 2);
    EXPECT_EQ(bad.out, "plantarch: " + at("bad.json") +
                           ": blocks/0/age = 1000000: out of range (valid: 0 to 100000 days)\n");
    const auto run = cli::run("project run " + at("bad.json") + " -o " + at("out/x.glb"));
    EXPECT_EQ(run.status, 2);
    EXPECT_FALSE(std::filesystem::exists(at("out")));
}

TEST_F(CliProject, JSONNestedDeepAndNumbersBeyondRangeGiveOneLine) {
    // 100,000 deep: refused before anything recurses on it (it used to crash `project check`
    // quoting the value).
    put(at("deep.json"), "{\"plantarch_project\": 1,\n\"name\": " + std::string(100000, '[') +
                             std::string(100000, ']') + "}");
    const auto deep = cli::run("project check " + at("deep.json"));
    EXPECT_EQ(deep.status, 2);
    EXPECT_EQ(deep.out, "plantarch: " + at("deep.json") +
                            ":2: name/0/0/0/0/0/0/0/...: nested too deep (valid: arrays and "
                            "objects nested at most "
                            "64 deep)\n");
    // Within the limit, the value is quoted cut short.
    put(at("wide.json"), "{\"plantarch_project\": 1, \"name\": " + std::string(60, '[') +
                             std::string(60, ']') + "}");
    const auto wide = cli::run("project check " + at("wide.json"));
    EXPECT_EQ(wide.status, 2);
    EXPECT_EQ(wide.out, "plantarch: " + at("wide.json") + ": name = " + std::string(57, '[') +
                            "...: expected a text in quotes\n");
    put(at("big.json"), R"({"plantarch_project": 1, "blocks": [{"species": "bean",
      "count": [2, 1e400]}]})");
    const auto big = cli::run("project run " + at("big.json") + " -o " + at("x.glb"));
    EXPECT_EQ(big.status, 2);
    EXPECT_EQ(big.out, "plantarch: " + at("big.json") +
                           ":2: blocks/0/count/1 = 1e400: out of range (valid: whole numbers 1 "
                           "to 1000000)\n");
}

TEST_F(CliProject, PipesAreNotReadAsProjectsSpeciesOrObstacles) {
    ASSERT_EQ(mkfifo(at("pipe.json").c_str(), 0600), 0);
    ASSERT_EQ(mkfifo(at("pipe.xml").c_str(), 0600), 0);
    ASSERT_EQ(mkfifo(at("pipe.obj").c_str(), 0600), 0);
    // `timeout`: a reader that opened the pipe would wait for a writer forever.
    const std::string cli = "timeout 60 " + std::string(PLANTARCH_CLI);
    const auto project = cli::runShell(cli + " project check " + at("pipe.json") + " 2>&1");
    EXPECT_EQ(project.status, 2);
    EXPECT_EQ(project.out, "plantarch: " + at("pipe.json") + ": is a FIFO, not a project file\n");
    put(at("s.json"), R"({"plantarch_project": 1, "blocks": [{"species": "pipe.xml"}]})");
    const auto species = cli::runShell(cli + " project check " + at("s.json") + " 2>&1");
    EXPECT_EQ(species.status, 2);
    EXPECT_EQ(species.out, "plantarch: " + at("s.json") +
                               ": blocks/0/species = pipe.xml: not a regular file, not a species "
                               "file (" +
                               at("pipe.xml") +
                               ") (valid: a library species name or "
                               "a species file (.xml))\n");
    put(at("o.json"), R"({"plantarch_project": 1, "obstacles": {"files": ["pipe.obj"]}})");
    const auto obstacle = cli::runShell(cli + " project check " + at("o.json") + " 2>&1");
    EXPECT_EQ(obstacle.status, 2);
    EXPECT_NE(obstacle.out.find("obstacles/files/0 = " + at("pipe.obj") +
                                ": is a FIFO, not an obstacle file"),
              std::string::npos)
        << obstacle.out;
}

TEST_F(CliProject, StatsQuoteTheProjectNameAsJSON) {
    put(at("p.json"), R"({"plantarch_project": 1, "name": "say \"hi\"\\", "blocks": [
      {"species": "bean", "layout": "single", "age": 5}]})");
    const auto s = cli::run("project run " + at("p.json") + " --stats");
    ASSERT_EQ(s.status, 0) << s.out;
    EXPECT_EQ(s.out.rfind(R"({"project": "say \"hi\"\\", "plants": 1,)", 0), 0u) << s.out;
}

TEST_F(CliProject, TheBuilderServesUntilInterrupted) {
    const std::string out = at("stdout.txt");
    const std::string command = std::string(PLANTARCH_CLI) + " builder --port 0 --output " +
                                at("b") + " >" + out + " 2>" + at("stderr.txt");
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
        execl("/bin/sh", "sh", "-c", ("exec " + command).c_str(), nullptr);
        _exit(127);
    }
    int port = 0;
    for (int i = 0; i < 500 && port == 0; ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        const std::string text = bytes(out);
        const auto colon = text.find("http://127.0.0.1:");
        if (colon != std::string::npos) port = std::atoi(text.c_str() + colon + 17);
    }
    ASSERT_GT(port, 0) << bytes(out) << bytes(at("stderr.txt"));
    httplib::Client client("127.0.0.1", port);
    auto r = client.Get("/api/config");
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 200);
    kill(pid, SIGINT);
    int status = 0;
    waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 0) << bytes(at("stderr.txt"));
    EXPECT_NE(bytes(out).find("plantarch builder: stopped"), std::string::npos);
    EXPECT_EQ(bytes(at("stderr.txt")), "");
}

TEST_F(CliProject, TheBuilderWarnsWhenListeningBeyondThisMachine) {
    const auto r =
        cli::runShell("timeout --preserve-status -s INT 2 " + std::string(PLANTARCH_CLI) +
                      " builder --port 0 --host 0.0.0.0 --output " + at("b") + " 2>&1");
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("plantarch: warning: --host 0.0.0.0: anyone who can reach this machine"),
              std::string::npos)
        << r.out;
    const auto port = cli::run("builder --port 70000");
    EXPECT_EQ(port.status, 2);
    EXPECT_NE(port.out.find("--port = 70000"), std::string::npos) << port.out;
}

// --open starts xdg-open with the page's address; its own output is dropped, and when it
// fails (no browser) one line says to open the address by hand. A stand-in xdg-open on PATH.
TEST_F(CliProject, TheBuilderOpensTheBrowserOrSaysWhy) {
    const std::string bin = at("bin");
    std::filesystem::create_directories(bin);
    auto fakeOpener = [&](int exitCode) {
        std::ofstream(bin + "/xdg-open")
            << "#!/bin/sh\necho \"$1\" > " << at("opened.txt")
            << "\necho 'xdg-open: no browser here' >&2\nexit " << exitCode << "\n";
        std::filesystem::permissions(bin + "/xdg-open", std::filesystem::perms::owner_all);
    };
    const std::string command = "PATH=" + bin + ":$PATH timeout --preserve-status -s INT 2 " +
                                std::string(PLANTARCH_CLI) + " builder --port 0 --open --output " +
                                at("b") + " 2>&1";
    fakeOpener(0);
    auto r = cli::runShell(command);
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_EQ(bytes(at("opened.txt")).rfind("http://127.0.0.1:", 0), 0u) << bytes(at("opened.txt"));
    EXPECT_EQ(r.out.find("no browser here"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("note:"), std::string::npos) << r.out;
    fakeOpener(3);
    r = cli::runShell(command);
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("plantarch: note: xdg-open found no web browser; open http://127.0.0.1:"),
              std::string::npos)
        << r.out;
    EXPECT_EQ(r.out.find("no browser here"), std::string::npos) << r.out;
}
