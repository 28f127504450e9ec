#include "plantarch/Context.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <limits>

#include "plantarch/Error.h"

using namespace plantarch;

namespace {

// A unit quad in the xy plane made of two triangles, optionally with UVs.
Mesh quad(float size = 1.0f, bool withUVs = false) {
    Mesh m;
    m.positions = {{0, 0, 0}, {size, 0, 0}, {size, size, 0}, {0, size, 0}};
    m.indices = {0, 1, 2, 0, 2, 3};
    if (withUVs) m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    return m;
}

// A grid of nx*ny quads (2*nx*ny triangles).
Mesh grid(int nx, int ny) {
    Mesh m;
    for (int j = 0; j <= ny; ++j)
        for (int i = 0; i <= nx; ++i) m.positions.push_back({float(i), float(j), 0.0f});
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            std::uint32_t a = j * (nx + 1) + i, b = a + 1, c = a + nx + 1, d = c + 1;
            m.indices.insert(m.indices.end(), {a, b, d, a, d, c});
        }
    return m;
}

}  // namespace

TEST(Context, AddObjectAssignsSequentialIDsAndPrimitiveRuns) {
    Context ctx;
    ObjectID a = ctx.addObject(quad());
    ObjectID b = ctx.addObject(grid(3, 2));
    EXPECT_EQ(a, 0u);
    EXPECT_EQ(b, 1u);
    EXPECT_EQ(ctx.objectCount(), 2u);
    EXPECT_EQ(ctx.triangleCount(), 2u + 12u);
    EXPECT_EQ(ctx.objectPrimitives(a).first, 0u);
    EXPECT_EQ(ctx.objectPrimitives(a).count, 2u);
    EXPECT_EQ(ctx.objectPrimitives(b).first, 2u);
    EXPECT_EQ(ctx.objectPrimitives(b).count, 12u);
    for (PrimitiveID p = 0; p < 14; ++p) EXPECT_EQ(ctx.primitiveObject(p), p < 2 ? a : b);
    auto v = ctx.primitiveVertices(1);
    EXPECT_EQ(v[0], vec3(0, 0, 0));
    EXPECT_EQ(v[1], vec3(1, 1, 0));
    EXPECT_EQ(v[2], vec3(0, 1, 0));
}

TEST(Context, IDsAreNeverReusedAfterDeletion) {
    Context ctx;
    ObjectID a = ctx.addObject(quad());
    ObjectID b = ctx.addObject(quad());
    ctx.deleteObject(a);
    EXPECT_FALSE(ctx.doesObjectExist(a));
    EXPECT_FALSE(ctx.doesPrimitiveExist(0));
    EXPECT_FALSE(ctx.doesPrimitiveExist(1));
    EXPECT_TRUE(ctx.doesPrimitiveExist(2));
    ObjectID c = ctx.addObject(quad());
    EXPECT_EQ(c, 2u);
    EXPECT_EQ(ctx.objectPrimitives(c).first, 4u);
    EXPECT_EQ(ctx.objectIDs(), (std::vector<ObjectID>{b, c}));
    EXPECT_EQ(ctx.triangleCount(), 4u);
    EXPECT_THROW(ctx.deleteObject(a), Error);
    EXPECT_THROW(ctx.object(a), Error);
    EXPECT_THROW(ctx.primitiveObject(0), Error);
}

TEST(Context, SkippedObjectIDsAreIssuedButNeverLive) {
    Context ctx;
    const ObjectID first = ctx.addObject(quad());
    ctx.skipObjectIDs(1000000);  // a million IDs at once, without a million objects
    EXPECT_EQ(ctx.objectIDLimit(), 1000000u);
    EXPECT_EQ(ctx.objectCount(), 1u);
    EXPECT_FALSE(ctx.doesObjectExist(999999));
    const ObjectID next = ctx.addObject(quad());
    EXPECT_EQ(next, 1000000u);
    EXPECT_EQ(ctx.objectIDs(), (std::vector<ObjectID>{first, next}));
    ctx.skipObjectIDs(10);  // below the limit: nothing changes
    EXPECT_EQ(ctx.objectIDLimit(), 1000001u);
    ctx.setObjectData(next, "organ", std::string("leaf"));
    EXPECT_EQ(ctx.objectDataString(next, "organ"), "leaf");
    EXPECT_THROW(ctx.skipObjectIDs(0xffffffffu), Error);
}

