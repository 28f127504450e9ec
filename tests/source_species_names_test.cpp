// No library species is named in the library's source: species are data (species/*.xml), and
// the code, its names and its texts speak of botanical forms (a spike, a drupe, a pome), not
// of the plants that happen to use them.
//
// The names come from the species directory itself, so a species added there is checked
// without a change here: each file's name (`almond_aldrich`), its first part before an
// underscore (`almond`, the species of a training variant), its common name without the
// qualifier in parentheses (`Almond Tree`) and its Latin name (`Prunus dulcis`). A name is
// found as a whole word, whatever the case, also inside identifiers: `_` and `-` separate
// words, as does a change from lower to upper case (`buildAlmondHull`), and the words of a
// name may be joined by spaces, `_`, `-` or nothing (`Ground Cherry` finds `groundcherry` and
// `ground_cherry`); a plural `s` or `es` still counts. Single words of a common name are not
// names of their own ("Tree", "Common", "Ground").

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "plantarch/SpeciesIO.h"

namespace {

namespace fs = std::filesystem;

using Words = std::vector<std::string>;  // a name as lower-case words

bool alnum(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0;
}

char lower(char c) {
    return char(std::tolower(static_cast<unsigned char>(c)));
}

bool upper(char c) {
    return std::isupper(static_cast<unsigned char>(c)) != 0;
}

// The alphanumeric words of a name, lower case ("Almond Tree (Aldrich)" without its
// parenthesis: "almond", "tree").
Words wordsOf(std::string name) {
    const std::size_t paren = name.find('(');
    if (paren != std::string::npos) name.resize(paren);
    Words words;
    std::string word;
    for (char c : name + " ") {
        if (alnum(c)) {
            word += lower(c);
        } else if (!word.empty()) {
            words.push_back(word);
            word.clear();
        }
    }
    return words;
}

// The names to look for, from every species file of the source tree.
std::set<Words> speciesNames() {
    std::set<Words> names;
    for (const auto& entry : fs::directory_iterator(fs::path(PLANTARCH_SOURCE_DIR) / "species")) {
        if (entry.path().extension() != ".xml") continue;
        const std::string stem = entry.path().stem().string();
        names.insert(wordsOf(stem));
        names.insert(wordsOf(stem.substr(0, stem.find('_'))));
        const plantarch::SpeciesModel species = plantarch::readSpeciesFile(entry.path().string());
        names.insert(wordsOf(species.commonName));
        names.insert(wordsOf(species.latinName));
    }
    names.erase(Words{});
    return names;
}

// A word starts at `i` of `line`: nothing alphanumeric before it, or a lower-case letter
// followed by an upper-case one (the start of a word inside a camelCase identifier).
bool wordStart(const std::string& line, std::size_t i) {
    return i == 0 || !alnum(line[i - 1]) ||
           (std::islower(static_cast<unsigned char>(line[i - 1])) && upper(line[i]));
}

bool wordEnd(const std::string& line, std::size_t i) {
    return i == line.size() || !alnum(line[i]) ||
           (std::islower(static_cast<unsigned char>(line[i - 1])) && upper(line[i]));
}

// Where the words of `name` are matched from `at` in `folded` (the line in lower case): the
// end of the match, or npos.
std::size_t matchFrom(const std::string& folded, std::size_t at, const Words& name) {
    std::size_t i = at;
    for (std::size_t w = 0; w < name.size(); ++w) {
        if (w > 0)
            while (i < folded.size() && (folded[i] == ' ' || folded[i] == '_' || folded[i] == '-'))
                ++i;
        if (folded.compare(i, name[w].size(), name[w]) != 0) return std::string::npos;
        i += name[w].size();
    }
    return i;
}

bool containsName(const std::string& line, const Words& name) {
    std::string folded = line;
    std::transform(folded.begin(), folded.end(), folded.begin(), lower);
    for (std::size_t at = folded.find(name[0]); at != std::string::npos;
         at = folded.find(name[0], at + 1)) {
        if (!wordStart(line, at)) continue;
        const std::size_t end = matchFrom(folded, at, name);
        if (end == std::string::npos) continue;
        for (const char* plural : {"", "s", "es"}) {
            const std::size_t n = std::char_traits<char>::length(plural);
            if (folded.compare(end, n, plural) == 0 && wordEnd(line, end + n)) return true;
        }
    }
    return false;
}

std::string joined(const Words& name) {
    std::string s;
    for (const std::string& w : name) s += (s.empty() ? "" : " ") + w;
    return s;
}

TEST(SourceText, NameMatchingFindsWholeWordsOnly) {
    const Words one{"almond"}, two{"ground", "cherry"};
    EXPECT_TRUE(containsName("// an Almond hull", one));
    EXPECT_TRUE(containsName("build_almond(x)", one));
    EXPECT_TRUE(containsName("buildAlmondHull", one));
    EXPECT_TRUE(containsName("ALMONDS", one));
    EXPECT_FALSE(containsName("almondine", one));
    EXPECT_FALSE(containsName("bitteralmond", one));
    EXPECT_TRUE(containsName("a groundcherry", two));
    EXPECT_TRUE(containsName("Ground Cherry", two));
    EXPECT_TRUE(containsName("ground_cherry_fruit", two));
    EXPECT_FALSE(containsName("ground plane, cherry", two));
    EXPECT_EQ(wordsOf("Almond Tree (Aldrich training)"), (Words{"almond", "tree"}));
}

TEST(SourceText, NoLibrarySpeciesNameInSrc) {
    const std::set<Words> names = speciesNames();
    ASSERT_GE(names.size(), 30u) << "the species directory was not read";
    std::vector<std::string> found;
    const fs::path src = fs::path(PLANTARCH_SOURCE_DIR) / "src";
    std::vector<fs::path> files;
    for (const auto& entry : fs::recursive_directory_iterator(src))
        if (entry.is_regular_file()) files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    ASSERT_FALSE(files.empty());
    for (const fs::path& file : files) {
        std::ifstream in(file);
        std::string line;
        for (int number = 1; std::getline(in, line); ++number)
            for (const Words& name : names)
                if (containsName(line, name)) {
                    found.push_back(fs::relative(file, PLANTARCH_SOURCE_DIR).string() + ":" +
                                    std::to_string(number) + ": " + joined(name));
                    break;
                }
    }
    std::string list;
    for (const std::string& f : found) list += "\n  " + f;
    EXPECT_TRUE(found.empty()) << found.size() << " lines name a library species:" << list;
}

}  // namespace
