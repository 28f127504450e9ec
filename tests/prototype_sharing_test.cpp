// Building plant after plant: organ shapes made by the library's own prototype functions are
// shared by every PlantArchitecture of the process, shapes of functions a user registers are
// not, and the Context's freed pool blocks are kept for the next Context.

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "core/pool_allocator.h"
#include "plantarch/PlantArchitecture.h"

using namespace plantarch;

namespace {

struct Built {
    std::vector<vec3> positions;
    std::vector<std::uint32_t> indices;
    std::size_t leafTriangles = 0;
    std::size_t leaves = 0;
};

// A bean at 30 days; `custom` replaces the library's leaf function by one of the user's.
Built buildBean(bool custom) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    if (custom)
        arch.registerLeafPrototype("procedural", [](const LeafPrototype&, Rng&, int) {
            Mesh m;
            m.positions = {{0, 0, 0}, {1, 0, 0}, {0.5f, 0.2f, 0}};
            m.indices = {0, 1, 2};
            return OrganPrototype{{m, Material{vec3(0.1f, 0.5f, 0.1f), "", "leaf"}}};
        });
    arch.loadPlantModelFromLibrary("bean");
    const unsigned p = arch.buildPlantInstanceFromLibrary(vec3(0.0f), 30.0f);
    Built b;
    for (ObjectID id : ctx.objectIDs()) {
        const auto& o = ctx.object(id);
        b.positions.insert(b.positions.end(), o.positions.begin(), o.positions.end());
        b.indices.insert(b.indices.end(), o.indices.begin(), o.indices.end());
    }
    for (ObjectID id : arch.getAllPlantObjectIDs(p))
        if (ctx.objectDataString(id, "organ") == std::string("leaf"))
            b.leafTriangles += ctx.object(id).indices.size() / 3;
    b.leaves = arch.getPlantLeafCount(p);
    return b;
}

}  // namespace

TEST(PrototypeSharing, UserLeafFunctionsStayWithTheirPlantArchitecture) {
    const Built first = buildBean(false);
    const Built custom = buildBean(true);
    const Built again = buildBean(false);
    ASSERT_GT(first.leaves, 10u);
    // The user's one-triangle leaf in the PlantArchitecture that registered it...
    EXPECT_EQ(custom.leafTriangles, custom.leaves);
    EXPECT_GT(first.leafTriangles, 10 * first.leaves);
    // ...and the library's leaves, to the bit, in the ones before and after it.
    EXPECT_EQ(first.positions, again.positions);
    EXPECT_EQ(first.indices, again.indices);
}

TEST(PoolRecycling, FreedBlocksAreReusedAndCanBeReleased) {
    core::releaseRecycledPools();
    EXPECT_EQ(core::recycledPoolBytes(), 0u);
    const std::size_t bytes = 3 * core::kRecycledBlock + 7;
    void* a = core::allocatePool(bytes);
    core::freePool(a, bytes);
    const std::size_t kept = core::recycledPoolBytes();
    EXPECT_GE(kept, bytes);
    // A request of the same size class gets the same block back.
    void* b = core::allocatePool(bytes - 100);
    EXPECT_EQ(a, b);
    EXPECT_EQ(core::recycledPoolBytes(), 0u);
    core::freePool(b, bytes - 100);
    // Small blocks go straight back to malloc.
    void* small = core::allocatePool(100);
    core::freePool(small, 100);
    EXPECT_EQ(core::recycledPoolBytes(), kept);
    core::releaseRecycledPools();
    EXPECT_EQ(core::recycledPoolBytes(), 0u);
}

TEST(PoolRecycling, AContextBuiltAfterAnotherIsTheSame) {
    Context a;
    {
        PlantArchitecture arch(&a);
        arch.loadPlantModelFromLibrary("bean");
        arch.buildPlantInstanceFromLibrary(vec3(0.0f), 40.0f);
    }
    // The second Context's pools come from the blocks the first ones left.
    std::vector<vec3> before;
    for (ObjectID id : a.objectIDs())
        for (const vec3& v : a.object(id).positions) before.push_back(v);
    {
        Context scratch;
        PlantArchitecture arch(&scratch);
        arch.loadPlantModelFromLibrary("bean");
        arch.buildPlantInstanceFromLibrary(vec3(0.0f), 40.0f);
    }
    Context b;
    PlantArchitecture arch(&b);
    arch.loadPlantModelFromLibrary("bean");
    arch.buildPlantInstanceFromLibrary(vec3(0.0f), 40.0f);
    std::vector<vec3> after;
    for (ObjectID id : b.objectIDs())
        for (const vec3& v : b.object(id).positions) after.push_back(v);
    EXPECT_EQ(before, after);
}
