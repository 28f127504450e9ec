// The soft collision scene's refresh: leaf proxies placed by the tessellator's own formulas
// (OrganPlacer::leaves), kept per petiole while nothing that shapes them changed, and plants
// known unchanged without comparing their proxies.
//
// The tests compose the internal parts (plant store, function registry, prototype cache,
// collision state) the way the PlantArchitecture facade does, around copies of plants a
// PlantArchitecture built, so they can read and change the plants and the scene directly.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <map>
#include <memory>
#include <tuple>

#include "architecture_parts.h"
#include "collision/collision_world.h"
#include "collision/growth_driver.h"
#include "collision/proxies.h"
#include "geometry/organ_sink.h"
#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"

using namespace plantarch;
using plantarch::testing::Parts;

namespace {

// Every leaf tessellation places: its prototype and transform, in tessellation order.
struct PlacedLeaf {
    const OrganPrototype* prototype;
    mat4 transform;
};

class LeafCapture final : public OrganSink {
public:
    std::vector<PlacedLeaf> leaves;
    bool wants(OrganKind kind) const override { return kind == OrganKind::Leaf; }
    void write(ObjectID&, const Mesh&, const Material&, const OrganLabels&) override {}
    void writeParts(std::vector<ObjectID>&, const OrganPrototype& prototype, const mat4& xf,
                    const OrganLabels&) override {
        leaves.push_back({&prototype, xf});
    }
};

std::vector<PlacedLeaf> tessellatedLeaves(Parts& parts, PlantInstance& plant) {
    LeafCapture sink;
    tessellatePlant(parts.store, parts.prototypes, sink, plant);
    return sink.leaves;
}

using PetioleID = std::tuple<unsigned, unsigned, unsigned>;
struct KeptTrig {
    PetioleTrig petiole;
    std::vector<LeafTrig> leaves;
};

// The same leaves by OrganPlacer::leaves, with the sines kept in `trigs` from call to call.
// Checks on the way that the start it returns is petioleStart's and petioleStartOn's.
std::vector<PlacedLeaf> placerLeaves(Parts& parts, PlantInstance& plant,
                                     std::map<PetioleID, KeptTrig>& trigs) {
    std::vector<PlacedLeaf> out;
    OrganPlacer placer(parts.store, parts.prototypes, plant);
    std::vector<LeafPlacement> leaves;
    for (const Shoot& s : plant.shoots) {
        if (s.removed) continue;
        for (unsigned k = 0; k < s.phytomers.size(); ++k)
            for (unsigned j = 0; j < s.phytomers[k].petioles.size(); ++j) {
                vec3 side;
                KeptTrig& kept = trigs[{s.id, k, j}];
                kept.leaves.resize(s.phytomers[k].petioles[j].leaves.size());
                const vec3 start =
                    placer.leaves(s.id, k, j, kept.petiole, kept.leaves, leaves, side);
                const vec3 expected = placer.petioleStart(s.id, k, j);
                const vec3 on = placer.petioleStartOn(s.id, k, side);
                EXPECT_EQ(std::memcmp(&start, &expected, sizeof start), 0);
                EXPECT_EQ(std::memcmp(&on, &expected, sizeof on), 0);
                EXPECT_EQ(leaves.size(), s.phytomers[k].petioles[j].leaves.size());
                for (const LeafPlacement& l : leaves)
                    if (l.prototype) out.push_back({l.prototype, l.transform});
            }
    }
    return out;
}

// Equal to the bit.
void expectSameLeaves(const std::vector<PlacedLeaf>& a, const std::vector<PlacedLeaf>& b) {
    ASSERT_EQ(a.size(), b.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (a[i].prototype != b[i].prototype ||
            std::memcmp(&a[i].transform, &b[i].transform, sizeof(mat4)) != 0)
            ++differ;
    EXPECT_EQ(differ, 0u) << "of " << a.size() << " leaves";
}

// The leaf proxies of a plant placed afresh by the tessellator.
collision::TriangleSoup freshProxies(Parts& parts, PlantInstance& plant,
                                     std::vector<collision::OrganTag>& tags) {
    collision::TriangleSoup soup;
    CollisionOrgans leaves;  // leaves only (the default)
    collision::ProxySink sink(collision::proxyCache(parts.collision), leaves, soup, tags);
    tessellatePlant(parts.store, parts.prototypes, sink, plant);
    return soup;
}

// The scene's proxies of every plant are where the tessellator puts the leaves now (to
// rounding: kept proxies are moved with their petiole's start), with the same tags, and the
// spheres and cells the grid bins them by are those of these triangles.
void expectSceneMatchesLeaves(Parts& parts) {
    const collision::World& world = parts.world();
    for (const auto& [id, plant] : parts.store.plants) {
        const collision::PlantProxies* p = world.plantProxies(id);
        ASSERT_NE(p, nullptr) << id;
        std::vector<collision::OrganTag> tags;
        const collision::TriangleSoup fresh = freshProxies(parts, parts.plant(id), tags);
        ASSERT_EQ(p->triangles.size(), fresh.size()) << id;
        EXPECT_EQ(p->tags, tags) << id;
        float worst = 0.0f;
        for (std::size_t i = 0; i < fresh.size(); ++i)
            worst = std::max(worst, glm::length(p->triangles[i] - fresh[i]));
        EXPECT_LT(worst, 1e-6f) << id;
        std::vector<glm::vec4> spheres;
        std::vector<std::uint64_t> keys;
        collision::boundingSpheres(p->triangles, spheres);
        collision::SoftGrid::cellKeys(spheres, p->keyCell, keys);
        ASSERT_EQ(spheres.size(), p->spheres.size()) << id;
        EXPECT_EQ(
            std::memcmp(spheres.data(), p->spheres.data(), spheres.size() * sizeof(glm::vec4)), 0)
            << id;
        EXPECT_EQ(keys, p->keys) << id;
    }
}

}  // namespace

// OrganPlacer::leaves gives tessellation's transforms to the bit, also with the sines kept
// from an earlier placement, and after the angles they were taken of changed.
TEST(CollisionRefresh, LeafPlacementsAreTheTessellators) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    const unsigned id = arch.buildPlantInstanceFromLibrary({0, 0, 0}, 25.0f);
    Parts parts(arch, {id});
    PlantInstance& plant = parts.plant(id);
    std::map<PetioleID, KeptTrig> trigs;
    expectSameLeaves(placerLeaves(parts, plant, trigs), tessellatedLeaves(parts, plant));
    ASSERT_GT(trigs.size(), 10u);

