// Every library species against the reference system's plants at its picture age: the means
// over seeds 1 to 3 of plantarch's height, one-sided leaf area, leaf count, widths along x
// and y (along each plant's own axes for the species turned at random, kTurned), flowers and
// fruit, compared with the reference's means over its seeds 1 to 5
// (tests/data/reference_stats.tsv).
//
// Bands: height, leaf area and leaf count within 25 %; widths within 35 % (a crown's width
// hangs on a few long shoots); flowers and fruit none where the reference has none, else
// within 40 % (they come in few, discrete events; a count under ten on average is taken over
// seeds 1 to 12, as three seeds of it vary by more than the band). A species outside a band fails;
// a departure made on purpose is listed in kDepartures with its reason and its own expected value,
// and nothing else is exempt.
//
// A fidelity target not yet met by every species, so ctest leaves it out for now (see
// docs/testing.md); run it with plantarch_tests --gtest_filter='FidelityStats.*'. It prints
// the whole table of ratios either way.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "plantarch/PlantArchitecture.h"
#include "plantarch/SpeciesIO.h"
#include "reference_table.h"

using namespace plantarch;

namespace {

const char* const kQuantities[] = {"height",  "leaf_area", "leaf_count", "width_x",
                                   "width_y", "flowers",   "fruit"};

struct Reference {
    float age = 0.0f;
    std::map<std::string, double> mean;
    std::map<std::string, std::pair<double, double>> range;  // its own plants' min and max
};

std::map<std::string, Reference> readReference() {
    std::map<std::string, Reference> out;
    for (const auto& row : test::readReferenceTable("reference_stats.tsv")) {
        EXPECT_EQ(row.size(), 6u) << "reference_stats.tsv: a row of " << row.size() << " cells";
        if (row.size() != 6) continue;
        out[row[0]].age = std::stof(row[1]);
        out[row[0]].mean[row[2]] = std::stod(row[3]);
        out[row[0]].range[row[2]] = {std::stod(row[4]), std::stod(row[5])};
    }
    return out;
}

// A departure on purpose: plantarch's own expected mean for one quantity of one species.
struct Departure {
    const char* species;
    const char* quantity;
    double expected;
    const char* reason;
};
const std::vector<Departure> kDepartures = {
    {"olive", "leaf_area", 1.7153 * test::kOliveOneSidedShare,
     "one side of the blade only, without the tile's transparent corners (species/olive.xml)"},
    // The reference counts its maize tassel as 7 fruit (one mesh per tassel branch) besides the
    // 3 ears; here the tassel is one organ, a whole branched tassel (species/maize.xml): 4.
    {"maize", "fruit", 4.0, "the tassel one organ, not 7 branch meshes (species/maize.xml)"},
    // The reference sets fruit only where a fruit prototype is given, and gives ground cherry
    // none: its flowers stay closed for good. Here a closed flower sets fruit after
    // time_to_fruit_set (20 days, with probability 0.5), as the species' phenology says, so
    // the earliest flowers (initiated from day 20) have set about one fruit by day 50 (the
    // mean over seeds 1 to 20 is 0.95).
    {"groundcherryweed", "fruit", 1.0,
     "closed flowers set fruit after time_to_fruit_set; the reference, without a fruit "
     "prototype, sets none (species/groundcherryweed.xml)"},
    {"sugarbeet", "width_y", 0.6105,
     "a spiral rosette, as wide along y as the reference's is along x (species/sugarbeet.xml)"},
};

// Turned at random: the reference turns each bean, tomato, cherry tomato and soybean by a
// random yaw and roll at its base, yet every one of its plants comes out with its long side
// along x (over its seeds 1 to 5 the narrowest width_x exceeds the widest width_y); plantarch
// turns each plant as those parameters say (the species files). Their widths are compared
// along each plant's own axes: its largest extent over all horizontal directions against the
// reference's longer width, and its extent square to that against the shorter one.
const std::set<std::string> kTurned = {"bean", "tomato", "cherrytomato", "soybean"};

constexpr double kFewEvents = 10.0;
constexpr std::uint64_t kSeedsForFewEvents = 12;

// Seeds 1 to N for every quantity: 3 unless PLANTARCH_FIDELITY_SEEDS gives another count, to
// tell a systematic deficit from the luck of three seeds (the bands hold for the default).
std::uint64_t seedCount() {
    const char* env = std::getenv("PLANTARCH_FIDELITY_SEEDS");
    if (!env || !*env) return 3;
    char* end = nullptr;
    const unsigned long long n = std::strtoull(env, &end, 10);
    EXPECT_TRUE(*end == 0 && n >= 1 && n <= 1000)
        << "PLANTARCH_FIDELITY_SEEDS: " << env << " (a whole number from 1 to 1000)";
    return *end == 0 && n >= 1 && n <= 1000 ? n : 3;
}

// Four significant digits, as the reference table has them.
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

// A plant's extents along its own axes: the largest horizontal extent over every degree of
// direction, and the extent square to that direction.
std::pair<double, double> ownAxesExtents(const std::vector<vec3>& points) {
    double longest = -1.0, across = 0.0;
    for (int degree = 0; degree < 180; ++degree) {
        const double a = degree * 3.14159265358979 / 180.0;
        const double c = std::cos(a), s = std::sin(a);
        double l0 = 1e30, l1 = -1e30, w0 = 1e30, w1 = -1e30;
        for (const vec3& q : points) {
            const double along = c * q.x + s * q.y, square = c * q.y - s * q.x;
            l0 = std::min(l0, along);
            l1 = std::max(l1, along);
            w0 = std::min(w0, square);
            w1 = std::max(w1, square);
        }
        if (l1 - l0 > longest) {
            longest = l1 - l0;
            across = w1 - w0;
        }
    }
    return {longest, across};
}

std::map<std::string, double> measure(const std::string& species, float age, std::uint64_t seed) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.setSeed(seed);
    arch.loadPlantModelFromLibrary(species);
    const unsigned p = arch.buildPlantInstanceFromLibrary(vec3(0.0f), age);
    std::map<std::string, double> m;
    m["height"] = arch.getPlantHeight(p);
    m["leaf_area"] = arch.getPlantLeafArea(p);
    m["leaf_count"] = arch.getPlantLeafCount(p);
    std::vector<vec3> points;
    for (ObjectID id : arch.getAllPlantObjectIDs(p))
        points.insert(points.end(), ctx.object(id).positions.begin(),
                      ctx.object(id).positions.end());
    vec3 lo(1e30f), hi(-1e30f);
    for (const vec3& q : points) {
        lo = glm::min(lo, q);
        hi = glm::max(hi, q);
    }
    m["width_x"] = hi.x - lo.x;
    m["width_y"] = hi.y - lo.y;
    if (kTurned.count(species)) {
        const auto [longest, across] = ownAxesExtents(points);
        m["width_long"] = longest;
        m["width_short"] = across;
    }
    double flowers = 0, fruit = 0;
    // The reference counts flower and fruit objects: an organ with geometry. A fruit the
    // instant it sets has no size yet, so no geometry, and is not counted (strawberry's first
    // flower opens on day 45 and sets on day 50 exactly; the reference's 2-day time step makes
    // each 5-day stage 6 days, so its first fruit sets on day 52).
    const auto drawn = [](const FloralBud& fb) {
        double n = 0;
        for (const FlowerOrgan& f : fb.flowers) n += f.objects.empty() ? 0.0 : 1.0;
        return n;
    };
    auto count = [&](const FloralBud& fb) {
        if (fb.stage == FloralStage::FlowerClosed || fb.stage == FloralStage::FlowerOpen)
            flowers += drawn(fb);
        if (fb.stage == FloralStage::Fruit) fruit += drawn(fb);
    };
    for (const Shoot& s : arch.plant(p).shoots) {
        if (s.removed) continue;
        for (const Phytomer& ph : s.phytomers)
            for (const Petiole& pt : ph.petioles)
                for (const FloralBud& fb : pt.floralBuds) count(fb);
        for (const FloralBud& fb : s.terminalFloralBuds) count(fb);
    }
    m["flowers"] = flowers;
    m["fruit"] = fruit;
    return m;
}

}  // namespace

