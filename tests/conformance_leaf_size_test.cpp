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
// One departure on purpose: the olive, whose reference leaf area counts both faces of each
// leaf and their transparent corners; its expected leaf is that share of the reference's
// (test::kOliveOneSidedShare, species/olive.xml).

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "plantarch/PlantArchitecture.h"
#include "plantarch/SpeciesIO.h"
#include "reference_table.h"

using namespace plantarch;

namespace {

struct ReferencePlant {
    std::string species;
    float age = 0.0f;
    double leafArea = 0.0;  // m^2
    double leafCount = 0.0;
};

std::vector<ReferencePlant> readReference() {
    std::vector<ReferencePlant> out;
    for (const auto& row : test::readReferenceTable("reference_leaf_size.tsv")) {
        EXPECT_EQ(row.size(), 4u) << "reference_leaf_size.tsv: a row of " << row.size() << " cells";
        if (row.size() != 4) continue;
        out.push_back({row[0], std::stof(row[1]), std::stod(row[2]), std::stod(row[3])});
        EXPECT_GT(out.back().leafCount, 0.0) << "reference_leaf_size.tsv: " << row[0];
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
        const double share = ref.species == "olive" ? test::kOliveOneSidedShare : 1.0;
        const double ratio = (area / count) / (share * ref.leafArea / ref.leafCount);
        std::ostringstream line;
        line.precision(3);
        line << "\n  " << ref.species << " at " << ref.age << " days: " << (area / count) * 1e4
             << " cm^2 a leaf, expected " << (share * ref.leafArea / ref.leafCount) * 1e4
             << " cm^2, ratio " << ratio;
        report += line.str();
        if (ratio < 1.0 - kBand || ratio > 1.0 + kBand) outside += line.str();
    }
    EXPECT_TRUE(outside.empty()) << "mean leaf area outside 1 +- " << kBand
                                 << " of the reference's:" << outside << "\nall species:" << report;
}

}  // namespace