TEST(Context, SetObjectMeshKeepsObjectIDAndPrimitiveIDsWhenCountUnchanged) {
    Context ctx;
    ObjectID a = ctx.addObject(quad(1.0f));
    ObjectID b = ctx.addObject(quad(1.0f));
    ctx.setObjectData(a, "organ", std::string("leaf"));
    const PrimitiveRange before = ctx.objectPrimitives(a);
    ctx.setObjectMesh(a, quad(2.0f));
    EXPECT_EQ(ctx.objectPrimitives(a).first, before.first);
    EXPECT_NEAR(ctx.objectArea(a), 4.0, 1e-6);
    EXPECT_EQ(ctx.objectDataString(a, "organ"), "leaf");
    // A different triangle count gives a fresh run of primitive IDs.
    ctx.setObjectMesh(a, grid(2, 2));
    const PrimitiveRange after = ctx.objectPrimitives(a);
    EXPECT_EQ(after.count, 8u);
    EXPECT_GE(after.first, 4u);
    EXPECT_FALSE(ctx.doesPrimitiveExist(before.first));
    EXPECT_EQ(ctx.primitiveObject(after.first), a);
    EXPECT_EQ(ctx.triangleCount(), 10u);
    // The other object is untouched.
    EXPECT_NEAR(ctx.objectArea(b), 1.0, 1e-6);
    EXPECT_EQ(ctx.objectPrimitives(b).first, 2u);
}

TEST(Context, CompactionNeverChangesIDsOrGeometry) {
    Context ctx;
    std::vector<ObjectID> ids;
    for (int i = 0; i < 2000; ++i) {
        Mesh m = grid(4, 4);
        m.transform(glm::translate(mat4(1.0f), vec3(float(i), 0, 0)));
        ids.push_back(ctx.addObject(m));
    }
    for (int i = 0; i < 2000; i += 2) ctx.deleteObject(ids[i]);
    for (int i = 1; i < 2000; i += 4) ctx.setObjectMesh(ids[i], grid(8, 8));  // relocates
    ctx.compact();
    for (int i = 1; i < 2000; i += 2) {
        const AABB box = ctx.objectBoundingBox(ids[i]);
        if (i % 4 == 1) {
            EXPECT_EQ(box.max, vec3(8, 8, 0));
            EXPECT_EQ(ctx.objectPrimitives(ids[i]).count, 128u);
        } else {
            EXPECT_EQ(box.min, vec3(float(i), 0, 0));
            EXPECT_EQ(ctx.objectPrimitives(ids[i]).count, 32u);
        }
        const PrimitiveRange r = ctx.objectPrimitives(ids[i]);
        EXPECT_EQ(ctx.primitiveObject(r.first + r.count - 1), ids[i]);
    }
    EXPECT_EQ(ctx.objectCount(), 1000u);
    EXPECT_EQ(ctx.triangleCount(), 500u * 128u + 500u * 32u);
}