    // Grown: lengths and leaf sizes change, the kept sines still hold.
    parts.grow(id, 4.0);
    expectSameLeaves(placerLeaves(parts, plant, trigs), tessellatedLeaves(parts, plant));

    // Angles changed behind the kept sines: they are taken again.
    int changed = 0;
    for (Shoot& s : plant.shoots)
        for (Phytomer& ph : s.phytomers)
            for (Petiole& pt : ph.petioles) {
                switch (changed++ % 4) {
                    case 0:
                        pt.azimuth += 17.0f;
                        break;
                    case 1:
                        pt.pitch -= 9.0f;
                        break;
                    case 2:
                        pt.curvature = -pt.curvature - 50.0f;
                        break;
                    default:
                        pt.clearance = {glm::normalize(vec3(0.3f, -1.0f, 0.2f)), 12.0f};
                        break;
                }
                for (LeafOrgan& leaf : pt.leaves) {
                    leaf.pitch += 3.0f;
                    leaf.roll = -leaf.roll;
                    leaf.yaw += 1.0f;
                }
                // Leaves moved along the petiole: some to where the one before them sits.
                for (std::size_t i = 1; i < pt.leaves.size(); ++i)
                    pt.leaves[i].position =
                        i % 2 ? pt.leaves[i - 1].position : 0.5f * pt.leaves[i].position;
            }
    Shoot& longest =
        *std::max_element(plant.shoots.begin(), plant.shoots.end(),
                          [](auto& a, auto& b) { return a.phytomers.size() < b.phytomers.size(); });
    ASSERT_GE(longest.phytomers.size(), 3u);
    Internode& in = longest.phytomers[1].internode;
    in.direction = glm::normalize(in.direction + vec3(0.1f, 0.0f, 0.0f));
    // The axes a petiole's lean is taken from turned behind the kept lean.
    Internode& turnedAxes = longest.phytomers[2].internode;
    turnedAxes.guide = glm::normalize(turnedAxes.guide + vec3(0.0f, 0.2f, 0.0f));
    Internode& rolled = longest.phytomers[0].internode;
    rolled.rollReference = glm::normalize(rolled.rollReference + vec3(0.2f, 0.1f, 0.0f));
    expectSameLeaves(placerLeaves(parts, plant, trigs), tessellatedLeaves(parts, plant));
    // Only the clearance turns' angles, their axes, the internodes' guides or their directions
    // changed, one at a time.
    for (int what = 0; what < 4; ++what) {
        int turns = 0;
        for (Shoot& s : plant.shoots)
            for (Phytomer& ph : s.phytomers) {
                Internode& axes = ph.internode;
                if (what == 2) axes.guide = glm::normalize(axes.guide + vec3(0.1f, -0.2f, 0.05f));
                if (what == 3)
                    axes.direction = glm::normalize(axes.direction + vec3(-0.05f, 0.1f, 0.0f));
                for (Petiole& pt : ph.petioles) {
                    if (pt.clearance.angle == 0.0f) continue;
                    ++turns;
                    if (what == 0) pt.clearance.angle += 5.0f;
                    if (what == 1)
                        pt.clearance.axis =
                            glm::normalize(pt.clearance.axis + vec3(0.0f, 0.0f, 0.3f));
                }
            }
        ASSERT_GT(turns, 3);
        expectSameLeaves(placerLeaves(parts, plant, trigs), tessellatedLeaves(parts, plant));
    }
    // One kept angle per leaf, or an error.
    {
        OrganPlacer placer(parts.store, parts.prototypes, plant);
        KeptTrig& kept = trigs.begin()->second;
        const auto [s, k, j] = trigs.begin()->first;
        std::vector<LeafTrig> fewer(kept.leaves.size() - 1);
        std::vector<LeafPlacement> leaves;
        vec3 side;
        EXPECT_THROW(placer.leaves(s, k, j, kept.petiole, fewer, leaves, side), Error);
    }
    // And fresh sines give the same.
    std::map<PetioleID, KeptTrig> fresh;
    expectSameLeaves(placerLeaves(parts, plant, fresh), tessellatedLeaves(parts, plant));
}

