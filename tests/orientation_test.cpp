// Organ orientation as the model's parameter definitions give it, checked on hand-built
// plants by measuring their geometry. Every expected angle is worked by hand from the
// definitions (docs/organs.md, "Orientation of organs"):
// - internode pitch: the angle between successive internodes (a zig-zag); each leans half of
//   it off the shoot axis toward its own petiole;
// - petiole pitch: the angle of the petiole's base from its internode's axis, on the side of
//   the petiole's azimuth, whatever its sign;
// - petiole curvature: degrees per metre of the full-grown petiole, positive curving up toward
//   vertical, negative down; a growing petiole keeps its full-grown bend;
// - leaf roll on lateral leaflets: about the leaflet's midrib, mirrored between the two sides,
//   positive lifting the edge toward the petiole tip.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/math.h"
#include "plantarch/PlantArchitecture.h"

using namespace plantarch;

namespace {

float angleBetween(vec3 a, vec3 b) {
    return degrees(
        std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0f, 1.0f)));
}

const vec3 kUp{0.0f, 0.0f, 1.0f};

// A vertical shoot with alternate leaves and nothing random: straight internodes, simple
// leaves, flat leaf prototypes.
ShootParameters plainShoot() {
    ShootParameters s;
    PhytomerParameters& p = s.phytomer_parameters;
    p.internode.pitch = 0.0f;
    p.internode.phyllotactic_angle = 180.0f;
    p.petiole.pitch = 50.0f;
    p.petiole.length = 0.2f;
    p.petiole.radius = 0.002f;
    p.petiole.taper = 1.0f;
    p.petiole.curvature = 0.0f;
    p.petiole.length_segments = 40;
    p.petiole.radial_subdivisions = 8;
    p.leaf.prototype_scale = 0.05f;
    s.max_nodes = 20;
    return s;
}

struct Plant {
    Context ctx;
    PlantArchitecture arch{&ctx};
    unsigned id = 0;
    unsigned sides = 0;

    // `setup` runs before the shoot type is defined (to register prototype functions).
    explicit Plant(const ShootParameters& p, unsigned nodes = 3, float leafScale = 1.0f,
                   void (*setup)(PlantArchitecture&) = nullptr)
        : sides(p.phytomer_parameters.petiole.radial_subdivisions) {
        if (setup) setup(arch);
        arch.defineShootType("main", p);
        id = arch.addPlantInstance({0, 0, 0}, 10);
        ShootSpec spec;
        spec.phytomers = nodes;
        spec.size.internodeRadius = 0.003f;
        spec.size.internodeLengthMax = 0.04f;
        spec.size.leafScale = leafScale;
        spec.shootType = "main";
        arch.addBaseStemShoot(id, spec);
    }

    const Phytomer& phytomer(unsigned node) const {
        return arch.plant(id).shoots[0].phytomers[node];
    }

    // The centres of a petiole tube's rings, base to tip (each ring is sides + 1 vertices,
    // the seam twice).
    std::vector<vec3> petiolePath(unsigned node) const {
        const auto v = ctx.object(phytomer(node).petioles[0].object);
        std::vector<vec3> centres;
        for (std::size_t r = 0; (r + 1) * (sides + 1) <= v.positions.size(); ++r) {
            vec3 c(0.0f);
            for (unsigned k = 0; k < sides; ++k) c += v.positions[r * (sides + 1) + k];
            centres.push_back(c / float(sides));
        }
        return centres;
    }
    vec3 petioleBase(unsigned node) const {
        const std::vector<vec3> c = petiolePath(node);
        return c[1] - c[0];
    }
    vec3 petioleTip(unsigned node) const {
        const std::vector<vec3> c = petiolePath(node);
        return c[c.size() - 1] - c[c.size() - 2];
    }
    // The axis of internode `node`: from the node below (the plant's base for the first) to
    // its tip.
    vec3 internode(unsigned node) const {
        const vec3 below = node == 0 ? vec3(0.0f) : arch.getNodePosition(id, 0, node - 1);
        return arch.getNodePosition(id, 0, node) - below;
    }

    // The area-weighted mean normal of a leaf's triangles.
    vec3 leafNormal(const LeafOrgan& leaf) const {
        vec3 n(0.0f);
        for (ObjectID o : leaf.objects) {
            const auto v = ctx.object(o);
            for (std::size_t t = 0; t + 2 < v.indices.size(); t += 3) {
                const vec3 a = v.positions[v.indices[t]], b = v.positions[v.indices[t + 1]],
                           c = v.positions[v.indices[t + 2]];
                n += glm::cross(b - a, c - a);
            }
        }
        return glm::normalize(n);
    }
};

