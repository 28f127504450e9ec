// Leaf size of every library species against the reference system's plants: the mean area of
// one leaf (leaflets counted one by one) of plants built at the reference's picture age, seeds
// 1 to 5, is within 35 % of the reference's mean (tests/data/reference_leaf_size.tsv: its
// one-sided leaf area over its leaf count, means of its seeds 1 to 5).
//
// Why 35 %: plantarch meshes each leaf to a procedural outline where the reference draws an
// alpha-textured rectangle, and a leaf's area within the same length and width differs
// between the two by up to about 20 %; the share of young, still-growing leaves at the
// picture age moves the mean by up to about 15 % more. A leaf 1.35 times the reference's (or
// under 0.65 times) is a size a user sees.
//
// A fidelity target not yet met by every species, so ctest leaves it out for now (see
// docs/testing.md); run it with plantarch_tests --gtest_filter='ConformanceLeafSize.*'.

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "plantarch/PlantArchitecture.h"
#include "plantarch/SpeciesIO.h"

using namespace plantarch;

namespace {

struct ReferencePlant {
    std::string species;
    float age = 0.0f;
    double leafArea = 0.0;  // m^2
    double leafCount = 0.0;
};

std::vector<ReferencePlant> readReference() {
    const std::string path =
        std::string(PLANTARCH_SOURCE_DIR) + "/tests/data/reference_leaf_size.tsv";
    std::ifstream in(path);
    EXPECT_TRUE(in) << "cannot read " << path;
    std::vector<ReferencePlant> out;
    std::string line;
    bool header = true;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        if (header) {
            header = false;
            continue;
        }
        std::istringstream cells(line);
        ReferencePlant p;
        cells >> p.species >> p.age >> p.leafArea >> p.leafCount;
        EXPECT_TRUE(cells && p.leafCount > 0) << path << ": bad line '" << line << "'";
        out.push_back(p);
    }
    return out;
}

TEST(ConformanceLeafSize, MeanLeafAreaWithin35PercentOfTheReference) {
    constexpr double kBand = 0.35;
    const std::vector<ReferencePlant> reference = readReference();
    ASSERT_EQ(reference.size(), listSpecies().size());
    std::string report, outside;
    for (const ReferencePlant& ref : reference) {
        double area = 0.0, count = 0.0;
        for (std::uint64_t seed = 1; seed <= 5; ++seed) {
            Context ctx;
            PlantArchitecture arch(&ctx);
            arch.setSeed(seed);
            arch.loadPlantModelFromLibrary(ref.species);
            const unsigned p = arch.buildPlantInstanceFromLibrary(vec3(0.0f), ref.age);
            area += arch.getPlantLeafArea(p);
            count += arch.getPlantLeafCount(p);
        }
        ASSERT_GT(count, 0.0) << ref.species << " has no leaves at " << ref.age << " days";
        const double ratio = (area / count) / (ref.leafArea / ref.leafCount);
        std::ostringstream line;
        line.precision(3);
        line << "\n  " << ref.species << " at " << ref.age << " days: " << (area / count) * 1e4
             << " cm^2 a leaf, reference " << (ref.leafArea / ref.leafCount) * 1e4
             << " cm^2, ratio " << ratio;
        report += line.str();
        if (ratio < 1.0 - kBand || ratio > 1.0 + kBand) outside += line.str();
    }
    EXPECT_TRUE(outside.empty()) << "mean leaf area outside 1 +- " << kBand
                                 << " of the reference's:" << outside << "\nall species:" << report;
}

}  // namespace
