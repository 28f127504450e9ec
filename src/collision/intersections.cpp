// Counting crossing object pairs (see intersections.h).

#include "collision/intersections.h"

#include <algorithm>
#include <array>

#include "collision/proxies.h"

namespace plantarch::collision {

namespace {

struct Item {
    AABB box;
    std::vector<std::array<vec3, 3>> triangles;
    std::vector<AABB> boxes;
};

bool overlap(const AABB& a, const AABB& b) {
    return a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y &&
           a.min.z <= b.max.z && b.min.z <= a.max.z;
}

bool cross(const Item& a, const Item& b) {
    for (std::size_t i = 0; i < a.triangles.size(); ++i) {
        if (!overlap(a.boxes[i], b.box)) continue;
        for (std::size_t j = 0; j < b.triangles.size(); ++j)
            if (overlap(a.boxes[i], b.boxes[j]) &&
                triangleTriangleOverlap(a.triangles[i], b.triangles[j][0], b.triangles[j][1],
                                        b.triangles[j][2], 1e-7f))
                return true;
    }
    return false;
}

}  // namespace

std::vector<long long> petioleGroups(const Context& ctx, const std::vector<ObjectID>& objects) {
    std::vector<long long> out;
    for (ObjectID o : objects) {
        const long long plant = ctx.objectDataInt(o, "plantID").value_or(-1);
        const long long shoot = ctx.objectDataInt(o, "shootID").value_or(-1);
        const long long node = ctx.objectDataInt(o, "node").value_or(-1);
        out.push_back(plant < 0 ? -1 : (plant << 40) | (shoot << 20) | node);
    }
    return out;
}

std::size_t countIntersectingPairs(const Context& ctx, const std::vector<ObjectID>& objects,
                                   const std::vector<long long>& groups) {
    std::vector<Item> items(objects.size());
    for (std::size_t k = 0; k < objects.size(); ++k) {
        const ObjectView v = ctx.object(objects[k]);
        Item& it = items[k];
        for (std::size_t t = 0; t + 2 < v.indices.size(); t += 3) {
            std::array<vec3, 3> tri = {v.positions[v.indices[t]], v.positions[v.indices[t + 1]],
                                       v.positions[v.indices[t + 2]]};
            AABB b;
            for (const vec3& p : tri) b.add(p);
            it.triangles.push_back(tri);
            it.boxes.push_back(b);
            it.box.add(b);
        }
    }
    std::vector<std::size_t> order(items.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return items[a].box.min.x < items[b].box.min.x;
    });
    std::size_t count = 0;
    for (std::size_t a = 0; a < order.size(); ++a) {
        const Item& A = items[order[a]];
        if (A.triangles.empty()) continue;
        for (std::size_t b = a + 1; b < order.size(); ++b) {
            const Item& B = items[order[b]];
            if (B.box.min.x > A.box.max.x) break;
            if (!groups.empty() && groups[order[a]] >= 0 && groups[order[a]] == groups[order[b]])
                continue;
            if (!B.triangles.empty() && overlap(A.box, B.box) && cross(A, B)) ++count;
        }
    }
    return count;
}

}  // namespace plantarch::collision
