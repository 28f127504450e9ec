// The triangle limit: jobs too large for the machine are refused (a canopy, from an estimate
// made before it is grown) or stopped as they pass it (a plant growing, geometry added), with
// TriangleBudgetError naming the estimate and the limit, and the scene left as it was.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "cli_run.h"
#include "plantarch/Context.h"
#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"

using namespace plantarch;

namespace {

Mesh quad() {
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    m.indices = {0, 1, 2, 0, 2, 3};
    return m;
}

template <class Fn>
TriangleBudgetError budgetErrorOf(Fn&& fn) {
    try {
        fn();
    } catch (const TriangleBudgetError& e) {
        return e;
    } catch (const std::exception& e) {
        ADD_FAILURE() << "another exception: " << e.what();
    }
    ADD_FAILURE() << "no TriangleBudgetError was thrown";
    return TriangleBudgetError("none", 0, 0);
}

}  // namespace

TEST(TriangleLimit, ContextRefusesGeometryPastTheLimit) {
    Context ctx;
    ctx.setTriangleLimit(5);
    const ObjectID a = ctx.addObject(quad());
    ctx.addObject(quad());
    EXPECT_EQ(ctx.triangleCount(), 4u);
    const TriangleBudgetError e = budgetErrorOf([&] { ctx.addObject(quad()); });
    EXPECT_EQ(e.estimate(), 6u);
    EXPECT_EQ(e.limit(), 5u);
    EXPECT_NE(std::string(e.what()).find("over the triangle limit of 5"), std::string::npos)
        << e.what();
    EXPECT_EQ(ctx.triangleCount(), 4u);  // nothing added
    EXPECT_EQ(ctx.objectCount(), 2u);
    Mesh big = quad();
    big.indices.insert(big.indices.end(), {0, 1, 3, 1, 2, 3});
    EXPECT_THROW(ctx.setObjectMesh(a, big), TriangleBudgetError);
    EXPECT_EQ(ctx.objectPrimitives(a).count, 2u);
    Context other;
    const std::vector<ObjectID> objects{other.addObject(big)};
    const ObjectSource source{&other, objects};
    EXPECT_THROW(ctx.appendObjects({&source, 1}), TriangleBudgetError);
    EXPECT_EQ(ctx.triangleCount(), 4u);
    ctx.setTriangleLimit(0);  // no limit
    EXPECT_NO_THROW(ctx.appendObjects({&source, 1}));
    EXPECT_EQ(ctx.triangleCount(), 8u);
}

TEST(TriangleLimit, APlantPastTheLimitStopsAndLeavesNothing) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    arch.setTriangleLimit(5000);
    EXPECT_EQ(ctx.triangleLimit(), 5000u);
    const TriangleBudgetError e =
        budgetErrorOf([&] { arch.buildPlantInstanceFromLibrary(vec3(0.0f), 40.0f); });
    EXPECT_GT(e.estimate(), 5000u);
    EXPECT_EQ(e.limit(), 5000u);
    EXPECT_EQ(ctx.triangleCount(), 0u);
    EXPECT_TRUE(arch.getAllPlantIDs().empty());
}

// The growth check counts the fewest triangles a plant's organs can take: a plant with
// exactly its own triangles as the limit grows whole, and one triangle less stops it.
TEST(TriangleLimit, APlantWithinTheLimitIsNeverStopped) {
    for (const char* species : {"bean", "maize", "strawberry", "almond"}) {
        SCOPED_TRACE(species);
        std::size_t triangles = 0;
        {
            Context ctx;
            PlantArchitecture arch(&ctx);
            arch.setTrellisGeometry(false);
            arch.loadPlantModelFromLibrary(species);
            arch.buildPlantInstanceFromLibrary(vec3(0.0f), 60.0f);
            triangles = ctx.triangleCount();
        }
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.setTrellisGeometry(false);
        arch.loadPlantModelFromLibrary(species);
        arch.setTriangleLimit(triangles);
        EXPECT_NO_THROW(arch.buildPlantInstanceFromLibrary(vec3(0.0f), 60.0f));
        EXPECT_EQ(ctx.triangleCount(), triangles);
        Context tight;
        PlantArchitecture again(&tight);
        again.setTrellisGeometry(false);
        again.loadPlantModelFromLibrary(species);
        again.setTriangleLimit(triangles - 1);
        EXPECT_THROW(again.buildPlantInstanceFromLibrary(vec3(0.0f), 60.0f), TriangleBudgetError);
        EXPECT_EQ(tight.triangleCount(), 0u);
    }
}

