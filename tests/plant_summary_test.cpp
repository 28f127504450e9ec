// summarizePlant against numbers worked out another way: widths from the objects' own
// vertices, the own-axes widths against a search ten times finer and unchanged by turning
// the plant, the inclination histogram of leaves pressed flat or stood on edge, counts from
// the plant state.

#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <numbers>

#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/PlantSummary.h"

using namespace plantarch;

namespace {

struct Built {
    Context ctx;
    PlantArchitecture arch{&ctx};
    unsigned plant = 0;
    Built(const char* species, float age, std::uint64_t seed) {
        arch.setSeed(seed);
        arch.loadPlantModelFromLibrary(species);
        plant = arch.buildPlantInstanceFromLibrary(vec3(0.0f), age);
    }
    void transform(const mat4& m, bool leavesOnly) {
        for (ObjectID id : leavesOnly ? arch.getPlantObjectIDs(plant, OrganKind::Leaf)
                                      : arch.getAllPlantObjectIDs(plant))
            ctx.transformObject(id, m);
    }
    std::vector<vec3> points() const {
        std::vector<vec3> out;
        for (ObjectID id : arch.getAllPlantObjectIDs(plant))
            for (const vec3& q : ctx.object(id).positions) out.push_back(q);
        return out;
    }
};

// The largest horizontal extent over directions every tenth of a degree.
double longestExtent(const std::vector<vec3>& points) {
    double best = 0.0;
    for (int step = 0; step < 1800; ++step) {
        const double a = step * std::numbers::pi / 1800.0;
        double lo = HUGE_VAL, hi = -HUGE_VAL;
        for (const vec3& q : points) {
            const double along = std::cos(a) * q.x + std::sin(a) * q.y;
            lo = std::min(lo, along);
            hi = std::max(hi, along);
        }
        best = std::max(best, hi - lo);
    }
    return best;
}

}  // namespace

TEST(PlantSummary, WidthsFromTheVerticesAndAlongThePlantsOwnAxes) {
    Built b("maize", 50.0f, 4);
    const PlantSummary s = summarizePlant(b.arch, b.plant);
    const std::vector<vec3> pts = b.points();
    vec3 lo(HUGE_VALF), hi(-HUGE_VALF);
    for (const vec3& q : pts) {
        lo = glm::min(lo, q);
        hi = glm::max(hi, q);
    }
    EXPECT_FLOAT_EQ(s.widthX, hi.x - lo.x);
    EXPECT_FLOAT_EQ(s.widthY, hi.y - lo.y);
    // A whole-degree search misses the longest direction by at most half a degree: the extent
    // it finds is within 1 - cos(0.5 deg) (4e-5) of the finer search's, and never above it.
    const double finer = longestExtent(pts);
    EXPECT_LE(s.widthLong, finer * (1 + 1e-6));
    EXPECT_GE(s.widthLong, finer * (1 - 1e-4));
    EXPECT_GE(s.widthLong, std::max(s.widthX, s.widthY) * (1 - 1e-6));
    EXPECT_GT(s.widthShort, 0.0f);
    EXPECT_LT(s.widthShort, s.widthLong);

    // Turned about the vertical by 37 degrees: the box widths change, the own-axes ones and
    // everything else do not (up to the whole-degree search and float rounding).
    b.transform(glm::rotate(mat4(1.0f), glm::radians(37.0f), vec3(0, 0, 1)), false);
    const PlantSummary t = summarizePlant(b.arch, b.plant);
    EXPECT_GT(std::abs(t.widthX - s.widthX), 0.01f);
    EXPECT_NEAR(t.widthLong, s.widthLong, 1e-3 * s.widthLong);
    EXPECT_NEAR(t.widthShort, s.widthShort, 0.03 * s.widthShort);
    EXPECT_NEAR(t.height, s.height, 1e-5);
    for (std::size_t i = 0; i < 9; ++i)
        EXPECT_NEAR(t.leafInclination[i], s.leafInclination[i], 1e-4);
}