// A canopy grown day by day with soft avoidance: after every refresh each plant's proxies are
// where its leaves are, though most petioles keep their proxies from earlier refreshes.
TEST(CollisionRefresh, ProxiesFollowTheLeavesAcrossRefreshes) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.setSeed(5);
    arch.loadPlantModelFromLibrary("bean");
    const std::vector<unsigned> ids =
        arch.buildPlantCanopyFromLibrary({0, 0, 0}, {0.15f, 0.15f}, {2, 2}, 8.0f);
    Parts parts(arch, ids);
    parts.enableSoftAvoidance();
    parts.advance(0.0);  // the plants enter the scene
    expectSceneMatchesLeaves(parts);
    for (int day = 0; day < 20; ++day) {
        parts.advance(1.0);
        expectSceneMatchesLeaves(parts);
    }
    // Both ways were taken: petioles placed again and petioles kept.
    std::uint64_t placed = 0, read = 0;
    for (const auto& [id, memo] : parts.world().memos) {
        placed += memo->placements;
        read += memo->reads;
    }
    EXPECT_GT(placed, 100u);
    EXPECT_GT(read, placed + 100u);
}

// Plants that did not change keep their proxies (not even compared); an edited plant gets
// proxies of its new state. Through the facade: its edits mark the plant for a rebuild.
TEST(CollisionRefresh, UnchangedPlantsAreKeptEditedOnesRebuilt) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    arch.enableSoftCollisionAvoidance();
    const std::vector<unsigned> ids =
        arch.buildPlantCanopyFromLibrary({0, 0, 0}, {0.2f, 0.2f}, {3, 1}, 20.0f);

    const CollisionStats before = arch.getCollisionStats();
    for (unsigned id : ids) arch.updateGeometry(id);  // read again at the next call
    arch.advanceTime(0.0);
    CollisionStats after = arch.getCollisionStats();
    EXPECT_EQ(after.plantsUnchanged - before.plantsUnchanged, ids.size());
    EXPECT_EQ(after.plantsRebuilt, before.plantsRebuilt);

    // Leaves removed from one plant, a branch pruned on another.
    auto longest = [&](unsigned plant) {
        unsigned best = 0;
        for (unsigned s = 1; s < arch.getShootCount(plant); ++s)
            if (arch.getShootNodeCount(plant, s) > arch.getShootNodeCount(plant, best)) best = s;
        return best;
    };
    arch.removeShootLeaves(ids[0], longest(ids[0]));
    ASSERT_GE(arch.getShootNodeCount(ids[1], longest(ids[1])), 4u);
    arch.pruneBranch(ids[1], longest(ids[1]), 2);
    arch.advanceTime(0.0);
    const CollisionStats edited = arch.getCollisionStats();
    EXPECT_EQ(edited.plantsRebuilt - after.plantsRebuilt, 2u);
    EXPECT_EQ(edited.plantsUnchanged, after.plantsUnchanged);  // the third is not read again
}