// The horizontal part of a direction, unit.
vec3 horizontal(vec3 v) {
    return glm::normalize(vec3(v.x, v.y, 0.0f));
}

}  // namespace

// Alternate leaves, internode pitch 10: successive internodes meet at 10 degrees, each leaning
// 5 degrees off the vertical shoot axis toward its own petiole; that petiole (pitch 50) then
// leaves at 50 + 5 = 55 degrees from vertical.
TEST(Orientation, InternodePitchIsTheAngleBetweenSuccessiveInternodesLeaningToThePetiole) {
    ShootParameters p = plainShoot();
    p.phytomer_parameters.internode.pitch = 10.0f;
    p.phytomer_parameters.petiole.length_segments = 1;
    const Plant f(p, 4);
    for (unsigned k = 0; k < 4; ++k) {
        SCOPED_TRACE("node " + std::to_string(k));
        const vec3 in = f.internode(k), base = f.petioleBase(k);
        EXPECT_NEAR(angleBetween(in, kUp), 5.0f, 0.1f);
        // The lean is toward the petiole's side.
        EXPECT_GT(glm::dot(horizontal(in), horizontal(base)), 0.999f);
        EXPECT_NEAR(angleBetween(base, kUp), 55.0f, 0.1f);
        EXPECT_NEAR(angleBetween(base, in), 50.0f, 0.1f);
        if (k + 1 < 4) {
            EXPECT_NEAR(angleBetween(in, f.internode(k + 1)), 10.0f, 0.1f);
        }
    }
}

// A petiole's pitch is an angle from the internode axis, taken on the side of the petiole's
// own azimuth: pitch -50 and pitch 50 place the same petiole.
TEST(Orientation, PetiolePitchSignDoesNotMoveThePetioleOffItsSide) {
    ShootParameters p = plainShoot();
    p.phytomer_parameters.petiole.length_segments = 1;
    const Plant up(p, 2);
    p.phytomer_parameters.petiole.pitch = -50.0f;
    const Plant down(p, 2);
    for (unsigned k = 0; k < 2; ++k) {
        EXPECT_NEAR(angleBetween(down.petioleBase(k), kUp), 50.0f, 0.1f);
        EXPECT_NEAR(angleBetween(down.petioleBase(k), up.petioleBase(k)), 0.0f, 0.1f);
    }
}

// Pitch 50 and curvature -100 degrees per metre over a 0.2 m petiole: 20 degrees of downward
// bend, so the tip runs at 50 + 20 = 70 degrees from vertical; pitch 80 with +100 bends up to
// 80 - 20 = 60. The path turns half a segment's share before its first and after its last
// segment, so the end segments run a quarter degree inside those (40 segments).
TEST(Orientation, PetioleCurvatureBendsByCurvatureTimesLength) {
    struct Case {
        float pitch, curvature, base, tip;
    };
    for (const Case c : {Case{50, -100, 50.25f, 69.75f}, Case{80, 100, 79.75f, 60.25f}}) {
        SCOPED_TRACE("pitch " + std::to_string(c.pitch));
        ShootParameters p = plainShoot();
        p.phytomer_parameters.petiole.pitch = c.pitch;
        p.phytomer_parameters.petiole.curvature = c.curvature;
        const Plant f(p, 2);
        EXPECT_NEAR(angleBetween(f.petioleBase(0), kUp), c.base, 0.05f);
        EXPECT_NEAR(angleBetween(f.petioleTip(0), kUp), c.tip, 0.05f);
    }
}

// A petiole grown to half its length (leaf scale fraction 0.5, 0.1 m long) already has the
// shape it has full grown: its tip still runs at 70 degrees from vertical.
TEST(Orientation, AGrowingPetioleKeepsItsFullGrownBend) {
    ShootParameters p = plainShoot();
    p.phytomer_parameters.petiole.curvature = -100.0f;
    const Plant half(p, 2, 0.5f);
    const std::vector<vec3> path = half.petiolePath(0);
    EXPECT_NEAR(glm::length(path.back() - path.front()), 0.1f, 0.005f);
    EXPECT_NEAR(angleBetween(half.petioleTip(0), kUp), 69.75f, 0.05f);
}