TEST(PlantSummary, InclinationOfLeavesPressedFlatOrStoodOnEdge) {
    Built b("bean", 40.0f, 2);
    const PlantSummary s = summarizePlant(b.arch, b.plant);
    float sum = 0.0f;
    for (float f : s.leafInclination) sum += f;
    EXPECT_NEAR(sum, 1.0f, 1e-5);
    // A bean's leaves lie in every bin from nearly flat to nearly vertical.
    EXPECT_GT(s.leafInclination[0] + s.leafInclination[1], 0.02f);
    EXPECT_GT(s.leafInclination[7] + s.leafInclination[8], 0.02f);

    // Pressed flat onto z = 0.5 m (about the leaves' middle, so no normal turns): all in 0-10.
    Built flat("bean", 40.0f, 2);
    flat.transform(glm::translate(mat4(1.0f), vec3(0, 0, 0.5f)) *
                       glm::scale(mat4(1.0f), vec3(1.0f, 1.0f, 0.0f)),
                   true);
    const PlantSummary f = summarizePlant(flat.arch, flat.plant);
    EXPECT_FLOAT_EQ(f.leafInclination[0], 1.0f);
    // Stood on edge in the plane x = 0: every normal horizontal, all in 80-90.
    Built edge("bean", 40.0f, 2);
    edge.transform(glm::scale(mat4(1.0f), vec3(0.0f, 1.0f, 1.0f)), true);
    const PlantSummary e = summarizePlant(edge.arch, edge.plant);
    EXPECT_FLOAT_EQ(e.leafInclination[8], 1.0f);
}

TEST(PlantSummary, CountsFromThePlantState) {
    Built b("bean", 70.0f, 7);  // flowers, fruit, branches
    const PlantSummary s = summarizePlant(b.arch, b.plant);
    const PlantInstance& p = b.arch.plant(b.plant);
    unsigned shoots = 0, phytomers = 0, flowers = 0, fruit = 0;
    for (const Shoot& sh : p.shoots) {
        if (sh.removed) continue;
        ++shoots;
        phytomers += unsigned(sh.phytomers.size());
        auto add = [&](const FloralBud& fb) {
            for (const FlowerOrgan& fl : fb.flowers) {
                if (fl.objects.empty()) continue;
                if (fb.stage == FloralStage::Fruit) ++fruit;
                if (fb.stage == FloralStage::FlowerOpen || fb.stage == FloralStage::FlowerClosed)
                    ++flowers;
            }
        };
        for (const Phytomer& ph : sh.phytomers)
            for (const Petiole& pt : ph.petioles)
                for (const FloralBud& fb : pt.floralBuds) add(fb);
        for (const FloralBud& fb : sh.terminalFloralBuds) add(fb);
    }
    unsigned rankShoots = 0, rankPhytomers = 0;
    for (unsigned n : s.shootsByRank) rankShoots += n;
    for (unsigned n : s.phytomersByRank) rankPhytomers += n;
    EXPECT_EQ(rankShoots, shoots);
    EXPECT_EQ(rankPhytomers, phytomers);
    EXPECT_GE(s.shootsByRank.size(), 2u);
    EXPECT_EQ(s.mainNodes, p.shoots[0].phytomers.size());
    EXPECT_EQ(s.flowers, flowers);
    EXPECT_EQ(s.fruit, fruit);
    EXPECT_GT(s.flowers + s.fruit, 0u);
    EXPECT_EQ(s.leaves, b.arch.getPlantLeafCount(b.plant));
    EXPECT_FLOAT_EQ(s.leafArea, b.arch.getPlantLeafArea(b.plant));
    EXPECT_FLOAT_EQ(s.height, b.arch.getPlantHeight(b.plant));
}

TEST(PlantSummary, ALeaflessPlantAndAnUnknownOne) {
    Built b("walnut", 400.0f, 1);  // dormant in its second winter: no leaves
    const PlantSummary s = summarizePlant(b.arch, b.plant);
    EXPECT_EQ(s.leaves, 0u);
    EXPECT_EQ(s.leafArea, 0.0f);
    for (float f : s.leafInclination) EXPECT_EQ(f, 0.0f);
    EXPECT_GT(s.height, 1.0f);
    EXPECT_THROW(summarizePlant(b.arch, b.plant + 1), Error);
}