TEST(Context, CopyTransformHide) {
    Context ctx;
    MaterialID red = ctx.addMaterial({.color = {1, 0, 0}});
    ObjectID a = ctx.addObject(quad(1.0f, true), red);
    ctx.setObjectData(a, "leafID", 7);
    ctx.setObjectData(a, "age", 3.5f);
    ctx.setObjectData(a, "normal", vec3(0, 0, 1));
    ObjectID b = ctx.copyObject(a);
    EXPECT_NE(a, b);
    EXPECT_EQ(ctx.objectMaterial(b), red);
    EXPECT_EQ(ctx.objectDataInt(b, "leafID"), 7);
    EXPECT_EQ(ctx.objectDataFloat(b, "age"), 3.5f);
    EXPECT_EQ(ctx.objectDataVec3(b, "normal"), vec3(0, 0, 1));
    EXPECT_EQ(ctx.object(b).uvs.size(), 4u);
    ctx.transformObject(b, glm::translate(mat4(1.0f), vec3(0, 0, 5)));
    EXPECT_EQ(ctx.objectBoundingBox(b).min.z, 5.0f);
    EXPECT_EQ(ctx.objectBoundingBox(a).min.z, 0.0f);
    EXPECT_EQ(ctx.boundingBox().max.z, 5.0f);
    ctx.setObjectHidden(b, true);
    EXPECT_TRUE(ctx.isObjectHidden(b));
    EXPECT_EQ(ctx.boundingBox().max.z, 0.0f);
    EXPECT_EQ(ctx.boundingBox(true).max.z, 5.0f);
}

TEST(Context, MaterialsAreDeduplicatedByValue) {
    Context ctx;
    EXPECT_EQ(ctx.materialCount(), 1u);  // the default material
    MaterialID a = ctx.addMaterial({.color = {0.1f, 0.5f, 0.1f}});
    MaterialID b = ctx.addMaterial({.color = {0.1f, 0.5f, 0.1f}});
    MaterialID c = ctx.addMaterial({.color = {0.1f, 0.5f, 0.1f}, .texture = "leaf.png"});
    EXPECT_EQ(a, b);
    EXPECT_NE(a, c);
    EXPECT_EQ(ctx.material(c).texture, "leaf.png");
    EXPECT_THROW(ctx.material(99), Error);
    EXPECT_THROW(ctx.addObject(quad(), MaterialID{99}), Error);
}

TEST(Context, ObjectDataTypesAreEnforced) {
    Context ctx;
    ObjectID a = ctx.addObject(quad());
    ObjectID b = ctx.addObject(quad());
    ctx.setObjectData(a, "plantID", 3);
    EXPECT_THROW(ctx.setObjectData(b, "plantID", 3.0f), Error);
    EXPECT_THROW(ctx.objectDataFloat(a, "plantID"), Error);
    EXPECT_EQ(ctx.objectDataInt(b, "plantID"), std::nullopt);
    EXPECT_EQ(ctx.objectDataInt(a, "nolabel"), std::nullopt);
    EXPECT_EQ(ctx.objectDataType("plantID"), DataType::Int);
    ctx.setObjectData(a, "organ", std::string("leaf"));
    ctx.setObjectData(b, "organ", std::string("internode"));
    EXPECT_EQ(ctx.objectDataLabels(), (std::vector<std::string>{"organ", "plantID"}));
    ctx.clearObjectData(a, "organ");
    EXPECT_FALSE(ctx.hasObjectData(a, "organ"));
    EXPECT_EQ(ctx.objectDataString(b, "organ"), "internode");
    // Data dies with its object.
    ctx.deleteObject(b);
    ObjectID c = ctx.addObject(quad());
    EXPECT_FALSE(ctx.hasObjectData(c, "organ"));
    try {
        ctx.setObjectData(c, "plantID", std::string("x"));
        FAIL() << "expected an Error";
    } catch (const Error& e) {
        EXPECT_EQ(e.parameter(), "plantID");
        EXPECT_EQ(e.validRange(), "int");
    }
}

