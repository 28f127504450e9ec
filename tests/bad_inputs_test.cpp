// The bad-input corpus (tests/bad-inputs/, format in its README.md): each case is a folder
// with a case.txt (command line, expected exit status, expected message) and the files it
// needs. The case runs in a scratch copy of its folder; the test fails on any difference:
// another status, a message not found, more or fewer lines on stderr than expected, or a
// file left behind by a command that failed.

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

const fs::path kCorpus = fs::path(PLANTARCH_SOURCE_DIR) / "tests" / "bad-inputs";

struct Case {
    std::string name;
    std::string args;
    int status = -1;
    std::vector<std::string> stderrHas;      // substrings, each must appear
    std::vector<std::string> stderrMatches;  // ECMAScript regexes, each must match somewhere
    std::vector<std::string> stdoutHas;
    int lines = 1;                      // lines on stderr
    std::vector<std::string> env;       // NAME=VALUE, {dir} is the scratch folder
    std::vector<std::string> problems;  // errors in case.txt itself
};

std::string trim(const std::string& s) {
    const auto a = s.find_first_not_of(" \t\r");
    if (a == std::string::npos) return "";
    return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
}

Case readCase(const fs::path& dir) {
    Case c;
    c.name = dir.filename().string();
    std::ifstream in(dir / "case.txt");
    if (!in) {
        c.problems.push_back("no case.txt");
        return c;
    }
    bool sawStatus = false;
    int number = 0;
    for (std::string line; std::getline(in, line);) {
        ++number;
        if (trim(line).empty() || trim(line)[0] == '#') continue;
        const auto colon = line.find(':');
        if (colon == std::string::npos) {
            c.problems.push_back("case.txt:" + std::to_string(number) + ": no 'key:'");
            continue;
        }
        const std::string key = trim(line.substr(0, colon));
        const std::string value = trim(line.substr(colon + 1));
        if (key == "args")
            c.args = value;
        else if (key == "status") {
            c.status = std::stoi(value);
            sawStatus = true;
        } else if (key == "stderr")
            c.stderrHas.push_back(value);
        else if (key == "stderr-regex")
            c.stderrMatches.push_back(value);
        else if (key == "stdout")
            c.stdoutHas.push_back(value);
        else if (key == "lines")
            c.lines = std::stoi(value);
        else if (key == "env")
            c.env.push_back(value);
        else
            c.problems.push_back("case.txt:" + std::to_string(number) + ": unknown key '" + key +
                                 "' (valid: args, status, stderr, stderr-regex, stdout, lines, "
                                 "env)");
    }
    if (c.args.empty()) c.problems.push_back("case.txt: no 'args:'");
    if (!sawStatus) c.problems.push_back("case.txt: no 'status:'");
    if (c.stderrHas.empty() && c.stderrMatches.empty())
        c.problems.push_back("case.txt: no 'stderr:' or 'stderr-regex:' (a message to expect)");
    return c;
}

std::vector<std::string> caseNames() {
    std::vector<std::string> names;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(kCorpus, ec))
        if (entry.is_directory()) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

std::string readAll(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::set<std::string> filesUnder(const fs::path& dir) {
    std::set<std::string> files;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        files.insert(fs::relative(e.path(), dir).string());
    return files;
}

std::string replaceAll(std::string s, const std::string& from, const std::string& to) {
    for (auto at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
        s.replace(at, from.size(), to);
    return s;
}

class BadInputs : public ::testing::TestWithParam<std::string> {};

}  // namespace

TEST(BadInputsCorpus, HasAtLeastSixtyWellFormedCases) {
    const std::vector<std::string> names = caseNames();
    EXPECT_GE(names.size(), 60u);
    for (const std::string& n : names) {
        const Case c = readCase(kCorpus / n);
        for (const std::string& p : c.problems) ADD_FAILURE() << n << ": " << p;
    }
}

TEST_P(BadInputs, ExitStatusAndMessage) {
    const Case c = readCase(kCorpus / GetParam());
    for (const std::string& p : c.problems) ADD_FAILURE() << p;
    if (!c.problems.empty()) return;

    // A scratch copy of the case's folder (case.txt left out), the command's working folder.
    const fs::path work = fs::temp_directory_path() / ("plantarch_bad_input_" + c.name);
    fs::remove_all(work);
    fs::create_directories(work);
    fs::copy(kCorpus / c.name, work, fs::copy_options::recursive);
    fs::remove(work / "case.txt");
    const std::set<std::string> before = filesUnder(work);

    std::string env;
    for (const std::string& e : c.env)
        env.append("'").append(replaceAll(e, "{dir}", work.string())).append("' ");
    const fs::path out = work.parent_path() / (c.name + ".stdout");
    const fs::path err = work.parent_path() / (c.name + ".stderr");
    std::string command = "cd '";
    // A case that hangs (an input read forever) fails with status 124 instead of hanging.
    command.append(work.string()).append("' && env ").append(env).append("timeout -k 10 300 ");
    command.append(PLANTARCH_CLI);
    command.append(" ").append(c.args).append(" >'").append(out.string());
    command.append("' 2>'").append(err.string()).append("'");
    const int raw = std::system(command.c_str());
    const int status = raw != -1 && WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    const std::string stdoutText = readAll(out), stderrText = readAll(err);
    const std::set<std::string> after = filesUnder(work);
    fs::remove(out);
    fs::remove(err);
    fs::remove_all(work);

    const std::string shown = "\n  plantarch " + c.args + "\n  stderr: " + stderrText +
                              "  stdout: " + stdoutText.substr(0, 300);
    EXPECT_EQ(status, c.status) << "exit status" << shown;
    for (const std::string& s : c.stderrHas)
        EXPECT_NE(stderrText.find(s), std::string::npos) << "stderr lacks: " << s << shown;
    for (const std::string& r : c.stderrMatches)
        EXPECT_TRUE(std::regex_search(stderrText, std::regex(r)))
            << "stderr does not match: " << r << shown;
    for (const std::string& s : c.stdoutHas)
        EXPECT_NE(stdoutText.find(s), std::string::npos) << "stdout lacks: " << s << shown;
    const long lines = std::count(stderrText.begin(), stderrText.end(), '\n');
    EXPECT_EQ(lines, c.lines) << "lines on stderr" << shown;
    // Every line a message of plantarch's own (no crash report, no stray library output).
    std::istringstream each(stderrText);
    for (std::string line; std::getline(each, line);)
        EXPECT_EQ(line.rfind("plantarch: ", 0), 0u) << "a line not from plantarch" << shown;
    if (c.status != 0) {
        std::vector<std::string> left;
        std::set_difference(after.begin(), after.end(), before.begin(), before.end(),
                            std::back_inserter(left));
        for (const std::string& f : left) ADD_FAILURE() << "left behind: " << f << shown;
    }
}

INSTANTIATE_TEST_SUITE_P(Corpus, BadInputs, ::testing::ValuesIn(caseNames()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                             std::string name = info.param;
                             for (char& ch : name)
                                 if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                             return name;
                         });
