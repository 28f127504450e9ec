// Labelled point clouds: points lie on their objects, spread by area, carry their labels, are
// the same for a seed, and are written as a PLY of vertices.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "plantarch/Context.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/PlantArchitecture.h"

using namespace plantarch;

namespace {

struct Bean {
    Context ctx;
    PlantArchitecture arch{&ctx};
    Bean() {
        arch.loadPlantModelFromLibrary("bean");
        arch.buildPlantInstanceFromLibrary(vec3(0.0f), 35);
    }
};

}  // namespace

TEST(PointCloud, PointsLieOnTheirObjectsWithTheirLabelsSpreadByArea) {
    Bean b;
    const PointCloud cloud = samplePoints(b.ctx, {.points = 40000, .seed = 3});
    ASSERT_EQ(cloud.positions.size(), 40000u);
    std::map<std::string, std::size_t> perOrgan;
    for (std::size_t i = 0; i < cloud.positions.size(); ++i) {
        const ObjectID id = cloud.objectID[i];
        ASSERT_TRUE(b.ctx.doesObjectExist(id));
        const AABB box = b.ctx.objectBoundingBox(id);
        const vec3 p = cloud.positions[i];
        for (int k = 0; k < 3; ++k) {
            EXPECT_GE(p[k], box.min[k] - 1e-5f);
            EXPECT_LE(p[k], box.max[k] + 1e-5f);
        }
        EXPECT_NEAR(glm::length(cloud.normals[i]), 1.0f, 1e-4f);
        EXPECT_EQ(cloud.plantID[i], b.ctx.objectDataInt(id, "plantID").value());
        const std::string organ(kOrganLabels[cloud.organ[i]]);
        EXPECT_EQ(organ, b.ctx.objectDataString(id, "organ").value());
        ++perOrgan[organ];
    }
    // The share of points on leaves is the leaves' share of the area (within 2 %).
    double leaf = 0.0, total = 0.0;
    for (ObjectID id : b.ctx.objectIDs()) {
        total += b.ctx.objectArea(id);
        if (b.ctx.objectDataString(id, "organ") == "leaf") leaf += b.ctx.objectArea(id);
    }
    EXPECT_NEAR(double(perOrgan["leaf"]) / 40000.0, leaf / total, 0.02);
    EXPECT_GT(perOrgan["internode"], 0u);
}

TEST(PointCloud, SameSeedSamePointsAnotherSeedOthers) {
    Bean b;
    const PointCloud a = samplePoints(b.ctx, {.points = 1000, .seed = 9});
    const PointCloud c = samplePoints(b.ctx, {.points = 1000, .seed = 9});
    const PointCloud d = samplePoints(b.ctx, {.points = 1000, .seed = 10});
    EXPECT_EQ(0, std::memcmp(a.positions.data(), c.positions.data(), 1000 * sizeof(vec3)));
    EXPECT_NE(0, std::memcmp(a.positions.data(), d.positions.data(), 1000 * sizeof(vec3)));
    EXPECT_EQ(a.objectID, c.objectID);
}

TEST(PointCloud, PlyOfVerticesWithLabels) {
    Bean b;
    const PointCloud cloud = samplePoints(b.ctx, {.points = 500, .seed = 1});
    const std::string path = (std::filesystem::temp_directory_path() /
                              ("plantarch_points_" + std::to_string(::getpid()) + ".ply"))
                                 .string();
    writePointCloudPLY(cloud, path);
    std::ifstream in(path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::filesystem::remove(path);
    const std::size_t end = bytes.find("end_header\n");
    ASSERT_NE(end, std::string::npos);
    const std::string header = bytes.substr(0, end);
    EXPECT_NE(header.find("element vertex 500\n"), std::string::npos);
    EXPECT_EQ(header.find("element face"), std::string::npos);
    EXPECT_NE(header.find("property uchar organ"), std::string::npos);
    EXPECT_NE(header.find("comment organ_label 3 leaf"), std::string::npos);
    const std::size_t body = end + std::strlen("end_header\n");
    EXPECT_NE(header.find("property int leaf_id\nproperty int shoot_id\nproperty int rank\n"
                          "property float age\n"),
              std::string::npos);
    ASSERT_EQ(bytes.size() - body, 500u * 49u);
    for (std::size_t i = 0; i < 500; ++i) {
        float x, age;
        std::uint32_t object;
        std::int32_t leaf, rank;
        const char* at = bytes.data() + body + 49 * i;
        std::memcpy(&x, at, 4);
        std::memcpy(&object, at + 28, 4);
        std::memcpy(&leaf, at + 33, 4);
        std::memcpy(&rank, at + 41, 4);
        std::memcpy(&age, at + 45, 4);
        EXPECT_EQ(x, cloud.positions[i].x);
        EXPECT_EQ(object, cloud.objectID[i]);
        EXPECT_EQ(std::uint8_t(at[32]), cloud.organ[i]);
        // The labels are the object's own.
        EXPECT_EQ(leaf, b.ctx.objectDataInt(object, "leafID").value_or(-1));
        EXPECT_EQ(rank, b.ctx.objectDataInt(object, "rank").value_or(-1));
        EXPECT_EQ(age, b.ctx.objectDataFloat(object, "age").value_or(-1.0f));
    }
}

TEST(PointCloud, BadCountsAndEmptyScenesAreErrors) {
    Context empty;
    EXPECT_THROW(samplePoints(empty, {.points = 10}), Error);
    Bean b;
    try {
        samplePoints(b.ctx, {.points = 0});
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("valid: 1 to 2147483648"), std::string::npos);
    }
}