// The same in the scene itself: unchanged plants keep the very same proxies; an edited one
// gets fewer, where its leaves now are, and stays there as the plants grow on.
TEST(CollisionRefresh, EditedPlantsGetProxiesOfTheirNewState) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    const std::vector<unsigned> ids =
        arch.buildPlantCanopyFromLibrary({0, 0, 0}, {0.2f, 0.2f}, {3, 1}, 20.0f);
    Parts parts(arch, ids);
    parts.enableSoftAvoidance();
    parts.advance(0.0);
    const collision::World& world = parts.world();
    std::vector<const vec3*> data;
    for (unsigned id : ids) data.push_back(world.plantProxies(id)->triangles.data());
    for (unsigned id : ids) parts.world().stale[id] = true;  // read again at the next call
    parts.advance(0.0);
    for (std::size_t i = 0; i < ids.size(); ++i)
        EXPECT_EQ(world.plantProxies(ids[i])->triangles.data(), data[i]);  // untouched

    // The leaves of the first plant's longest shoot removed.
    PlantInstance& edited = parts.plant(ids[0]);
    Shoot& longest =
        *std::max_element(edited.shoots.begin(), edited.shoots.end(),
                          [](auto& a, auto& b) { return a.phytomers.size() < b.phytomers.size(); });
    for (Phytomer& ph : longest.phytomers)
        for (Petiole& pt : ph.petioles)
            for (LeafOrgan& l : pt.leaves) l.removed = true;
    const std::size_t full = world.plantProxies(ids[0])->triangles.size();
    parts.world().stale[ids[0]] = true;
    parts.advance(0.0);
    EXPECT_LT(world.plantProxies(ids[0])->triangles.size(), full);
    EXPECT_EQ(world.plantProxies(ids[2])->triangles.data(), data[2]);
    expectSceneMatchesLeaves(parts);
    parts.advance(2.0);
    expectSceneMatchesLeaves(parts);
}

