// OutputSet and checkOutputPath (include/plantarch/OutputFiles.h): files held back until the
// set commits, all together; nothing when it is discarded; paths checked before any work.

#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "error_of.h"
#include "folder_test.h"
#include "plantarch/Error.h"
#include "plantarch/OutputFiles.h"

namespace fs = std::filesystem;
using plantarch::Error;

namespace {

class OutputSetTest : public FolderTest {
protected:
    OutputSetTest() : FolderTest("plantarch-output-set-") {}
};

// The message of the plantarch::Error a call throws.
template <class F>
std::string errorOf(F&& f) {
    return plantarch::testing::errorOf(std::forward<F>(f)).what();
}

}  // namespace

TEST_F(OutputSetTest, FilesAppearTogetherAtCommit) {
    plantarch::writeFileAtomically(at("a.txt"), "old a");
    {
        plantarch::OutputSet set;
        plantarch::writeFileAtomically(at("a.txt"), "new a");
        plantarch::writeFileAtomically(at("b.txt"), "b");
        EXPECT_EQ(set.size(), 2u);
        EXPECT_EQ(names(), std::vector<std::string>{"a.txt"});  // nothing named yet
        EXPECT_EQ(bytes(at("a.txt")), "old a");
        set.commit();
        EXPECT_EQ(names(), (std::vector<std::string>{"a.txt", "b.txt"}));
        plantarch::writeFileAtomically(at("c.txt"), "c");  // after commit: in place at once
        EXPECT_EQ(bytes(at("c.txt")), "c");
    }
    EXPECT_EQ(bytes(at("a.txt")), "new a");
}

TEST_F(OutputSetTest, ADiscardedSetLeavesEveryTargetAsItWas) {
    plantarch::writeFileAtomically(at("a.txt"), "old a");
    {
        plantarch::OutputSet set;
        plantarch::writeFileAtomically(at("a.txt"), "new a");
        plantarch::writeFileAtomically(at("b.txt"), "b");
    }
    EXPECT_EQ(names(), std::vector<std::string>{"a.txt"});
    EXPECT_EQ(bytes(at("a.txt")), "old a");
}

TEST_F(OutputSetTest, OneSetAtATime) {
    plantarch::OutputSet set;
    EXPECT_EQ(errorOf([] { plantarch::OutputSet second; }),
              "an output set is already open: commit or discard it first");
}

TEST_F(OutputSetTest, ATargetThatBecameADirectoryReplacesNothing) {
    plantarch::writeFileAtomically(at("a.txt"), "old a");
    plantarch::OutputSet set;
    plantarch::writeFileAtomically(at("a.txt"), "new a");
    plantarch::writeFileAtomically(at("d"), "d");
    fs::create_directory(at("d"));  // made after the file was written
    EXPECT_EQ(errorOf([&] { set.commit(); }),
              at("d") + ": cannot replace file: is a directory, not a file");
    EXPECT_EQ(bytes(at("a.txt")), "old a");
    EXPECT_EQ(names(), (std::vector<std::string>{"a.txt", "d/"}));
}

// More files than the process keeps descriptors for: the later ones are named temporaries,
// still put in place together, and none is left when the set is discarded.
TEST_F(OutputSetTest, ManyFilesBeyondTheDescriptorsKept) {
    for (bool commit : {false, true}) {
        {
            plantarch::OutputSet set;
            for (int i = 0; i < 400; ++i) {
                const std::string number = std::to_string(i);
                plantarch::writeFileAtomically(at(std::string(1, 'f').append(number)), number);
            }
            EXPECT_GT(names().size(), 0u);  // the named ones are visible as temporaries
            for (const std::string& n : names()) EXPECT_NE(n.find(".tmp-"), std::string::npos);
            if (commit) set.commit();
        }
        if (!commit) {
            EXPECT_EQ(names(), std::vector<std::string>{});
        }
    }
    EXPECT_EQ(names().size(), 400u);
    EXPECT_EQ(bytes(at("f399")), "399");
}

TEST_F(OutputSetTest, CheckOutputPathSaysWhy) {
    fs::create_directory(at("d.obj"));
    EXPECT_EQ(errorOf([&] { plantarch::checkOutputPath(at("d.obj")); }),
              at("d.obj") + ": cannot write: is a directory, not a file");
    EXPECT_NE(errorOf([&] {
                  plantarch::checkOutputPath(at("none/x.obj"));
              }).find("x.obj: cannot write: no folder " + at("none")),
              std::string::npos);
    EXPECT_EQ(errorOf([] { plantarch::checkOutputPath("/proc/x.obj"); }),
              "/proc/x.obj: cannot write in folder /proc: it does not take new files");
    EXPECT_NO_THROW(plantarch::checkOutputPath(at("ok.obj")));
    EXPECT_EQ(names(), std::vector<std::string>{"d.obj/"});  // the check leaves nothing
}

