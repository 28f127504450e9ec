// Every library species against the reference system's plants at three ages: the means over
// seeds 1 to 40 of plantarch's height, one-sided leaf area, leaf count, widths along each
// plant's own horizontal axes (its longest extent and the extent square to it, so a plant
// turned at random compares with one lying along x), flowers and fruit, against the means of
// the reference's seeds 1 to 40 (tests/data/reference_stats.tsv, written from a build of the
// reference by bench/scripts/fidelity.py).
//
// Bands: height, leaf area and leaf count within 25 %; widths within 35 % (a crown's width
// hangs on a few long shoots); flowers and fruit none where the reference has none, else
// within 40 % (they come in few, discrete events). A quantity outside its band fails; a
// departure made on purpose is listed in kDepartures with its reason and its own expected
// value, and nothing else is exempt.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "plantarch/PlantArchitecture.h"
#include "plantarch/PlantSummary.h"
#include "plantarch/SpeciesIO.h"
#include "reference_table.h"

using namespace plantarch;

namespace {

const char* const kQuantities[] = {"height",      "leaf_area", "leaf_count", "width_long",
                                   "width_short", "flowers",   "fruit"};

struct Stat {
    double mean = 0.0, min = 0.0, max = 0.0;
};
using Row = std::map<std::string, Stat>;  // quantity -> the reference's numbers

// species -> age -> quantity
std::map<std::string, std::map<float, Row>> readReference() {
    std::map<std::string, std::map<float, Row>> out;
    for (const auto& row : test::readReferenceTable("reference_stats.tsv")) {
        EXPECT_EQ(row.size(), 6u) << "reference_stats.tsv: a row of " << row.size() << " cells";
        if (row.size() != 6) continue;
        out[row[0]][std::stof(row[1])][row[2]] = {std::stod(row[3]), std::stod(row[4]),
                                                  std::stod(row[5])};
    }
    return out;
}

// A departure on purpose: plantarch's own expected mean for one quantity of one species, at
// one tabled age (0: every age), given as `factor` times the reference's mean of `of` (the
// quantity itself when empty), or as the number `factor` when `of` is "value".
struct Departure {
    const char* species;
    float age;
    const char* quantity;
    const char* of;
    double factor;
    const char* reason;
};
const std::vector<Departure> kDepartures = {
    {"olive", 0, "leaf_area", "", test::kOliveOneSidedShare,
     "one side of the blade only, without the tile's transparent corners (species/olive.xml)"},
    // The reference counts its maize tassel as 7 fruit (one mesh per tassel branch) besides
    // the 3 ears (its 10 at 35 and 50 days, every seed); here the tassel is one organ.
    {"maize", 35, "fruit", "value", 4.0,
     "the tassel one organ, not 7 branch meshes (species/maize.xml)"},
    {"maize", 50, "fruit", "value", 4.0,
     "the tassel one organ, not 7 branch meshes (species/maize.xml)"},
    // The reference sets fruit only where a fruit prototype is given, and gives ground cherry
    // none: its flowers stay closed for good. Here a closed flower sets fruit after
    // time_to_fruit_set (20 days, with probability 0.5), as the species' phenology says.
    {"groundcherryweed", 50, "fruit", "value", 1.0,
     "closed flowers set fruit after time_to_fruit_set; the reference, without a fruit "
     "prototype, sets none (species/groundcherryweed.xml)"},
    // The reference's beet lays its leaves in one vertical plane (0.23-0.26 m across at every
    // age, its long side 0.52-0.64 m); the leaves here follow its 137.5 degree spiral, so the
    // rosette is as wide across as along: the reference's long side.
    {"sugarbeet", 0, "width_short", "width_long", 1.0,
     "a spiral rosette, round where the reference's is flat (species/sugarbeet.xml)"},
    // The reference's walnut makes nodes 0-3 of every shoot blind in its creation rule, but the
    // rule sees a built shoot's whole node count as every node's index and never acts on the
    // planted scaffolds: 95 of its 164 fruit at 200 days (seeds 1-20) sit on those nodes.
    // plantarch keeps them blind, as the rule says, and is held to the reference's other
    // fruit (69 of 164).
    {"walnut", 200, "fruit", "", 69.0 / 164.0,
     "nodes 0-3 blind, as the species' rule says; the reference's built scaffolds flower there "
     "(species/walnut.xml)"},
    // The reference turns each leaf to the mirror image of its petiole's azimuth (a petiole at
    // azimuth a carries its leaf toward -a), which flattens its plants across x: plantarch's
    // own plants (seeds 1-20) with their leaves mirrored that way are 0.081 and 0.123 m across
    // at 20 and 35 days, as drawn 0.156 and 0.202 m, 1.94 and 1.64 times as much. By 50 days
    // the branches set the width and both agree.
    {"groundcherryweed", 20, "width_short", "", 1.94,
     "leaves along their petioles; the reference mirrors them across x (docs/testing.md)"},
    {"groundcherryweed", 35, "width_short", "", 1.64,
     "leaves along their petioles; the reference mirrors them across x (docs/testing.md)"},
    // The reference draws the tomato's base-stem bud at node 0 twice (once as it builds the
    // plant, again as it breaks the plant's dormancy), so that bud breaks with 0.25 x 0.25 =
    // 6 % where the species says 25 %; a node-0 branch is the plant's largest (11 nodes, 77
    // leaves). Over 200 seeds plantarch's leaf count at 50 days is 1.126 of the reference's
    // (233.1 against 207.1), and 206.9 with node 0 kept from branching.
    {"tomato", 50, "leaf_count", "", 1.126,
     "the base stem's first bud breaks as the species says; the reference draws it twice "
     "(species/tomato.xml)"},
    // A leaf_scale rule multiplies a new leaf's size by s (the cherry tomato's 0.7 + 0.3 age /
    // 15: 0.7 to 0.94 for its first four leaves). The reference's plant files record that
    // size, but its geometry applies s twice (it scales the leaf's mesh by s and also divides
    // its growth fraction by s), so those leaves are drawn at s^2. Its own leaves redrawn at
    // the recorded size (area / s^2 per phytomer, seeds 1-40) have 1.373 times its leaf area
    // at 20 days; plantarch draws them at the recorded size and is held to that.
    {"cherrytomato", 20, "leaf_area", "", 1.373,
     "leaves drawn at the size a leaf_scale rule gives; the reference applies it twice "
     "(docs/testing.md)"},
    // The reference's laterals point out of the wall, where its wires are outside their cone
    // of perception (0.5-0.9 m deep at 400 days over its seeds, bare wood only); here they are
    // tied along the wires, so the wall is as deep as its leaves and fruiting shoots in leaf
    // and its wood when bare: over seeds 1-40, 0.41 m at 200 days and 0.26 m at 400.
    {"apple_fruitingwall", 200, "width_short", "value", 0.41,
     "a wall trained along its wires (species/apple_fruitingwall.xml)"},
    {"apple_fruitingwall", 400, "width_short", "value", 0.26,
     "a wall trained along its wires, bare in winter (species/apple_fruitingwall.xml)"},
};

// Seeds 1 to N: 40 unless PLANTARCH_FIDELITY_SEEDS gives another count. Fewer seeds of a
// branching species vary by a band: the tomato's leaf count over seeds 1-10 is 1.30 of the
// reference's, over seeds 1-20 1.15, over 200 seeds 1.13; the ground cherry's leaf count at
// 50 days runs from 48 to 485 over the reference's seeds 1-20.
std::uint64_t seedCount() {
    const char* env = std::getenv("PLANTARCH_FIDELITY_SEEDS");
    if (!env || !*env) return 40;
    char* end = nullptr;
    const unsigned long long n = std::strtoull(env, &end, 10);
    EXPECT_TRUE(*end == 0 && n >= 1 && n <= 1000)
        << "PLANTARCH_FIDELITY_SEEDS: " << env << " (a whole number from 1 to 1000)";
    return *end == 0 && n >= 1 && n <= 1000 ? n : 40;
}

std::string digits4(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", v);
    return text;
}

double band(const std::string& quantity) {
    if (quantity.starts_with("width")) return 0.35;
    if (quantity == "flowers" || quantity == "fruit") return 0.40;
    return 0.25;
}

std::map<std::string, double> measure(const std::string& species, float age, std::uint64_t seed) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.setSeed(seed);
    arch.loadPlantModelFromLibrary(species);
    const PlantSummary s =
        summarizePlant(arch, arch.buildPlantInstanceFromLibrary(vec3(0.0f), age));
    return {{"height", s.height},        {"leaf_area", s.leafArea},     {"leaf_count", s.leaves},
            {"width_long", s.widthLong}, {"width_short", s.widthShort}, {"flowers", s.flowers},
            {"fruit", s.fruit}};
}

}  // namespace