TEST(Context, DataColumnsSetAsLabelsDo) {
    Context ctx;
    const ObjectID a = ctx.addObject(quad());
    const ObjectID b = ctx.addObject(quad());
    const DataColumn organ = ctx.dataColumn("organ", DataType::String);
    const DataColumn plant = ctx.dataColumn("plantID", DataType::Int);
    EXPECT_EQ(ctx.objectDataLabels(), (std::vector<std::string>{"organ", "plantID"}));
    ctx.setObjectData(a, organ, std::string("leaf"));
    ctx.setObjectData(b, organ, std::string("leaf"));
    ctx.setObjectData(b, organ, std::string("petiole"));
    ctx.setObjectData(a, plant, 7);
    EXPECT_EQ(ctx.objectDataString(a, "organ"), "leaf");
    EXPECT_EQ(ctx.objectDataString(b, "organ"), "petiole");
    EXPECT_EQ(ctx.objectDataInt(a, "plantID"), 7);
    EXPECT_FALSE(ctx.hasObjectData(b, "plantID"));
    // The same column by name; a value of another type, a column of no Context, a label
    // holding another type: errors.
    EXPECT_EQ(ctx.dataColumn("organ", DataType::String).index, organ.index);
    EXPECT_THROW(ctx.setObjectData(a, organ, 3), Error);
    EXPECT_THROW(ctx.setObjectData(a, DataColumn{99, DataType::Int}, 3), Error);
    EXPECT_THROW(ctx.dataColumn("organ", DataType::Float), Error);
    EXPECT_THROW(ctx.dataColumn("", DataType::Float), Error);
    EXPECT_THROW(ctx.setObjectData(77, plant, 1), Error);
    // A copy's columns are its own.
    Context copy = ctx;
    copy.setObjectData(b, plant, 9);
    copy.setObjectData(a, organ, std::string("fruit"));
    EXPECT_EQ(copy.objectDataInt(b, "plantID"), 9);
    EXPECT_EQ(copy.objectDataString(a, "organ"), "fruit");
    EXPECT_FALSE(ctx.hasObjectData(b, "plantID"));
    EXPECT_EQ(ctx.objectDataString(a, "organ"), "leaf");
    // The string set last is remembered per column, not across a new object's value.
    const ObjectID c = ctx.addObject(quad());
    ctx.setObjectData(c, organ, std::string("leaf"));
    EXPECT_EQ(ctx.objectDataString(c, "organ"), "leaf");
}

TEST(Context, PlacedMeshesEqualTransformedCopies) {
    const mat4 xf = glm::rotate(glm::translate(mat4(1.0f), vec3(0.3f, -2.0f, 1.5f)), 0.7f,
                                glm::normalize(vec3(1.0f, 2.0f, 3.0f))) *
                    glm::scale(mat4(1.0f), vec3(0.2f));
    Context placed, copied;
    const Mesh m = grid(3, 2);
    Mesh moved = m;
    moved.transform(xf);
    const ObjectID a = placed.addObject(m, xf);
    const ObjectID b = copied.addObject(moved);
    ASSERT_EQ(a, b);
    EXPECT_EQ(placed.objectMesh(a).positions, copied.objectMesh(b).positions);
    EXPECT_EQ(placed.objectMesh(a).indices, copied.objectMesh(b).indices);
    // Replacing keeps the ID; the placed mesh equals the transformed copy to the bit.
    Mesh q = quad(2.0f, true);
    placed.setObjectMesh(a, q, xf);
    q.transform(xf);
    copied.setObjectMesh(b, q);
    EXPECT_EQ(placed.objectMesh(a).positions, copied.objectMesh(b).positions);
    EXPECT_EQ(placed.objectMesh(a).uvs, copied.objectMesh(b).uvs);
    // Checked as any mesh: bad indices, non-finite input, and a transform that overflows.
    Mesh bad = quad();
    bad.indices[2] = 4;
    EXPECT_THROW(placed.addObject(bad, xf), Error);
    EXPECT_THROW(placed.setObjectMesh(a, bad, xf), Error);
    bad = quad();
    bad.positions[1].y = std::numeric_limits<float>::infinity();
    EXPECT_THROW(placed.addObject(bad, xf), Error);
    EXPECT_THROW(placed.addObject(quad(), glm::scale(mat4(1.0f), vec3(1e38f)) * 10.0f), Error);
    mat4 nan = xf;
    nan[3][0] = std::nanf("");
    EXPECT_THROW(placed.addObject(quad(), nan), Error);
    EXPECT_EQ(placed.objectCount(), 1u);
    EXPECT_EQ(placed.triangleCount(), 2u);
}