TEST(TriangleLimit, AHugeCanopyIsRefusedFromItsEstimate) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    arch.setTriangleLimit(100000000);
    const TriangleBudgetError e = budgetErrorOf([&] {
        arch.buildPlantCanopyFromLibrary(vec3(0.0f), vec2(0.3f), glm::ivec2(1000, 1000), 40.0f);
    });
    // A bean of 40 days has some 30,000-40,000 triangles: a million need about 3e10.
    EXPECT_GT(e.estimate(), 20000000000u);
    EXPECT_LT(e.estimate(), 50000000000u);
    EXPECT_EQ(e.limit(), 100000000u);
    const std::string what = e.what();
    EXPECT_NE(what.find("a canopy of 1000000 plants needs about"), std::string::npos) << what;
    EXPECT_NE(what.find("over the triangle limit of 100000000"), std::string::npos) << what;
    EXPECT_EQ(ctx.triangleCount(), 0u);
    EXPECT_TRUE(arch.getAllPlantIDs().empty());
    // The same canopy with soft collision avoidance (plants grown together) is refused too,
    // from one plant grown alone.
    arch.enableSoftCollisionAvoidance();
    const TriangleBudgetError soft = budgetErrorOf([&] {
        arch.buildPlantCanopyFromLibrary(vec3(0.0f), vec2(0.3f), glm::ivec2(1000, 1000), 40.0f);
    });
    EXPECT_GT(soft.estimate(), 20000000000u);
    EXPECT_NE(std::string(soft.what()).find("the mean of its first 1 plant"), std::string::npos)
        << soft.what();
    EXPECT_TRUE(arch.getAllPlantIDs().empty());
}

TEST(TriangleLimit, ACanopyWithinTheLimitIsTheSameAsWithout) {
    std::size_t free = 0;
    {
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.loadPlantModelFromLibrary("bean");
        arch.buildPlantCanopyFromLibrary(vec3(0.0f), vec2(0.3f), glm::ivec2(3, 3), 30.0f);
        free = ctx.triangleCount();
    }
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    // The estimate is the first plants' mean times nine: a margin for plants that differ.
    arch.setTriangleLimit(free * 3 / 2);
    arch.buildPlantCanopyFromLibrary(vec3(0.0f), vec2(0.3f), glm::ivec2(3, 3), 30.0f);
    EXPECT_EQ(ctx.triangleCount(), free);
    // A limit the canopy passes only in its later plants: stopped, nothing left behind.
    Context tight;
    PlantArchitecture again(&tight);
    again.loadPlantModelFromLibrary("bean");
    again.setTriangleLimit(free - 1);
    EXPECT_THROW(again.buildPlantCanopyFromLibrary(vec3(0.0f), vec2(0.3f), glm::ivec2(3, 3), 30.0f),
                 TriangleBudgetError);
    EXPECT_EQ(tight.triangleCount(), 0u);
    EXPECT_TRUE(again.getAllPlantIDs().empty());
}

TEST(TriangleLimit, CliRefusesAHugeCanopyWithOneLine) {
    const cli::Result r =
        cli::run("--max-triangles 100000000 canopy bean --count 1000x1000 --age 40 -o never.obj");
    EXPECT_EQ(r.status, 2) << r.out;
    EXPECT_NE(r.out.find("plantarch: a canopy of 1000000 plants needs about "), std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("over the triangle limit of 100000000 (--max-triangles)"),
              std::string::npos)
        << r.out;
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
}

TEST(TriangleLimit, CliDefaultLimitRefusesTheMillionBeanCanopy) {
    // The default limit (half the memory at 100 bytes a triangle) is below 3e10 triangles on
    // any machine with less than 6 TB of memory.
    const cli::Result r = cli::run("canopy bean --count 1000x1000 --age 40 -o never.obj");
    EXPECT_EQ(r.status, 2) << r.out;
    EXPECT_NE(r.out.find("over the triangle limit of"), std::string::npos) << r.out;
}

TEST(TriangleLimit, CliTinyLimitStopsANormalBuild) {
    const cli::Result r = cli::run("build bean --age 30 --max-triangles 1000 -o never.obj");
    EXPECT_EQ(r.status, 2) << r.out;
    EXPECT_NE(r.out.find("over the triangle limit of 1000 (--max-triangles)"), std::string::npos)
        << r.out;
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
    const cli::Result bad = cli::run("build bean --age 30 --max-triangles -5 --stats");
    EXPECT_EQ(bad.status, 2);
    EXPECT_NE(bad.out.find("--max-triangles = -5: not a triangle count (valid: 0 to 4294967295, "
                           "0 for no limit)"),
              std::string::npos)
        << bad.out;
    const cli::Result none = cli::run("build bean --age 30 --max-triangles 0 --stats");
    EXPECT_EQ(none.status, 0) << none.out;
}
