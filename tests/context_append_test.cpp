// Context::appendObjects (the bulk copy canopies use), reserve and clear(false).

#include <gtest/gtest.h>
#include <omp.h>

#include "plantarch/Context.h"
#include "plantarch/Error.h"

using namespace plantarch;

namespace {

// An n x n grid of quads with UVs, shifted by `at`.
Mesh sheet(int n, vec3 at, bool withUVs) {
    Mesh m;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            m.positions.push_back(at + vec3(float(i), float(j), 0.0f));
            if (withUVs) m.uvs.push_back({float(i) / float(n), float(j) / float(n)});
        }
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const std::uint32_t a = std::uint32_t(j * (n + 1) + i), b = a + 1,
                                c = a + std::uint32_t(n) + 1, d = c + 1;
            m.indices.insert(m.indices.end(), {a, b, d, a, d, c});
        }
    return m;
}

// A Context of `count` labelled objects, some without UVs, one hidden, one deleted.
Context source(int count, float shift) {
    Context ctx;
    const MaterialID green = ctx.addMaterial(Material{.color = {0.1f, 0.6f, 0.2f}});
    const MaterialID brown = ctx.addMaterial(Material{.color = {0.4f, 0.3f, 0.1f}});
    for (int k = 0; k < count; ++k) {
        const ObjectID id = ctx.addObject(sheet(3 + k % 5, vec3(shift, float(k), 0.0f), k % 3 != 0),
                                          k % 2 ? green : brown);
        ctx.setObjectData(id, "organ", std::int32_t(k % 4));
        ctx.setObjectData(id, "age", float(k) * 0.5f);
        if (k % 2) ctx.setObjectData(id, "name", std::string(k % 4 == 1 ? "leaf" : "stem"));
        if (k % 5 == 0) ctx.setObjectData(id, "normal", vec3(0.0f, 0.0f, float(k)));
    }
    ctx.setObjectHidden(2, true);
    ctx.deleteObject(3);
    ctx.setPrimitiveData(ctx.objectPrimitives(4).first + 1, "hit", std::int32_t(7));
    return ctx;
}

std::vector<ObjectID> live(const Context& ctx) {
    return ctx.objectIDs();
}

void expectSameObject(const Context& a, ObjectID ia, const Context& b, ObjectID ib) {
    const ObjectView va = a.object(ia), vb = b.object(ib);
    ASSERT_EQ(va.positions.size(), vb.positions.size());
    EXPECT_TRUE(std::equal(va.positions.begin(), va.positions.end(), vb.positions.begin()));
    EXPECT_TRUE(
        std::equal(va.indices.begin(), va.indices.end(), vb.indices.begin(), vb.indices.end()));
    ASSERT_EQ(va.uvs.size(), vb.uvs.size());
    EXPECT_TRUE(std::equal(va.uvs.begin(), va.uvs.end(), vb.uvs.begin()));
    EXPECT_EQ(a.material(va.material), b.material(vb.material));
    EXPECT_EQ(va.hidden, vb.hidden);
    for (const std::string& label : a.objectDataLabels())
        EXPECT_EQ(a.objectData(ia, label), b.objectData(ib, label)) << label;
}

}  // namespace

TEST(ContextAppend, CopiesGeometryMaterialsDataAndFlagsInOrder) {
    const Context a = source(40, 0.0f), b = source(25, 100.0f);
    Context scene;
    const ObjectID before = scene.addObject(sheet(2, vec3(-5.0f), false));
    scene.setObjectData(before, "organ", std::int32_t(9));
    const std::vector<ObjectID> fromA = live(a), fromB = live(b);
    std::vector<ObjectID> reversedB(fromB.rbegin(), fromB.rend());
    const std::vector<ObjectSource> sources = {{&a, fromA}, {&b, reversedB}};
    const std::vector<ObjectID> ids = scene.appendObjects(sources);

    ASSERT_EQ(ids.size(), fromA.size() + fromB.size());
    for (std::size_t k = 0; k < ids.size(); ++k) EXPECT_EQ(ids[k], before + 1 + k);
    for (std::size_t k = 0; k < fromA.size(); ++k) expectSameObject(a, fromA[k], scene, ids[k]);
    for (std::size_t k = 0; k < reversedB.size(); ++k)
        expectSameObject(b, reversedB[k], scene, ids[fromA.size() + k]);
    EXPECT_EQ(scene.objectDataInt(before, "organ"), 9);
    EXPECT_EQ(scene.materialCount(), 3u);  // the default and the two shared ones
    EXPECT_EQ(scene.objectCount(), 1 + a.objectCount() + b.objectCount());
    EXPECT_EQ(scene.triangleCount(), 8 + a.triangleCount() + b.triangleCount());
    // Primitive runs follow one another; the primitive datum moved with its object.
    for (std::size_t k = 1; k < ids.size(); ++k)
        EXPECT_EQ(scene.objectPrimitives(ids[k]).first, scene.objectPrimitives(ids[k - 1]).end());
    const ObjectID copyOf4 =
        ids[std::size_t(std::find(fromA.begin(), fromA.end(), 4u) - fromA.begin())];
    EXPECT_EQ(scene.primitiveData(scene.objectPrimitives(copyOf4).first + 1, "hit"),
              DataValue(std::int32_t(7)));
    EXPECT_EQ(scene.primitiveObject(scene.objectPrimitives(ids.back()).first), ids.back());
    // The result is an ordinary Context: objects can be edited and deleted.
    scene.deleteObject(ids[0]);
    scene.compact();
    expectSameObject(a, fromA[1], scene, ids[1]);
}

