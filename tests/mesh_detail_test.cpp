// setMeshDetail and --mesh-detail: a factor on every organ's mesh resolution that changes the
// geometry and nothing else.

#include <gtest/gtest.h>

#include <string>

#include "cli_run.h"
#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"

using namespace plantarch;

namespace {

struct Built {
    std::size_t triangles = 0;
    std::string exact;  // the plant string with every value exact: the plant's state
    float leafArea = 0.0f;
};

Built build(const std::string& species, float age, float detail) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.setMeshDetail(detail);
    arch.loadPlantModelFromLibrary(species);
    const unsigned p = arch.buildPlantInstanceFromLibrary(vec3(0.0f), age);
    return {ctx.triangleCount(), arch.getPlantString(p, {.significantDigits = 0}),
            arch.getPlantLeafArea(p)};
}

}  // namespace

TEST(MeshDetail, CoarserAndFinerMeshesOfTheSamePlant) {
    for (const char* species : {"bean", "bindweed", "almond"}) {
        SCOPED_TRACE(species);
        const float age = std::string(species) == "almond" ? 400.0f : 45.0f;
        const Built normal = build(species, age, 1.0f);
        const Built coarse = build(species, age, 0.5f);
        const Built fine = build(species, age, 2.0f);
        EXPECT_LT(coarse.triangles, normal.triangles * 9 / 10);
        EXPECT_GT(fine.triangles, normal.triangles * 11 / 10);
        // The plants themselves are the same to the bit.
        EXPECT_EQ(coarse.exact, normal.exact);
        EXPECT_EQ(fine.exact, normal.exact);
        EXPECT_NEAR(coarse.leafArea, normal.leafArea, 0.03f * normal.leafArea);
    }
}

TEST(MeshDetail, SettingItRedrawsThePlantsThereAre) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    arch.buildPlantInstanceFromLibrary(vec3(0.0f), 40.0f);
    const std::size_t before = ctx.triangleCount();
    EXPECT_EQ(arch.getMeshDetail(), 1.0f);
    arch.setMeshDetail(0.5f);
    EXPECT_EQ(arch.getMeshDetail(), 0.5f);
    EXPECT_EQ(ctx.triangleCount(), build("bean", 40.0f, 0.5f).triangles);
    EXPECT_LT(ctx.triangleCount(), before);
    arch.setMeshDetail(1.0f);
    EXPECT_EQ(ctx.triangleCount(), before);
}

TEST(MeshDetail, OutOfRangeIsOneError) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    for (float bad : {0.0f, 0.05f, 4.5f, -1.0f}) {
        try {
            arch.setMeshDetail(bad);
            ADD_FAILURE() << bad << " was accepted";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("mesh_detail"), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("0.1 to 4"), std::string::npos) << e.what();
        }
    }
    EXPECT_EQ(arch.getMeshDetail(), 1.0f);
}

TEST(MeshDetail, CommandLineOption) {
    const cli::Result normal = cli::run("build bindweed --age 40 --stats");
    const cli::Result coarse = cli::run("build bindweed --age 40 --stats --mesh-detail 0.4");
    ASSERT_EQ(normal.status, 0) << normal.out;
    ASSERT_EQ(coarse.status, 0) << coarse.out;
    const auto triangles = [](const std::string& json) {
        const std::size_t at = json.find("\"triangles\": ");
        return at == std::string::npos ? 0L : std::stol(json.substr(at + 13));
    };
    EXPECT_GT(triangles(normal.out), 0);
    EXPECT_LT(triangles(coarse.out), triangles(normal.out) * 8 / 10);
    const cli::Result bad = cli::run("build bean --mesh-detail 5");
    EXPECT_EQ(bad.status, 2);
    EXPECT_EQ(bad.out, "plantarch: --mesh-detail = 5: not a mesh detail (valid: 0.1 to 4)\n");
}

// The lowest detail (0.1) draws plants with a tenth of the triangles or fewer (leaves,
// flowers and fruit thinned to about 1/25 of theirs, tubes to 3 sides and fewer segments),
// with the same plant state, and no state depends on it.
TEST(MeshDetail, LowestDetailIsATenthOfTheTriangles) {
    for (const char* species : {"tomato", "bean", "soybean", "maize", "cowpea", "strawberry"}) {
        SCOPED_TRACE(species);
        const Built normal = build(species, 60.0f, 1.0f);
        const Built lowest = build(species, 60.0f, 0.1f);
        EXPECT_LE(lowest.triangles * 10, normal.triangles)
            << lowest.triangles << " of " << normal.triangles;
        EXPECT_GT(lowest.triangles, 0u);
        EXPECT_EQ(lowest.exact, normal.exact);
        // Coarse blades are smaller, but still leaves of about their size.
        EXPECT_GT(lowest.leafArea, 0.5f * normal.leafArea);
    }
}

// Every step down draws fewer triangles (or as many), down to the lowest.
TEST(MeshDetail, TrianglesFallWithTheDetail) {
    std::size_t above = build("tomato", 90.0f, 1.0f).triangles;
    for (float detail : {0.75f, 0.5f, 0.4f, 0.25f, 0.15f, 0.1f}) {
        SCOPED_TRACE(detail);
        const std::size_t n = build("tomato", 90.0f, detail).triangles;
        EXPECT_LE(n, above);
        above = n;
    }
}