// A FIFO, a device node or a socket at the target is refused, never replaced by a regular
// file: when checked, when opened and at commit (made after the file was opened). A symbolic
// link is replaced by the file; what it pointed at is left alone.
TEST_F(OutputSetTest, FifosDevicesAndSocketsAreRefusedAndLeftInPlace) {
    ASSERT_EQ(::mkfifo(at("p.glb").c_str(), 0600), 0);
    const std::string fifo = at("p.glb") + ": cannot write: is a FIFO, not a file";
    EXPECT_EQ(errorOf([&] { plantarch::checkOutputPath(at("p.glb")); }).rfind(fifo, 0), 0u);
    EXPECT_EQ(errorOf([&] { plantarch::writeFileAtomically(at("p.glb"), "x"); }).rfind(fifo, 0),
              0u);
    fs::create_symlink("/dev/null", at("null.obj"));
    EXPECT_NO_THROW(plantarch::checkOutputPath(at("null.obj")));
    EXPECT_EQ(errorOf([] { plantarch::checkOutputPath("/dev/null"); }),
              "/dev/null: cannot write: is a device, not a file (plantarch writes whole files and "
              "puts them in place)");
    const int sock = ::socket(AF_UNIX, SOCK_STREAM, 0);
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    const std::string socketPath = at("s.ply");
    ASSERT_LT(socketPath.size(), sizeof(addr.sun_path));
    std::strcpy(addr.sun_path, socketPath.c_str());
    ASSERT_EQ(::bind(sock, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)), 0);
    EXPECT_NE(errorOf([&] { plantarch::checkOutputPath(socketPath); }).find("is a socket"),
              std::string::npos);
    ::close(sock);
    {  // a FIFO made while the set was open: nothing is replaced
        plantarch::OutputSet set;
        plantarch::writeFileAtomically(at("a.txt"), "a");
        plantarch::writeFileAtomically(at("late.glb"), "late");
        ASSERT_EQ(::mkfifo(at("late.glb").c_str(), 0600), 0);
        EXPECT_EQ(errorOf([&] {
                      set.commit();
                  }).rfind(at("late.glb") + ": cannot replace file: is a FIFO", 0),
                  0u);
    }
    EXPECT_TRUE(fs::is_fifo(at("p.glb")));
    EXPECT_TRUE(fs::is_fifo(at("late.glb")));
    EXPECT_FALSE(fs::exists(at("a.txt")));
    plantarch::writeFileAtomically(at("null.obj"), "o");  // the link is replaced
    EXPECT_FALSE(fs::is_symlink(at("null.obj")));
    EXPECT_EQ(bytes(at("null.obj")), "o");
    EXPECT_TRUE(fs::is_character_file("/dev/null"));
}

// Without unnamed files (the fallback), writing works the same and a discarded file leaves
// nothing either.
TEST_F(OutputSetTest, NamedTemporariesWorkTheSame) {
    ::setenv("PLANTARCH_NAMED_TEMPORARIES", "1", 1);
    {
        plantarch::OutputSet set;
        plantarch::writeFileAtomically(at("a.txt"), "a");
        EXPECT_EQ(names().size(), 1u);
        EXPECT_NE(names()[0].find("a.txt.tmp-"), std::string::npos);
        set.commit();
    }
    {
        plantarch::OutputSet set;
        plantarch::writeFileAtomically(at("b.txt"), "b");
    }
    ::unsetenv("PLANTARCH_NAMED_TEMPORARIES");
    EXPECT_EQ(names(), std::vector<std::string>{"a.txt"});
}

TEST_F(OutputSetTest, FoldersMadeForOutputsGoAgainOrStay) {
    fs::create_directory(at("have"));
    {
        std::vector<plantarch::FolderMadeForOutputs> made =
            plantarch::makeFoldersForOutputs(at("have/a/b"));
        ASSERT_EQ(made.size(), 2u);  // "have" was there already
        EXPECT_EQ(made[0].path(), at("have/a"));
        EXPECT_EQ(made[1].path(), at("have/a/b"));
        EXPECT_TRUE(fs::is_directory(at("have/a/b")));
        for (auto m = made.rbegin(); m != made.rend(); ++m) m->remove();  // a failed job
    }
    EXPECT_FALSE(fs::exists(at("have/a")));
    EXPECT_TRUE(fs::is_directory(at("have")));
    {
        std::vector<plantarch::FolderMadeForOutputs> made =
            plantarch::makeFoldersForOutputs(at("have/c"));
        for (plantarch::FolderMadeForOutputs& m : made) m.keep();  // a job that succeeded
    }
    EXPECT_TRUE(fs::is_directory(at("have/c")));
    plantarch::writeFileAtomically(at("file"), "x");
    EXPECT_NE(errorOf([&] {
                  plantarch::makeFoldersForOutputs(at("file/d"));
              }).find("cannot create folder"),
              std::string::npos);
    EXPECT_FALSE(fs::exists(at("file/d")));
}