// buildProxies tells whether a plant's proxies may have changed since its last call: not when
// nothing moved, yes when petioles only moved with the stem (kept, moved along) or a leaf fell.
TEST(CollisionRefresh, BuildProxiesKnowsWhatChanged) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    const unsigned id = arch.buildPlantInstanceFromLibrary({0, 0, 0}, 25.0f);
    Parts parts(arch, {id});
    PlantInstance& plant = parts.plant(id);
    const collision::Worker worker = parts.worker();
    collision::PlantProxyMemo memo;
    collision::TriangleSoup soup;
    std::vector<collision::OrganTag> tags;
    const CollisionOrgans leaves;
    auto expectFresh = [&] {
        std::vector<collision::OrganTag> freshTags;
        const collision::TriangleSoup fresh = freshProxies(parts, plant, freshTags);
        ASSERT_EQ(soup.size(), fresh.size());
        EXPECT_EQ(tags, freshTags);
        float worst = 0.0f;
        for (std::size_t i = 0; i < fresh.size(); ++i)
            worst = std::max(worst, glm::length(soup[i] - fresh[i]));
        EXPECT_LT(worst, 1e-6f);
    };
    EXPECT_TRUE(collision::buildProxies(worker, plant, leaves, memo, soup, tags));
    expectFresh();
    const std::uint64_t placed = memo.placements;
    EXPECT_EQ(placed, memo.reads);
    EXPECT_FALSE(collision::buildProxies(worker, plant, leaves, memo, soup, tags));
    expectFresh();

    // The stems thicken: every petiole's start moves, none is placed again.
    for (Shoot& s : plant.shoots)
        for (Phytomer& ph : s.phytomers) ph.internode.radius *= 1.5f;
    EXPECT_TRUE(collision::buildProxies(worker, plant, leaves, memo, soup, tags));
    expectFresh();
    EXPECT_EQ(memo.placements, placed);
    EXPECT_FALSE(collision::buildProxies(worker, plant, leaves, memo, soup, tags));

    // A leaf falls: its petiole is placed again, with one leaf fewer.
    const std::size_t before = soup.size();
    for (Shoot& s : plant.shoots)
        for (Phytomer& ph : s.phytomers)
            for (Petiole& pt : ph.petioles)
                if (!pt.leaves.empty() && memo.placements == placed) {
                    pt.leaves.back().removed = true;
                    EXPECT_TRUE(collision::buildProxies(worker, plant, leaves, memo, soup, tags));
                }
    EXPECT_EQ(memo.placements, placed + 1);
    EXPECT_LT(soup.size(), before);
    expectFresh();

    // Leaves fall everywhere, one a petiole at a time, until none is left (petioles whose
    // proxies shrink leave room behind in the memo, which is taken back on the way).
    for (int round = 0; round < 4; ++round) {
        for (Shoot& s : plant.shoots)
            for (Phytomer& ph : s.phytomers)
                for (Petiole& pt : ph.petioles) {
                    auto standing = std::find_if(pt.leaves.rbegin(), pt.leaves.rend(),
                                                 [](const LeafOrgan& l) { return !l.removed; });
                    if (standing != pt.leaves.rend()) standing->removed = true;
                }
        EXPECT_EQ(collision::buildProxies(worker, plant, leaves, memo, soup, tags), round < 3);
        expectFresh();
    }
    EXPECT_TRUE(soup.empty());
    std::size_t kept = 0;
    for (const auto& m : memo.shoots) kept += m.local.size();
    EXPECT_LT(kept, before / 2);  // taken back
}

// Prototypes and their outlines are kept by pointer within one growth call only: dropping the
// prototype caches between calls (as registering a prototype function does) makes the next
// call look them up again (built anew from the same keys, so the same shapes) instead of
// reading freed ones.
TEST(CollisionRefresh, PrototypesAreLookedUpAgainAfterTheCachesAreCleared) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    const std::vector<unsigned> ids =
        arch.buildPlantCanopyFromLibrary({0, 0, 0}, {0.15f, 0.15f}, {2, 2}, 12.0f);
    Parts parts(arch, ids);
    parts.enableSoftAvoidance();
    parts.advance(1.0);
    const std::uint64_t calls = parts.world().calls;
    parts.dropPrototypes();
    parts.advance(2.0);
    EXPECT_EQ(parts.world().calls, calls + 1);
    expectSceneMatchesLeaves(parts);
}

