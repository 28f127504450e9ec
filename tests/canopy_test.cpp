// Canopies: grid and scattered layouts, germination, and the same bytes for any thread count.

#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <functional>
#include <set>
#include <utility>

#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/PlantArchitecture.h"

using namespace plantarch;

namespace {

Error errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e;
    }
    ADD_FAILURE() << "expected a plantarch::Error";
    return Error("none");
}

// Every object's ID, labels and vertex bytes, in ID order.
std::string fingerprint(const Context& ctx) {
    std::string out;
    ctx.forEachObject([&](const ObjectView& v) {
        out += std::to_string(v.id) + ":" + std::to_string(*ctx.objectDataInt(v.id, "plantID")) +
               *ctx.objectDataString(v.id, "organ") + ";";
        out.append(reinterpret_cast<const char*>(v.positions.data()),
                   v.positions.size() * sizeof(vec3));
    });
    return out;
}

std::string canopy(int threads) {
    const int before = omp_get_max_threads();
    omp_set_num_threads(threads);
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.setSeed(5);
    arch.loadPlantModelFromLibrary("bean");
    arch.buildPlantCanopyFromLibrary({0, 0, 0}, {0.3f, 0.3f}, {3, 3}, 30.0f);
    omp_set_num_threads(before);
    return fingerprint(ctx);
}

}  // namespace

TEST(Canopy, GridPositionsAndPlantIDs) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    const auto ids = arch.buildPlantCanopyFromLibrary({1, 2, 0}, {0.5f, 0.25f}, {3, 2}, 10.0f);
    ASSERT_EQ(ids.size(), 6u);
    EXPECT_EQ(ids, (std::vector<unsigned>{0, 1, 2, 3, 4, 5}));
    EXPECT_EQ(arch.getPlantBasePosition(0), vec3(0.5f, 1.875f, 0.0f));
    EXPECT_EQ(arch.getPlantBasePosition(5), vec3(1.5f, 2.125f, 0.0f));
    for (unsigned id : ids) {
        EXPECT_GT(arch.getPlantLeafCount(id), 0u);
        for (ObjectID o : arch.getAllPlantObjectIDs(id))
            EXPECT_EQ(ctx.objectDataInt(o, "plantID"), int(id));
    }
    // Every object in the Context belongs to exactly one plant's organs.
    EXPECT_EQ(arch.getAllObjectIDs().size(), ctx.objectCount());
    // Plants differ from one another (own random streams) ...
    EXPECT_NE(arch.getPlantLeafArea(0), arch.getPlantLeafArea(1));
    // ... and a canopy plant is the plant built alone with the same ID and seed.
    Context alone;
    PlantArchitecture single(&alone);
    single.loadPlantModelFromLibrary("bean");
    const unsigned p = single.buildPlantInstanceFromLibrary(arch.getPlantBasePosition(0), 10.0f);
    EXPECT_FLOAT_EQ(single.getPlantLeafArea(p), arch.getPlantLeafArea(0));
}

TEST(Canopy, SameBytesWithOneAndTwoThreads) {
    const std::string one = canopy(1);
    const std::string two = canopy(2);
    EXPECT_GT(one.size(), 100000u);
    EXPECT_EQ(one, two);
}

TEST(Canopy, GerminationRate) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    const int n = 30 * 30;
    const auto ids =
        arch.buildPlantCanopyFromLibrary({0, 0, 0}, {0.1f, 0.1f}, {30, 30}, 0.0f, 0.7f);
    EXPECT_NEAR(double(ids.size()), 0.7 * n, 5.0 * std::sqrt(n * 0.7 * 0.3));
    EXPECT_TRUE(
        arch.buildPlantCanopyFromLibrary({5, 0, 0}, {0.1f, 0.1f}, {4, 4}, 0.0f, 0.0f).empty());
}

TEST(Canopy, ScatteredPlantsStayInTheirRectangle) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    CanopyOptions o;
    o.layout = CanopyOptions::Layout::Scatter;
    o.center = {10, -4, 0};
    o.extent = {2.0f, 1.0f};
    o.plants = 25;
    const auto ids = arch.buildPlantCanopyFromLibrary(o, 5.0f);
    ASSERT_EQ(ids.size(), 25u);
    std::set<std::pair<float, float>> distinct;
    for (unsigned id : ids) {
        const vec3 b = arch.getPlantBasePosition(id);
        EXPECT_LE(std::abs(b.x - 10.0f), 1.0f);
        EXPECT_LE(std::abs(b.y + 4.0f), 0.5f);
        distinct.insert({b.x, b.y});
    }
    EXPECT_EQ(distinct.size(), 25u);
    o.plants = 0;
    EXPECT_EQ(errorOf([&] { arch.buildPlantCanopyFromLibrary(o, 5.0f); }).parameter(),
              "plant_count");
    o.plants = 4;
    o.extent = {-1.0f, 1.0f};
    EXPECT_EQ(errorOf([&] { arch.buildPlantCanopyFromLibrary(o, 5.0f); }).parameter(),
              "canopy_extent");
    EXPECT_EQ(arch.getAllPlantIDs().size(), 25u);  // failed calls add nothing
}

TEST(Canopy, GridOptionsAreTheSpecificationsForm) {
    // The positional form is CanopyOptions' grid: the same positions, plants and geometry.
    auto build = [](bool options, std::size_t& plants) {
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.setSeed(5);
        arch.loadPlantModelFromLibrary("bean");
        if (options) {
            CanopyOptions o;
            o.center = {1, 2, 0};
            o.spacing = {0.5f, 0.25f};
            o.count = {3, 2};
            o.germinationRate = 0.6f;
            plants = arch.buildPlantCanopyFromLibrary(o, 12.0f).size();
        } else {
            plants = arch.buildPlantCanopyFromLibrary({1, 2, 0}, {0.5f, 0.25f}, {3, 2}, 12.0f, 0.6f)
                         .size();
        }
        return fingerprint(ctx);
    };
    std::size_t gridPlants = 0, specPlants = 0;
    const std::string grid = build(true, gridPlants);
    EXPECT_EQ(build(false, specPlants), grid);
    EXPECT_EQ(gridPlants, specPlants);
    EXPECT_GT(gridPlants, 0u);
    EXPECT_LT(gridPlants, 6u);  // some positions did not germinate
}

TEST(Canopy, BadArgumentsAreErrors) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    EXPECT_THROW(arch.buildPlantCanopyFromLibrary({0, 0, 0}, {0.3f, 0.3f}, {2, 2}, 10.0f), Error);
    arch.loadPlantModelFromLibrary("bean");
    EXPECT_THROW(arch.buildPlantCanopyFromLibrary({0, 0, 0}, {0.3f, 0.3f}, {2, 2}, 10.0f, 1.5f),
                 Error);
    EXPECT_THROW(arch.buildPlantCanopyFromLibrary({0, 0, 0}, {0.3f, 0.3f}, {0, 2}, 10.0f), Error);
    EXPECT_THROW(arch.buildPlantCanopyFromLibrary({0, 0, 0}, {-0.3f, 0.3f}, {2, 2}, 10.0f), Error);
    EXPECT_THROW(arch.buildPlantCanopyFromLibrary({0, 0, 0}, {0.3f, 0.3f}, {2, 2}, -1.0f), Error);
    EXPECT_THROW(arch.buildPlantCanopyFromLibrary({0, 0, 0}, {0.3f, 0.3f}, {2, 2}, 10.0f, 1.0f,
                                                  {{"no_such_parameter", 1.0f}}),
                 Error);
    EXPECT_EQ(ctx.objectCount(), 0u);  // nothing half-built
}