TEST(Context, PrimitiveData) {
    Context ctx;
    ObjectID a = ctx.addObject(grid(2, 1));
    const PrimitiveRange r = ctx.objectPrimitives(a);
    ctx.setPrimitiveData(r.first + 1, "reflectance", 0.3f);
    EXPECT_EQ(std::get<float>(*ctx.primitiveData(r.first + 1, "reflectance")), 0.3f);
    EXPECT_FALSE(ctx.primitiveData(r.first, "reflectance").has_value());
    EXPECT_THROW(ctx.setPrimitiveData(r.first, "reflectance", 1), Error);
    EXPECT_THROW(ctx.setPrimitiveData(9999, "reflectance", 1.0f), Error);
    ctx.deleteObject(a);
    EXPECT_THROW(ctx.primitiveData(r.first + 1, "reflectance"), Error);
}

TEST(Context, RejectsInvalidMeshes) {
    Context ctx;
    Mesh bad = quad();
    bad.indices.push_back(0);
    EXPECT_THROW(ctx.addObject(bad), Error);
    bad = quad();
    bad.indices[2] = 4;
    EXPECT_THROW(ctx.addObject(bad), Error);
    bad = quad();
    bad.positions[1].x = std::nanf("");
    EXPECT_THROW(ctx.addObject(bad), Error);
    bad = quad();
    bad.uvs = {{0, 0}};
    EXPECT_THROW(ctx.addObject(bad), Error);
    EXPECT_EQ(ctx.objectCount(), 0u);
    EXPECT_EQ(ctx.triangleCount(), 0u);
}

TEST(Context, ForEachObjectVisitsLiveObjectsInOrder) {
    Context ctx;
    for (int i = 0; i < 5; ++i) ctx.addObject(quad(float(i + 1)));
    ctx.deleteObject(2);
    std::vector<ObjectID> seen;
    double area = 0;
    ctx.forEachObject([&](const ObjectView& v) {
        seen.push_back(v.id);
        EXPECT_EQ(v.triangleCount(), 2u);
        area += ctx.objectArea(v.id);
    });
    EXPECT_EQ(seen, (std::vector<ObjectID>{0, 1, 3, 4}));
    EXPECT_NEAR(area, 1 + 4 + 16 + 25, 1e-6);
}

TEST(Context, CopiesAreIndependent) {
    Context ctx;
    ObjectID a = ctx.addObject(quad());
    Context other = ctx;
    other.transformObject(a, glm::translate(mat4(1.0f), vec3(1, 0, 0)));
    EXPECT_EQ(ctx.objectBoundingBox(a).min.x, 0.0f);
    EXPECT_EQ(other.objectBoundingBox(a).min.x, 1.0f);
    ctx.clear();
    EXPECT_EQ(ctx.objectCount(), 0u);
    EXPECT_EQ(ctx.addObject(quad()), 0u);
}

TEST(Context, MemoryPerTriangleIsSmall) {
    Context ctx;
    Mesh leaf = grid(10, 5);  // 100 triangles, 66 vertices
    for (int i = 0; i < 1000; ++i) {
        ObjectID id = ctx.addObject(leaf);
        ctx.setObjectData(id, "plantID", i / 100);
        ctx.setObjectData(id, "organ", std::string("leaf"));
    }
    const double perTriangle = double(ctx.memoryBytes()) / double(ctx.triangleCount());
    EXPECT_LT(perTriangle, 64.0);
}
