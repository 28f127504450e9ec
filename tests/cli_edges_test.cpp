// The command line at its edges, where a one-line case in tests/bad-inputs/ cannot reach:
// standard output that cannot be written (a full disk), a species library holding links and
// FIFOs, and the moment between a command putting its files in place and its exit.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli.h"
#include "cli_run.h"
#include "folder_test.h"
#include "plantarch/OutputFiles.h"

namespace fs = std::filesystem;

namespace {

class CliEdges : public FolderTest {
protected:
    CliEdges() : FolderTest("plantarch-cli-edges-") {}
};

// `plantarch ARGS` with its standard output on /dev/full (every write fails with ENOSPC), and
// stderr as the result's text.
cli::Result runToFullDisk(const std::string& args) {
    return cli::runShell(std::string(PLANTARCH_CLI) + " " + args + " 2>&1 >/dev/full");
}

}  // namespace

TEST_F(CliEdges, AStandardOutputThatCannotBeWrittenFailsTheCommand) {
    ASSERT_TRUE(fs::exists("/dev/full"));
    const std::string line = "plantarch: cannot write standard output: No space left on device\n";
    for (const std::string& args : {std::string("info bean --xml"), std::string("info bean"),
                                    std::string("list"), std::string("build bean --age 5 --stats"),
                                    std::string("--help"), std::string("--version")}) {
        const cli::Result r = runToFullDisk(args);
        EXPECT_EQ(r.status, 2) << args;
        EXPECT_EQ(r.out, line) << args;
    }
    // The same commands with a standard output that takes the bytes succeed.
    EXPECT_EQ(cli::runShell(std::string(PLANTARCH_CLI) + " info bean --xml >/dev/null").status, 0);
}

TEST_F(CliEdges, StatisticsThatCannotBeWrittenLeaveNoFile) {
    // --stats is printed before the files go in place, so its failed write places none.
    const cli::Result r = runToFullDisk("build bean --age 5 --stats -o " + at("new/plant.obj"));
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.out, "plantarch: cannot write standard output: No space left on device\n");
    EXPECT_EQ(names(), std::vector<std::string>{});
}

TEST_F(CliEdges, TheLibraryListNamesEntriesThatAreNoSpeciesFile) {
    const fs::path library = fs::path(PLANTARCH_SOURCE_DIR) / "species";
    fs::copy_file(library / "bean.xml", at("bean.xml"));
    fs::create_symlink(at("gone.xml"), at("dangling.xml"));
    fs::create_symlink(at("loop.xml"), at("loop.xml"));
    ASSERT_EQ(::mkfifo(at("pipe.xml").c_str(), 0600), 0);
    const std::string env = "PLANTARCH_SPECIES_DIR=" + at("") + " ";
    const cli::SplitResult out = [&] {
        const std::string errFile = at("stderr");
        const cli::Result s = cli::runShell(env + PLANTARCH_CLI + " list 2>" + errFile);
        std::ifstream in(errFile);
        std::stringstream err;
        err << in.rdbuf();
        fs::remove(errFile);
        return cli::SplitResult{s.status, s.out, err.str()};
    }();
    EXPECT_EQ(out.status, 2);
    EXPECT_EQ(out.out.find("bean  "), 0u) << out.out;  // the good species is still listed
    EXPECT_NE(out.err.find("plantarch: skipped species 'dangling': " + at("dangling.xml") +
                           ": cannot open species file: No such file or directory\n"),
              std::string::npos)
        << out.err;
    EXPECT_NE(out.err.find("plantarch: skipped species 'loop': " + at("loop.xml") +
                           ": cannot open species file: Too many levels of symbolic links\n"),
              std::string::npos)
        << out.err;
    EXPECT_NE(out.err.find("plantarch: skipped species 'pipe': " + at("pipe.xml") + ": "),
              std::string::npos)
        << out.err;
    EXPECT_EQ(std::count(out.err.begin(), out.err.end(), '\n'), 3) << out.err;
}

// Once a command's files are in place it has succeeded: an interrupt between that moment and
// its exit must not turn it into a failure (status 130) with its files in place.
TEST_F(CliEdges, AnInterruptAfterTheFilesAreInPlaceDoesNotFailTheCommand) {
    const std::string target = at("plant.xml");
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
        plantarch::removeTemporaryFilesOnSignal();
        {
            plantarch::cli::CommandOutputs outputs({target});
            plantarch::writeFileAtomically(target, "<plants/>\n");
            outputs.commit();
            ::raise(SIGINT);  // held back from here to the exit
            ::raise(SIGTERM);
        }
        std::fflush(stdout);
        ::_exit(0);
    }
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    EXPECT_TRUE(WIFEXITED(status))
        << "ended by signal " << (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
    EXPECT_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, 0);
    EXPECT_EQ(names(), std::vector<std::string>{"plant.xml"});
}

// Before the files are in place an interrupt ends the command as usual, and the folders it
// made for its outputs go with its temporaries.
TEST_F(CliEdges, AnInterruptBeforeTheFilesAreInPlaceRemovesTheFoldersMadeForThem) {
    for (int signal : {SIGINT, SIGTERM}) {
        const std::string target = at("made/deeper/plant.xml");
        const pid_t pid = ::fork();
        ASSERT_GE(pid, 0);
        if (pid == 0) {
            plantarch::removeTemporaryFilesOnSignal();
            plantarch::cli::CommandOutputs outputs({target});
            plantarch::writeFileAtomically(target, "<plants/>\n");
            ::raise(signal);
            ::_exit(0);
        }
        int status = 0;
        ASSERT_EQ(::waitpid(pid, &status, 0), pid);
        ASSERT_TRUE(WIFSIGNALED(status));
        EXPECT_EQ(WTERMSIG(status), signal);
        EXPECT_EQ(names(), std::vector<std::string>{}) << "signal " << signal;
    }
}
