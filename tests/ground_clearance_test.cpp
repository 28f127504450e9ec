// Ground clearance (docs/growth.md): no leaf, flower or fruit of a plant goes below its ground
// level, the z of its base.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "plantarch/PlantArchitecture.h"
#include "plantarch/SpeciesIO.h"

using namespace plantarch;

namespace {

constexpr float kInf = std::numeric_limits<float>::max();

// The lowest vertex of the plant's organs of these kinds, m (kInf when it has none).
float lowest(const PlantArchitecture& arch, const Context& ctx, unsigned plant,
             std::initializer_list<OrganKind> kinds) {
    float z = kInf;
    for (OrganKind kind : kinds)
        for (ObjectID id : arch.getPlantObjectIDs(plant, kind))
            for (const vec3& q : ctx.object(id).positions) z = std::min(z, q.z);
    return z;
}

constexpr std::initializer_list<OrganKind> kSideOrgans = {OrganKind::Leaf, OrganKind::FlowerClosed,
                                                          OrganKind::FlowerOpen, OrganKind::Fruit};

}  // namespace

// Every library species at its picture age, seeds 1 to 3: no leaf, flower or fruit vertex more
// than 1 mm below the plant's base.
TEST(GroundClearance, EveryLibraryPlantKeepsItsLeavesFlowersAndFruitAboveTheGround) {
    std::string table = "\nspecies              age seed  side organs  petioles  internodes (mm)";
    std::size_t below = 0;
    for (const std::string& name : listSpecies()) {
        const float age = loadSpecies(name).recommendedAge;
        for (std::uint64_t seed = 1; seed <= 3; ++seed) {
            SCOPED_TRACE(name + " seed " + std::to_string(seed));
            Context ctx;
            PlantArchitecture arch(&ctx);
            arch.setSeed(seed);
            arch.loadPlantModelFromLibrary(name);
            const unsigned p = arch.buildPlantInstanceFromLibrary(vec3(0.0f), age);
            const float side = lowest(arch, ctx, p, kSideOrgans);
            const float petioles = lowest(arch, ctx, p, {OrganKind::Petiole, OrganKind::Peduncle});
            const float stems = lowest(arch, ctx, p, {OrganKind::Internode});
            char row[160];
            std::snprintf(row, sizeof row, "\n%-18s %6.0f %4d %11.1f %9.1f %11.1f", name.c_str(),
                          double(age), int(seed), double(side) * 1e3, double(petioles) * 1e3,
                          double(stems) * 1e3);
            table += row;
            EXPECT_GE(side, -1e-3f);
            below += side < -1e-3f ? 1 : 0;
        }
    }
    std::printf("%s\n%zu plants with a side organ below the ground\n", table.c_str(), below);
}