// One test a species (ctest runs them side by side), each printing its rows of the table.
class FidelityStats : public ::testing::TestWithParam<std::string> {};

TEST(FidelityStatsTable, EverySpeciesAtThreeOrMoreAges) {
    const auto reference = readReference();
    EXPECT_EQ(reference.size(), listSpecies().size());
    for (const std::string& species : listSpecies()) {
        ASSERT_TRUE(reference.count(species)) << species << " not in reference_stats.tsv";
        EXPECT_GE(reference.at(species).size(), 3u) << species << ": fewer than three ages";
    }
}

TEST_P(FidelityStats, WithinItsBandsAtEveryTabledAge) {
    const std::string species = GetParam();
    const auto reference = readReference();
    ASSERT_TRUE(reference.count(species));
    const std::uint64_t seeds = seedCount();
    std::string table =
        "\nspecies              age   height  leaf_area leaf_count   long   short   flowers   "
        "fruit";
    std::size_t outside = 0, compared = 0;
    {
        const auto& ages = reference.at(species);
        for (const auto& [age, ref] : ages) {
            SCOPED_TRACE(species + " at " + digits4(age) + " days");
            std::map<std::string, double> ours;
            std::map<std::string, std::string> firstSeeds;  // for the message
            for (std::uint64_t seed = 1; seed <= seeds; ++seed)
                for (const auto& [q, v] : measure(species, age, seed)) {
                    ours[q] += v / double(seeds);
                    if (seed <= 5) firstSeeds[q] += (seed > 1 ? ", " : "") + digits4(v);
                }
            char cell[64];
            std::snprintf(cell, sizeof cell, "\n%-18s %6.0f", species.c_str(), double(age));
            table += cell;
            for (const char* q : kQuantities) {
                ASSERT_TRUE(ref.count(q)) << q << " missing from reference_stats.tsv";
                double expected = ref.at(q).mean;
                const char* reason = nullptr;
                for (const Departure& d : kDepartures)
                    if (species == d.species && std::string(q) == d.quantity &&
                        (d.age == 0 || d.age == age)) {
                        const std::string of = d.of;
                        expected =
                            of == "value" ? d.factor : d.factor * ref.at(of.empty() ? q : of).mean;
                        reason = d.reason;
                    }
                const double got = ours[q];
                bool ok;
                if (expected == 0.0) {
                    ok = got == 0.0;
                    if (ok)
                        std::snprintf(cell, sizeof cell, " %8s", "0");
                    else
                        std::snprintf(cell, sizeof cell, "  %6.1f*", got);
                } else {
                    const double ratio = got / expected;
                    ok = std::abs(ratio - 1.0) <= band(q);
                    std::snprintf(cell, sizeof cell, " %7.2f%c", ratio,
                                  ok ? (reason ? '+' : ' ') : '*');
                }
                table += cell;
                ++compared;
                if (!ok) ++outside;
                EXPECT_TRUE(ok) << q << ": plantarch " << digits4(got) << ", expected "
                                << digits4(expected)
                                << (reason ? std::string(" (") + reason + ")" : std::string())
                                << ", band " << band(q) * 100 << " %; plantarch's first seeds "
                                << firstSeeds[q] << "; the reference's plants "
                                << digits4(ref.at(q).min) << " to " << digits4(ref.at(q).max);
            }
        }
    }
    std::printf(
        "%s\n(ratio of plantarch's mean over seeds 1 to %llu to the reference's, or to the "
        "departure's own expected value, marked +; * outside its band; where the reference "
        "has none, 0 or plantarch's mean)\n%zu of %zu outside\n",
        table.c_str(), static_cast<unsigned long long>(seeds), outside, compared);
}

INSTANTIATE_TEST_SUITE_P(Species, FidelityStats, ::testing::ValuesIn(listSpecies()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                             return info.param;
                         });
