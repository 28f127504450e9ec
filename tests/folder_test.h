#pragma once
// A test fixture with a folder of its own under the system's temporary folder, made empty
// before each test and removed after it.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

class FolderTest : public ::testing::Test {
protected:
    /// `prefix` names the folder together with the test's name.
    explicit FolderTest(std::string prefix) : prefix_(std::move(prefix)) {}

    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = std::filesystem::temp_directory_path() / (prefix_ + info->name());
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override {
        std::error_code ignored;
        std::filesystem::remove_all(dir_, ignored);
    }

    /// A path in the folder.
    std::string at(const std::string& name) const { return (dir_ / name).string(); }
    /// Every name in the folder and below it, sorted (folders with a trailing '/').
    std::vector<std::string> names() const {
        std::vector<std::string> all;
        for (const auto& e : std::filesystem::recursive_directory_iterator(dir_))
            all.push_back(std::filesystem::relative(e.path(), dir_).string() +
                          (e.is_directory() ? "/" : ""));
        std::sort(all.begin(), all.end());
        return all;
    }
    static std::string bytes(const std::string& path) {
        std::ifstream in(path, std::ios::binary);
        std::ostringstream s;
        s << in.rdbuf();
        return s.str();
    }
    // The bytes of a file that must exist (a test comparing two files fails when either is
    // missing, instead of finding two empty texts equal).
    static std::string existingBytes(const std::string& path) {
        std::error_code error;
        if (!std::filesystem::is_regular_file(path, error)) {
            ADD_FAILURE() << "no such file: " << path;
            return "(missing " + path + ")";
        }
        return bytes(path);
    }
    static void put(const std::string& path, const std::string& text) {
        std::ofstream(path, std::ios::binary) << text;
    }

    std::filesystem::path dir_;

private:
    std::string prefix_;
};
