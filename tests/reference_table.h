// Reading the tables of reference numbers under tests/data/: tab- or space-separated rows,
// '#' comment lines, and one header row.
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace plantarch::test {

/// The data rows of tests/data/`name`, each as its cells. A file that cannot be read fails
/// the calling test (and gives no rows).
inline std::vector<std::vector<std::string>> readReferenceTable(const std::string& name) {
    const std::string path = std::string(PLANTARCH_SOURCE_DIR) + "/tests/data/" + name;
    std::ifstream in(path);
    EXPECT_TRUE(in) << "cannot read " << path;
    std::vector<std::vector<std::string>> rows;
    std::string line;
    bool header = true;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        if (header) {
            header = false;
            continue;
        }
        std::istringstream cells(line);
        std::vector<std::string> row;
        for (std::string cell; cells >> cell;) row.push_back(cell);
        rows.push_back(std::move(row));
    }
    return rows;
}

/// The reference builds each olive leaf of two back-to-back tiles (upper and lower face), 0.2
/// leaf lengths wide, and its leaf area counts both faces and their transparent corners: 0.4
/// leaf lengths squared a leaf. plantarch's olive blade is one-sided and the shape of the
/// texture's leaf, which fills 0.89 of a tile's height and 0.71 of its bounding box: the same
/// leaves measure 0.5 x 0.633 of the reference's figure (species/olive.xml says why).
inline constexpr double kOliveOneSidedShare = 0.5 * 0.633;

}  // namespace plantarch::test
