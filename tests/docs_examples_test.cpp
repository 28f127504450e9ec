// The command-line examples of README.md and docs/*.md: they write only under out/, the files
// they read are shipped, the links of the pages stay inside the repository, and the examples
// that need shipped files (obstacles) and the species format's complete example run.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.h"

namespace fs = std::filesystem;

namespace {

const fs::path kSource = PLANTARCH_SOURCE_DIR;

std::string text(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::vector<fs::path> pages() {
    std::vector<fs::path> all{kSource / "README.md"};
    for (const auto& e : fs::directory_iterator(kSource / "docs"))
        if (e.path().extension() == ".md") all.push_back(e.path());
    std::sort(all.begin(), all.end());
    return all;
}

struct Example {
    std::string page;
    std::string line;
    std::vector<std::string> words;
};

// Every line of a ```sh block that runs build/plantarch, split into words (comments dropped).
std::vector<Example> examples() {
    std::vector<Example> all;
    for (const fs::path& page : pages()) {
        std::istringstream in(text(page));
        bool sh = false;
        for (std::string line; std::getline(in, line);) {
            if (line.rfind("```", 0) == 0) {
                sh = line == "```sh";
                continue;
            }
            if (!sh || line.rfind("build/plantarch ", 0) != 0) continue;
            std::istringstream words(line.substr(0, line.find(" #")));
            Example e{page.filename().string(), line, {}};
            for (std::string w; words >> w;) e.words.push_back(w);
            all.push_back(e);
        }
    }
    return all;
}

// The paths an example writes: after -o, --output, --coco and '>', and convert's output.
std::vector<std::string> written(const Example& e) {
    std::vector<std::string> out;
    const auto& w = e.words;
    for (std::size_t i = 0; i + 1 < w.size(); ++i)
        if (w[i] == "-o" || w[i] == "--output" || w[i] == "--coco" || w[i] == ">")
            out.push_back(w[i + 1]);
    const auto convert = std::find(w.begin(), w.end(), "convert");
    if (convert != w.end() && w.end() - convert >= 3) out.push_back(*(convert + 2));
    return out;
}

// Runs an example as written from `dir` (its standard output dropped): the shell's status.
int runIn(const fs::path& dir, const Example& e) {
    std::string args;
    for (std::size_t i = 1; i < e.words.size(); ++i) args += " " + e.words[i];
    return std::system(
        ("cd '" + dir.string() + "' && " + PLANTARCH_CLI + args + " > /dev/null").c_str());
}

bool underOut(const std::string& path) {
    return path == "out" || path.rfind("out/", 0) == 0;
}

}  // namespace

TEST(DocsExamples, EveryExampleWritesUnderOut) {
    const std::vector<Example> all = examples();
    ASSERT_GT(all.size(), 60u);
    for (const Example& e : all)
        for (const std::string& path : written(e))
            EXPECT_TRUE(underOut(path)) << e.page << ": " << e.line;
}

TEST(DocsExamples, FilesTheExamplesReadAreShipped) {
    int checked = 0;
    for (const Example& e : examples())
        for (std::size_t i = 0; i + 1 < e.words.size(); ++i)
            if (e.words[i] == "--obstacle" || e.words[i] == "--attraction-points") {
                EXPECT_TRUE(fs::is_regular_file(kSource / e.words[i + 1]))
                    << e.page << ": " << e.line;
                ++checked;
            }
    EXPECT_GE(checked, 2);
}

TEST(DocsExamples, LinksStayInsideTheRepository) {
    const std::regex link(R"(\]\(([^)#\s]+)(#[^)]*)?\))");
    const fs::path root = fs::weakly_canonical(kSource);
    for (const fs::path& page : pages()) {
        const std::string body = text(page);
        for (std::sregex_iterator it(body.begin(), body.end(), link), end; it != end; ++it) {
            const std::string target = (*it)[1];
            if (target.find("://") != std::string::npos || target.rfind("mailto:", 0) == 0)
                continue;
            const fs::path resolved = fs::weakly_canonical(page.parent_path() / target);
            const std::string rel = fs::relative(resolved, root).string();
            EXPECT_FALSE(rel.rfind("..", 0) == 0)
                << page.filename() << " links outside: " << target;
            EXPECT_TRUE(fs::exists(resolved)) << page.filename() << " links to nothing: " << target;
        }
    }
}

// The obstacle examples run as written, from a folder where examples/ is the repository's.
TEST(DocsExamples, ObstacleExamplesRun) {
    const fs::path dir = fs::temp_directory_path() / "plantarch-docs-examples";
    fs::remove_all(dir);
    fs::create_directories(dir);
    fs::create_directory_symlink(kSource / "examples", dir / "examples");
    int ran = 0;
    for (const Example& e : examples()) {
        if (e.line.find("--obstacle") == std::string::npos) continue;
        ASSERT_EQ(runIn(dir, e), 0) << e.line;
        for (const std::string& path : written(e)) EXPECT_TRUE(fs::exists(dir / path)) << path;
        ++ran;
    }
    EXPECT_GE(ran, 2);
    fs::remove_all(dir);
}

// The light and physiology examples (docs/physiology.md) run as written and write what they
// name.
TEST(DocsExamples, LightExamplesRun) {
    const fs::path dir = fs::temp_directory_path() / "plantarch-docs-light-examples";
    fs::remove_all(dir);
    fs::create_directories(dir);
    int ran = 0;
    for (const Example& e : examples()) {
        const bool physiology =
            std::find(e.words.begin(), e.words.end(), "--carbon") != e.words.end();
        if (e.words.size() < 2 || (e.words[1] != "light" && !physiology)) continue;
        ASSERT_EQ(runIn(dir, e), 0) << e.line;
        for (std::size_t i = 0; i + 1 < e.words.size(); ++i) {
            if (e.words[i] == "-o" || e.words[i] == "--series" || e.words[i] == "--leaves") {
                EXPECT_TRUE(fs::exists(dir / e.words[i + 1])) << e.words[i + 1];
            }
        }
        ++ran;
    }
    EXPECT_GE(ran, 2);
    fs::remove_all(dir);
}

// The measured-plant examples (reconstruct, skeleton and MTG outputs) run as written, from a
// folder where examples/ is the repository's, and write what they name.
TEST(DocsExamples, MeasuredPlantExamplesRun) {
    const fs::path dir = fs::temp_directory_path() / "plantarch-docs-measured-examples";
    fs::remove_all(dir);
    fs::create_directories(dir / "out");
    fs::create_directory_symlink(kSource / "examples", dir / "examples");
    int ran = 0;
    for (const Example& e : examples()) {
        const bool measured =
            std::find(e.words.begin(), e.words.end(), "reconstruct") != e.words.end() ||
            e.line.find(".mtg") != std::string::npos;
        if (!measured) continue;
        ASSERT_EQ(runIn(dir, e), 0) << e.line;
        for (const std::string& path : written(e)) EXPECT_TRUE(fs::exists(dir / path)) << path;
        ++ran;
    }
    EXPECT_GE(ran, 4);
    fs::remove_all(dir);
}

// The project examples run as written, from a folder where examples/ is the repository's.
TEST(DocsExamples, ProjectExamplesRun) {
    const fs::path dir = fs::temp_directory_path() / "plantarch-docs-project-examples";
    fs::remove_all(dir);
    fs::create_directories(dir / "out");
    fs::create_directory_symlink(kSource / "examples", dir / "examples");
    int ran = 0;
    for (const Example& e : examples()) {
        // Those of shipped projects (docs/builder.md runs projects the builder saved).
        if (e.words.size() < 4 || e.words[1] != "project" || e.words[3].rfind("examples/", 0) != 0)
            continue;
        ASSERT_EQ(runIn(dir, e), 0) << e.page << ": " << e.line;
        // One file per plant (--separate) is named for each plant; its index is not.
        const bool separate = e.line.find("--separate") != std::string::npos;
        for (const std::string& path : written(e)) {
            fs::path p = dir / path;
            if (separate) p = p.parent_path() / (p.stem().string() + "_index.json");
            EXPECT_TRUE(fs::exists(p)) << e.page << ": " << path;
        }
        ++ran;
    }
    EXPECT_GE(ran, 5);
    fs::remove_all(dir);
}

// docs/species-format.md's complete example is a sensible plant at its default age.
TEST(DocsExamples, TheCompleteSpeciesExampleIsASensiblePlant) {
    const std::string doc = text(kSource / "docs" / "species-format.md");
    const std::size_t start = doc.find("```xml\n<?xml");
    ASSERT_NE(start, std::string::npos);
    const std::string xml = doc.substr(start + 7, doc.find("```", start + 7) - start - 7);
    const std::smatch age = [&] {
        std::smatch m;
        std::regex_search(xml, m, std::regex(R"(<recommended_age[^>]*default="([0-9.]+)\")"));
        return m;
    }();
    ASSERT_FALSE(age.empty());
    const fs::path file = fs::temp_directory_path() / "plantarch-docs-example_tree.xml";
    std::ofstream(file, std::ios::binary) << xml;
    const cli::Result r =
        cli::run("build " + file.string() + " --age " + age[1].str() + " --stats");
    fs::remove(file);
    ASSERT_EQ(r.status, 0) << r.out;
    auto field = [&](const std::string& name) {
        std::smatch m;
        std::regex_search(r.out, m, std::regex("\"" + name + "\": ([0-9.]+)"));
        return m.empty() ? -1.0 : std::stod(m[1]);
    };
    EXPECT_GE(field("shoots"), 5);
    EXPECT_LE(field("shoots"), 100);
    EXPECT_GT(field("leaves"), 20);
    EXPECT_LT(field("triangles"), 100000);
}
