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