// Leaf placement (the proxies' and the meshes') is glm's vec3 arithmetic, to the bit: the
// frame upright along the tangent (toward the petiole's side where the tangent stands
// vertical), a lateral leaflet swung across the rachis, then pitch, yaw and roll, the offset
// and the scale. Random angles, tangents near and at vertical, both leaflet sides.
TEST(CollisionRefresh, LeafTransformIsPlainVectorArithmetic) {
    Rng rng(31, 5);
    const vec3 up(0.0f, 0.0f, 1.0f);
    auto bits = [](const mat4& m) {
        std::array<std::uint32_t, 16> b;
        std::memcpy(b.data(), &m[0][0], sizeof b);
        return b;
    };
    auto sc = [](float degrees) {
        const float a = degrees * (3.14159265358979f / 180.0f);
        return SinCos{std::cos(a), std::sin(a)};
    };
    int leaflets = 0, fallbacks = 0;
    for (int i = 0; i < 4000; ++i) {
        vec3 tangent(rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f));
        if (i % 9 == 0) tangent = vec3(0.0f, 0.0f, i % 2 ? 1.0f : -1.0f);  // vertical
        if (i % 9 == 1) tangent = vec3(1e-6f, 0.0f, 1.0f);
        tangent = glm::normalize(tangent);
        const vec3 side =
            glm::normalize(vec3(rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f), 0.1f));
        const vec3 origin(rng.uniform(-2.0f, 2.0f), rng.uniform(-2.0f, 2.0f),
                          rng.uniform(0.0f, 3.0f));
        const vec3 offset(rng.uniform(-0.01f, 0.01f), rng.uniform(-0.01f, 0.01f),
                          rng.uniform(-0.01f, 0.01f));
        const float scale = rng.uniform(0.001f, 0.2f);
        LeafTrig t;
        t.leaflet = int(rng.uniform(0.0f, 3.0f)) - 1;
        t.swing = sc(rng.uniform(0.0f, 90.0f));
        t.turn = {sc(rng.uniform(-90.0f, 90.0f)), sc(rng.uniform(-60.0f, 60.0f)),
                  sc(rng.uniform(-45.0f, 45.0f))};
        const mat4 got = geometry::leafTransform(origin, tangent, side, t, scale, offset);

        vec3 x = glm::normalize(tangent);
        vec3 z = up - glm::dot(up, x) * x;
        if (glm::length(z) < 1e-4f) {
            z = side - glm::dot(side, x) * x;
            ++fallbacks;
        }
        ASSERT_GE(glm::length(z), 1e-6f);
        z = glm::normalize(z);
        vec3 y = glm::cross(z, x);
        if (t.leaflet != 0) {
            x = glm::normalize(t.swing.s * x + t.swing.c * (t.leaflet < 0 ? 1.0f : -1.0f) * y);
            y = glm::cross(z, x);
            ++leaflets;
        }
        const SinCos p = t.turn.pitch, w = t.turn.yaw, r = t.turn.roll;
        const vec3 x1 = p.c * x + p.s * z, z1 = -p.s * x + p.c * z;
        const vec3 x2 = w.c * x1 + w.s * y, y2 = -w.s * x1 + w.c * y;
        const vec3 y3 = r.c * y2 + r.s * z1, z3 = -r.s * y2 + r.c * z1;
        const vec3 o = offset * scale;
        mat4 want(1.0f);
        want[0] = glm::vec4(x2 * scale, 0.0f);
        want[1] = glm::vec4(y3 * scale, 0.0f);
        want[2] = glm::vec4(z3 * scale, 0.0f);
        want[3] = glm::vec4(origin + x2 * o.x + y3 * o.y + z3 * o.z, 1.0f);
        ASSERT_EQ(bits(got), bits(want)) << "case " << i;
    }
    EXPECT_GT(leaflets, 2000);
    EXPECT_GT(fallbacks, 400);
}
