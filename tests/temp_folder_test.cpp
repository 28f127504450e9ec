// Every test process works in a temporary folder of its own (TMPDIR points into it, for the
// tests and the commands they run), removed when the tests end, so the suite leaves nothing
// behind in the system's temporary folder.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace {

class TemporaryFolder : public ::testing::Environment {
public:
    TemporaryFolder() {
        const char* base = std::getenv("TMPDIR");
        path_ = std::filesystem::path(base && *base ? base : "/tmp") /
                ("plantarch-tests-" + std::to_string(::getpid()));
    }
    // Made in SetUp, not in the constructor: listing the tests (--gtest_list_tests, run by
    // CMake's test discovery after every build) constructs the environment but runs neither
    // SetUp nor TearDown, and would leave an empty folder behind each time.
    void SetUp() override {
        std::filesystem::create_directories(path_);
        ::setenv("TMPDIR", path_.c_str(), 1);
    }
    void TearDown() override {
        std::error_code ignored;
        std::filesystem::remove_all(path_, ignored);
    }
    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

TemporaryFolder* const folder =
    static_cast<TemporaryFolder*>(::testing::AddGlobalTestEnvironment(new TemporaryFolder));

}  // namespace

TEST(TemporaryFolder, TestsWriteIntoTheirOwnFolder) {
    EXPECT_EQ(std::filesystem::temp_directory_path(), folder->path());
    EXPECT_TRUE(std::filesystem::is_directory(folder->path()));
}

// Listing the tests (what CMake's test discovery does) leaves no folder behind.
TEST(TemporaryFolder, ListingTheTestsLeavesNothing) {
    const std::filesystem::path parent = folder->path() / "listing";
    std::filesystem::create_directories(parent);
    const std::string self = std::filesystem::read_symlink("/proc/self/exe").string();
    const std::string cmd = "TMPDIR='" + parent.string() + "' '" + self +
                            "' --gtest_list_tests --gtest_filter=TemporaryFolder.* > /dev/null";
    ASSERT_EQ(std::system(cmd.c_str()), 0);
    EXPECT_TRUE(std::filesystem::is_empty(parent));
}
