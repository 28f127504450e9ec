// Canopy grid: every plant of buildPlantCanopyFromLibrary stands where the documented formula
// puts it (include/plantarch/PlantArchitecture.h, CanopyOptions): position (i, j), i along x
// and j along y, at center + ((i - (nx - 1) / 2) sx, (j - (ny - 1) / 2) sy, 0), numbered row by
// row with i fastest. A non-square grid with unequal spacing, so that x and y, counts and
// spacings cannot be confused without a plant moving.

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

#include "plantarch/PlantArchitecture.h"

using namespace plantarch;

namespace {

constexpr int kNx = 3, kNy = 5;
const vec2 kSpacing{0.4f, 0.25f};
const vec3 kCenter{1.0f, -2.0f, 0.5f};

vec3 gridPoint(int i, int j) {
    return kCenter + vec3((float(i) - 0.5f * float(kNx - 1)) * kSpacing.x,
                          (float(j) - 0.5f * float(kNy - 1)) * kSpacing.y, 0.0f);
}

// The lowest point of the plant's stem geometry.
vec3 stemBottom(const PlantArchitecture& arch, const Context& ctx, unsigned plant) {
    vec3 lowest(0.0f, 0.0f, std::numeric_limits<float>::max());
    for (ObjectID id : arch.getPlantObjectIDs(plant, OrganKind::Internode))
        for (const vec3& v : ctx.object(id).positions)
            if (v.z < lowest.z) lowest = v;
    return lowest;
}

TEST(ConformanceCanopy, GridPlantsStandAtTheFormulaInRowOrder) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    const std::vector<unsigned> ids =
        arch.buildPlantCanopyFromLibrary(kCenter, kSpacing, glm::ivec2(kNx, kNy), 5.0f);
    ASSERT_EQ(ids.size(), std::size_t(kNx * kNy));
    EXPECT_EQ(arch.getAllPlantIDs(), ids);
    for (int k = 0; k < kNx * kNy; ++k) {
        const int i = k % kNx, j = k / kNx;
        SCOPED_TRACE("plant " + std::to_string(k) + " at (" + std::to_string(i) + ", " +
                     std::to_string(j) + ")");
        EXPECT_EQ(ids[std::size_t(k)], ids[0] + unsigned(k));  // numbered in grid order
        const vec3 want = gridPoint(i, j);
        const vec3 base = arch.getPlantBasePosition(ids[std::size_t(k)]);
        EXPECT_NEAR(base.x, want.x, 1e-6f);
        EXPECT_NEAR(base.y, want.y, 1e-6f);
        EXPECT_NEAR(base.z, want.z, 1e-6f);
        // The geometry stands there too: the stem starts at the base (a 5-day bean's stem
        // base is within its 1 cm radius of it).
        const vec3 bottom = stemBottom(arch, ctx, ids[std::size_t(k)]);
        EXPECT_NEAR(bottom.x, want.x, 0.01f);
        EXPECT_NEAR(bottom.y, want.y, 0.01f);
        EXPECT_NEAR(bottom.z, want.z, 0.01f);
    }
}

// With a germination rate the plants that do grow keep their grid places and their order.
TEST(ConformanceCanopy, GerminatedPlantsKeepTheirGridPlacesInOrder) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    CanopyOptions o;
    o.center = kCenter;
    o.spacing = kSpacing;
    o.count = glm::ivec2(kNx, kNy);
    o.germinationRate = 0.5f;
    const std::vector<unsigned> ids = arch.buildPlantCanopyFromLibrary(o, 1.0f);
    ASSERT_GT(ids.size(), 0u);
    ASSERT_LT(ids.size(), std::size_t(kNx * kNy));
    int previous = -1;
    for (unsigned id : ids) {
        const vec3 base = arch.getPlantBasePosition(id);
        int found = -1;
        for (int k = 0; k < kNx * kNy; ++k)
            if (glm::length(base - gridPoint(k % kNx, k / kNx)) < 1e-6f) found = k;
        ASSERT_GE(found, 0) << "plant " << id << " is not on a grid point";
        EXPECT_GT(found, previous) << "plant " << id << " out of grid order";
        previous = found;
    }
}

}  // namespace