TEST(FidelityStats, EverySpeciesWithinItsBandsAtItsPictureAge) {
    const std::map<std::string, Reference> reference = readReference();
    ASSERT_EQ(reference.size(), listSpecies().size());
    std::string table =
        "\nspecies              age   height  leaf_area leaf_count width_x width_y "
        "flowers   fruit";
    std::size_t outside = 0;
    const std::uint64_t seeds = seedCount();
    for (const auto& [species, ref] : reference) {
        SCOPED_TRACE(species);
        std::map<std::string, double> ours;
        std::map<std::string, std::string> perSeed;  // for the message: each seed's value
        for (std::uint64_t seed = 1; seed <= seeds; ++seed)
            for (const auto& [q, v] : measure(species, ref.age, seed)) {
                ours[q] += v / double(seeds);
                if (seed <= 5) perSeed[q] += (seed > 1 ? ", " : "") + digits4(v);
            }
        // A few flowers or fruit (a mean under kFewEvents) come in so few discrete events that
        // the mean of three seeds moves by a whole band from seed to seed (grapevine_VSP: 1 to
        // 5 clusters, seeds 1 to 3 give 3.0 where 12 seeds give 2.5): those are held to the
        // mean of seeds 1 to kSeedsForFewEvents.
        for (const char* q : {"flowers", "fruit"}) {
            const double expected = ref.mean.at(q);
            if (expected == 0.0 || expected >= kFewEvents || seeds >= kSeedsForFewEvents) continue;
            double sum = 0.0;
            for (std::uint64_t seed = 1; seed <= kSeedsForFewEvents; ++seed)
                sum += measure(species, ref.age, seed).at(q);
            ours[q] = sum / double(kSeedsForFewEvents);
        }
        char row[256];
        std::snprintf(row, sizeof row, "\n%-18s %6.0f", species.c_str(), double(ref.age));
        table += row;
        for (const char* q : kQuantities) {
            double expected = ref.mean.at(q);
            const char* reason = nullptr;
            for (const Departure& d : kDepartures)
                if (species == d.species && std::string(q) == d.quantity) {
                    expected = d.expected;
                    reason = d.reason;
                }
            double got = ours[q];
            std::string measured = q;  // what plantarch's value is
            if (kTurned.count(species) && measured.starts_with("width")) {
                const double other = ref.mean.at(measured == "width_x" ? "width_y" : "width_x");
                measured = expected >= other ? "width_long" : "width_short";
                got = ours[measured];
                perSeed[q] = perSeed[measured];
                reason = "turned at random: along the plant's own axes (kTurned)";
            }
            bool ok;
            if (expected == 0.0) {
                ok = got == 0.0;
                if (ok)
                    std::snprintf(row, sizeof row, " %8s", "0");
                else
                    std::snprintf(row, sizeof row, "  %+6ld*", std::lround(got));
            } else {
                const double ratio = got / expected;
                ok = std::abs(ratio - 1.0) <= band(q);
                std::snprintf(row, sizeof row, " %7.2f%c", ratio, ok ? ' ' : '*');
            }
            table += row;
            if (!ok) ++outside;
            // The spread on both sides tells a systematic gap from three unusual plants.
            const auto [lo, hi] = ref.range.at(q);
            EXPECT_TRUE(ok) << q << ": plantarch " << (measured != q ? measured + " " : "")
                            << digits4(got) << ", expected " << digits4(expected)
                            << (reason ? std::string(" (") + reason + ")" : std::string())
                            << ", band " << band(q) * 100 << " %; plantarch's first seeds "
                            << perSeed[q] << "; the reference's 5 plants " << digits4(lo) << " to "
                            << digits4(hi);
        }
    }
    std::printf(
        "%s\n(ratio plantarch's mean over seeds 1 to %llu / reference; * outside its band; for a "
        "quantity the reference has none of, 0 or plantarch's count; the widths of the plants "
        "turned at random, kTurned, along their own long and short axes)\n%zu outside\n",
        table.c_str(), static_cast<unsigned long long>(seeds), outside);
}

