// OutputSet and checkOutputPath (include/plantarch/OutputFiles.h): files held back until the
// set commits, all together; nothing when it is discarded; paths checked before any work.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
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
