// Growth asks its Steering (growth/steering.h), and nothing else, which way new organs point:
// each internode and petiole growth makes is offered to it once, a Steering that turns
// nothing leaves the plant exactly as unsteered growth makes it, and what it turns stays
// turned. Collision avoidance is one such Steering; these tests use their own.

#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "architecture_parts.h"
#include "plantarch/PlantArchitecture.h"

using namespace plantarch;
using plantarch::testing::Parts;

namespace {

// Counts what it is asked; with `turn`, points every new internode's guide along +x.
class Recorder final : public Steering {
public:
    explicit Recorder(bool turn) : turn_(turn) {}

    void steerShootAxis(const PlantInstance&, const Shoot&, Internode& in, float) override {
        ++axes;
        if (turn_) {
            in.guide = vec3(1.0f, 0.0f, 0.0f);
            in.rollReference = vec3(0.0f, 0.0f, 1.0f);
        }
    }
    void keepInternodeClear(const PlantInstance&, const Shoot&, Internode&) override {
        ++clearances;
    }
    void steerPetiole(const PlantInstance&, const Shoot&, const Internode&, float internodeFraction,
                      unsigned, Petiole&) override {
        ++petioles;
        // Growth offers a petiole with its internode just begun (a hundredth of full length).
        if (!(internodeFraction > 0.0f && internodeFraction <= 1.0f)) ++odd;
    }
    void steerPeduncle(const PlantInstance&, const Shoot&, unsigned, unsigned, unsigned, bool,
                       FloralBud&) override {
        ++peduncles;
    }

    unsigned axes = 0, clearances = 0, petioles = 0, peduncles = 0, odd = 0;

private:
    bool turn_;
};

struct Counts {
    unsigned phytomers = 0, petioles = 0, floralBuds = 0;
};

Counts countOf(const PlantInstance& p) {
    Counts c;
    for (const Shoot& s : p.shoots) {
        c.floralBuds += unsigned(s.terminalFloralBuds.size());
        for (const Phytomer& ph : s.phytomers) {
            ++c.phytomers;
            c.petioles += unsigned(ph.petioles.size());
            for (const Petiole& pt : ph.petioles) c.floralBuds += unsigned(pt.floralBuds.size());
        }
    }
    return c;
}

// A bean at 12 days, copied into the test's own parts.
struct Bean {
    Context ctx;
    PlantArchitecture arch{&ctx};
    unsigned id;
    Bean() {
        arch.loadPlantModelFromLibrary("bean");
        id = arch.buildPlantInstanceFromLibrary({0, 0, 0}, 12.0f);
    }
};

bool sameBits(vec3 a, vec3 b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

}  // namespace

TEST(GrowthSteering, EveryNewInternodeAndPetioleIsOfferedOnce) {
    Bean bean;
    Parts parts(bean.arch, {bean.id});
    const Counts before = countOf(parts.plant(bean.id));
    Recorder steering(false);
    parts.grow(bean.id, 50.0, &steering);
    const Counts after = countOf(parts.plant(bean.id));
    ASSERT_GT(after.phytomers, before.phytomers + 20);
    EXPECT_EQ(steering.axes, after.phytomers - before.phytomers);
    EXPECT_EQ(steering.clearances, after.phytomers - before.phytomers);
    EXPECT_EQ(steering.petioles, after.petioles - before.petioles);
    // Peduncles are offered as their buds break (the bean's first buds, made from about day
    // 12, flower 40 days later: within these 50 days).
    EXPECT_GT(steering.peduncles, 0u);
    EXPECT_LE(steering.peduncles, after.floralBuds);
    EXPECT_EQ(steering.odd, 0u);
}

TEST(GrowthSteering, ASteeringThatTurnsNothingChangesNothing) {
    Bean bean;
    Parts plain(bean.arch, {bean.id}), steered(bean.arch, {bean.id});
    Recorder steering(false);
    plain.grow(bean.id, 30.0);
    steered.grow(bean.id, 30.0, &steering);
    const PlantInstance& a = plain.plant(bean.id);
    const PlantInstance& b = steered.plant(bean.id);
    ASSERT_EQ(a.shoots.size(), b.shoots.size());
    for (std::size_t i = 0; i < a.shoots.size(); ++i) {
        ASSERT_EQ(a.shoots[i].phytomers.size(), b.shoots[i].phytomers.size());
        for (std::size_t k = 0; k < a.shoots[i].phytomers.size(); ++k) {
            const Phytomer& p = a.shoots[i].phytomers[k];
            const Phytomer& q = b.shoots[i].phytomers[k];
            EXPECT_TRUE(sameBits(p.internode.direction, q.internode.direction));
            EXPECT_TRUE(sameBits(p.internode.guide, q.internode.guide));
            ASSERT_EQ(p.petioles.size(), q.petioles.size());
            for (std::size_t j = 0; j < p.petioles.size(); ++j) {
                EXPECT_EQ(p.petioles[j].pitch, q.petioles[j].pitch);
                EXPECT_EQ(p.petioles[j].azimuth, q.petioles[j].azimuth);
            }
        }
    }
    EXPECT_EQ(Rng(a.rng).nextU32(), Rng(b.rng).nextU32());  // the same draws were made
}

TEST(GrowthSteering, TurnedInternodesStayTurned) {
    Bean bean;
    Parts parts(bean.arch, {bean.id});
    std::vector<std::size_t> existing;
    for (const Shoot& s : parts.plant(bean.id).shoots) existing.push_back(s.phytomers.size());
    Recorder steering(true);
    parts.grow(bean.id, 20.0, &steering);
    unsigned turned = 0;
    for (const Shoot& s : parts.plant(bean.id).shoots) {
        const std::size_t first = s.id < existing.size() ? existing[s.id] : 0;
        for (std::size_t k = first; k < s.phytomers.size(); ++k) {
            EXPECT_TRUE(sameBits(s.phytomers[k].internode.guide, vec3(1.0f, 0.0f, 0.0f)))
                << "shoot " << s.id << " node " << k;
            ++turned;
        }
    }
    EXPECT_EQ(turned, steering.axes);
    EXPECT_GT(turned, 10u);
}