// A trifoliate leaf on a horizontal petiole (pitch 90, no bend), leaflets unpitched and
// unswung, roll 30: each lateral leaflet turns 30 degrees about its own midrib, lifting its
// edge toward the petiole tip, so its normal leans 30 degrees from vertical back toward the
// petiole's base, on both sides alike. The tip leaflet takes no rotation and stays flat.
TEST(Orientation, LateralLeafletRollLiftsTheEdgeTowardThePetioleTip) {
    for (float roll : {30.0f, -20.0f}) {
        SCOPED_TRACE("roll " + std::to_string(roll));
        ShootParameters p = plainShoot();
        p.phytomer_parameters.petiole.pitch = 90.0f;
        p.phytomer_parameters.leaf.leaves_per_petiole = 3;
        p.phytomer_parameters.leaf.leaflet_offset = 0.3f;
        p.phytomer_parameters.leaf.roll = roll;
        const Plant f(p, 2);
        const Petiole& pt = f.phytomer(0).petioles[0];
        ASSERT_EQ(pt.leaves.size(), 3u);
        const vec3 tipward = horizontal(f.petioleBase(0));
        for (const LeafOrgan& leaf : pt.leaves) {
            SCOPED_TRACE("leaflet " + std::to_string(leaf.leafletIndex));
            const vec3 n = f.leafNormal(leaf);
            ASSERT_GT(n.z, 0.0f);
            const float lean = degrees(std::atan2(-glm::dot(n, tipward), n.z));
            EXPECT_NEAR(lean, leaf.leafletIndex == 0 ? 0.0f : roll, 0.5f);
        }
    }
}

// A peduncle with pitch 40 leaves the vertical internode at 40 degrees on its petiole's side
// (in the petiole's axil). Its roll 90 turns its flower a quarter turn about the peduncle's
// own axis: the flower (pitch 60 from the peduncle) then leans to the peduncle's side,
// square to the vertical plane the peduncle stands in, instead of in that plane.
TEST(Orientation, PeduncleLeavesOnItsPetiolesSideAndItsRollTurnsTheFlowers) {
    for (float roll : {0.0f, 90.0f}) {
        SCOPED_TRACE("roll " + std::to_string(roll));
        ShootParameters p = plainShoot();
        p.phytomer_parameters.petiole.length_segments = 1;
        PeduncleParameters& pd = p.phytomer_parameters.peduncle;
        pd.length = 0.1f;
        pd.pitch = 40.0f;
        pd.roll = roll;
        pd.length_segments = 1;
        pd.radial_subdivisions = 8;
        InflorescenceParameters& inf = p.phytomer_parameters.inflorescence;
        inf.pitch = 60.0f;
        inf.flower_prototype_scale = 0.02f;
        inf.flower_prototype_function = "needle";
        // A flower that is a needle along its own axis, from its base at the origin to x = 1.
        Plant f(p, 2, 1.0f, [](PlantArchitecture& arch) {
            arch.registerFloralPrototype("needle", [](const FloralPrototypeRequest&, Rng&) {
                Mesh m;
                m.positions = {vec3(0.0f), vec3(1.0f, 0.0f, 0.0f), vec3(0.0f, 0.05f, 0.0f)};
                m.indices = {0, 1, 2};
                return OrganPrototype{{m, Material{}}};
            });
        });
        ASSERT_EQ(f.arch.addFloralBud(f.id, 0, 0, FloralStage::FlowerOpen), 1u);
        const FloralBud& fb = f.phytomer(0).petioles[0].floralBuds.back();  // the one added
        const auto tube = f.ctx.object(fb.peduncleObject);
        vec3 first(0.0f), last(0.0f);
        for (unsigned k = 0; k < 8; ++k) {
            first += tube.positions[k];
            last += tube.positions[9 + k];
        }
        const vec3 peduncle = glm::normalize(last - first);
        EXPECT_NEAR(angleBetween(peduncle, kUp), 40.0f, 0.1f);
        EXPECT_GT(glm::dot(horizontal(peduncle), horizontal(f.petioleBase(0))), 0.9999f);
        const auto needle = f.ctx.object(fb.flowers[0].objects[0]);
        const vec3 flower = glm::normalize(needle.positions[1] - needle.positions[0]);
        EXPECT_NEAR(angleBetween(flower, peduncle), 60.0f, 0.1f);
        // Square to the peduncle's vertical plane: how far the flower leans out of it.
        const vec3 across = glm::normalize(glm::cross(kUp, peduncle));
        EXPECT_NEAR(degrees(std::asin(std::abs(glm::dot(flower, across)))),
                    roll == 0.0f ? 0.0f : 60.0f, 0.1f);
    }
}