// Younger plants: the reference's bean and tomato at 20 and 35 days (one plant each), against
// the mean of plantarch's seeds 1 to 3, in the same bands (height 25 %, widths 35 %). Both are
// turned at random here (see kTurned), so their widths are taken along each plant's own axes:
// the longest extent against the reference plant's longer width, the extent square to it
// against its shorter. With a single reference plant the comparison is looser than at the
// picture age.
TEST(FidelityStats, BeanAndTomatoWithinTheirBandsAtYoungerAges) {
    const auto rows = test::readReferenceTable("reference_young_plants.tsv");
    ASSERT_EQ(rows.size(), 4u);
    std::string table = "\nspecies              age   height    long   short";
    std::size_t outside = 0;
    for (const auto& row : rows) {
        ASSERT_EQ(row.size(), 5u);
        const std::string& species = row[0];
        const float age = std::stof(row[1]);
        SCOPED_TRACE(species + " at " + row[1] + " days");
        std::map<std::string, double> ours;
        const std::uint64_t seeds = seedCount();
        for (std::uint64_t seed = 1; seed <= seeds; ++seed)
            for (const auto& [q, v] : measure(species, age, seed)) ours[q] += v / double(seeds);
        char cell[64];
        std::snprintf(cell, sizeof cell, "\n%-18s %6.0f", species.c_str(), double(age));
        table += cell;
        const char* const quantities[] = {"height", "width_long", "width_short"};
        const double wx = std::stod(row[3]), wy = std::stod(row[4]);
        for (int i = 0; i < 3; ++i) {
            const double expected =
                i == 0 ? std::stod(row[2]) : (i == 1 ? std::max(wx, wy) : std::min(wx, wy));
            const double ratio = ours[quantities[i]] / expected;
            const bool ok = std::abs(ratio - 1.0) <= band(quantities[i]);
            std::snprintf(cell, sizeof cell, " %7.2f%c", ratio, ok ? ' ' : '*');
            table += cell;
            if (!ok) ++outside;
            EXPECT_TRUE(ok) << quantities[i] << ": plantarch " << digits4(ours[quantities[i]])
                            << ", reference " << digits4(expected);
        }
    }
    std::printf("%s\n(ratio plantarch / reference; * outside its band)\n%zu outside\n",
                table.c_str(), outside);
}