TEST(ContextAppend, SameResultForAnyThreadCount) {
    std::vector<Context> parts;
    for (int k = 0; k < 12; ++k) parts.push_back(source(160, float(k) * 10.0f));
    std::vector<std::vector<ObjectID>> objects;
    for (const Context& c : parts) objects.push_back(live(c));
    std::vector<ObjectSource> sources;
    for (std::size_t k = 0; k < parts.size(); ++k) sources.push_back({&parts[k], objects[k]});
    auto build = [&](int threads) {
        const int saved = omp_get_max_threads();
        omp_set_num_threads(threads);
        Context scene;
        scene.appendObjects(sources);
        omp_set_num_threads(saved);
        return scene;
    };
    const Context one = build(1), two = build(2);
    ASSERT_EQ(one.objectIDLimit(), two.objectIDLimit());
    ASSERT_GT(one.vertexCount(), 65536u);  // large enough to be copied on all threads
    for (ObjectID id = 0; id < one.objectIDLimit(); ++id) expectSameObject(one, id, two, id);
}

TEST(ContextAppend, RefusesBadSourcesAndChangesNothing) {
    const Context a = source(6, 0.0f);
    Context scene;
    scene.setObjectData(scene.addObject(sheet(1, vec3(0.0f), false)), "age", std::int32_t(3));
    const std::vector<ObjectID> good = live(a);
    const std::vector<ObjectID> missing = {0, 3};  // 3 was deleted
    const std::size_t triangles = scene.triangleCount(), materials = scene.materialCount();
    auto unchanged = [&] {
        EXPECT_EQ(scene.objectCount(), 1u);
        EXPECT_EQ(scene.triangleCount(), triangles);
        EXPECT_EQ(scene.materialCount(), materials);
        EXPECT_FALSE(scene.objectDataType("organ").has_value());
    };
    {
        const std::vector<ObjectSource> s = {{&a, missing}};
        EXPECT_THROW(scene.appendObjects(s), Error);
        unchanged();
    }
    {
        // "age" holds ints here and floats in the source.
        const std::vector<ObjectSource> s = {{&a, good}};
        try {
            scene.appendObjects(s);
            ADD_FAILURE() << "no error";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("age"), std::string::npos) << e.what();
        }
        unchanged();
    }
    {
        const std::vector<ObjectID> own = {0};
        const std::vector<ObjectSource> s = {{&scene, own}};
        EXPECT_THROW(scene.appendObjects(s), Error);
        const std::vector<ObjectSource> none = {{nullptr, own}};
        EXPECT_THROW(scene.appendObjects(none), Error);
        unchanged();
    }
    EXPECT_TRUE(scene.appendObjects({}).empty());
}

TEST(ContextAppend, ReserveAndClearKeepingCapacity) {
    Context ctx;
    ctx.reserve(100, 100000, 200000);
    const std::size_t reserved = ctx.memoryBytes();
    EXPECT_GE(reserved, 100000 * sizeof(vec3) + 600000 * sizeof(std::uint32_t));
    for (int k = 0; k < 50; ++k) ctx.addObject(sheet(20, vec3(float(k)), false));
    EXPECT_EQ(ctx.memoryBytes(), reserved);  // no pool grew
    ctx.setObjectData(0, "organ", std::int32_t(1));
    ctx.clear(false);
    EXPECT_EQ(ctx.objectCount(), 0u);
    EXPECT_EQ(ctx.objectIDLimit(), 0u);
    EXPECT_EQ(ctx.materialCount(), 1u);
    EXPECT_FALSE(ctx.objectDataType("organ").has_value());
    EXPECT_GE(ctx.memoryBytes(), reserved);  // the pools kept their room
    const ObjectID id = ctx.addObject(sheet(1, vec3(0.0f), false));
    EXPECT_EQ(id, 0u);
    EXPECT_TRUE(ctx.object(id).uvs.empty());
    ctx.clear();
    EXPECT_LT(ctx.memoryBytes(), reserved / 10);
}
