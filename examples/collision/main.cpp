// Collision avoidance and attraction points (docs/collision.md): a bean beside a wall, a dense
// canopy with soft avoidance, and a shoot led along a wire. Exits 1 if a promise is broken.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "plantarch/PlantArchitecture.h"
using namespace plantarch;

// A box from `lo` to `hi` as one Context object (12 triangles).
ObjectID addBox(Context& context, vec3 lo, vec3 hi) {
    Mesh m;
    for (int i = 0; i < 8; ++i)
        m.positions.push_back(
            {(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
    m.indices = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
    return context.addObject(m, Material{{0.8f, 0.8f, 0.8f}});
}

int main() {
    // 1. A solid wall 12 cm from a bean: the plant grows along it, never through it.
    Context context;
    PlantArchitecture plantarch(&context);
    const ObjectID wall = addBox(context, {0.12f, -1, 0}, {0.15f, 1, 1.5f});
    plantarch.loadPlantModelFromLibrary("bean");
    plantarch.enableSolidObstacleAvoidance({.obstacles = {wall}, .avoidanceDistance = 0.2f});
    const unsigned bean = plantarch.buildPlantInstanceFromLibrary(vec3(0, 0, 0), 50);
    float maxX = -1;
    for (ObjectID o : plantarch.getAllPlantObjectIDs(bean))
        for (const vec3& p : context.object(o).positions) maxX = std::max(maxX, p.x);
    std::printf("bean beside a wall at x = 0.12 m: farthest vertex at x = %.3f m\n", maxX);

    // 2. A dense canopy with soft collision avoidance: shoots turn toward open space. The
    //    plants grow together, so each sees its neighbours; any thread count, same plants.
    Context field;
    PlantArchitecture canopy(&field);
    canopy.loadPlantModelFromLibrary("bean");
    canopy.enableSoftCollisionAvoidance(
        {.cone = {.halfAngle = 80, .lookAhead = 0.1f, .rays = 256, .inertia = 0.4f}});
    canopy.buildPlantCanopyFromLibrary(vec3(0), vec2(0.2f, 0.2f), glm::ivec2(3, 3), 30);
    const CollisionStats stats = canopy.getCollisionStats();
    std::printf("canopy: %llu of %llu new internodes turned toward open space\n",
                (unsigned long long)stats.softSteered, (unsigned long long)stats.softCones);

    // 3. Attraction points along a trellis wire 0.5 m up: a cane trained along the wire keeps
    //    to it instead of curving up (gravitropism) or wandering (tortuosity).
    Context vineyard;
    PlantArchitecture vine(&vineyard);
    ShootParameters cane;
    cane.max_nodes = 25;
    cane.internode_length_max = 0.04f;
    cane.phyllochron_min = 1;
    cane.elongation_rate_max = 0.25f;
    cane.gravitropic_curvature = 60;
    cane.tortuosity = 3;
    cane.phytomer_parameters.leaf.prototype_scale = 0.06f;
    vine.defineShootType("cane", cane);
    const unsigned plant = vine.addPlantInstance(vec3(0), 0);
    const unsigned trunk = vine.addBaseStemShoot(
        plant, {.phytomers = 10,
                .size = {.internodeRadius = 0.005f, .internodeLengthMax = 0.05f},
                .shootType = "cane"});
    vine.removeShootApex(plant, trunk);
    const unsigned arm = vine.appendShoot(plant, trunk,
                                          {.phytomers = 1,
                                           .baseRotation = {.pitch = 90},
                                           .size = {.internodeRadius = 0.003f,
                                                    .internodeLengthMax = 0.04f,
                                                    .internodeLengthScale = 0.1f,
                                                    .leafScale = 0.1f},
                                           .shootType = "cane"});
    std::vector<vec3> wire;
    for (int i = 0; i <= 60; ++i) wire.push_back(vec3(0.02f * float(i), 0, 0.5f));
    vine.enableAttractionPoints(
        plant, {.points = wire, .halfAngle = 70, .lookAhead = 0.25f, .inertia = 0.3f});
    vine.advanceTime(plant, 25);
    const vec3 tip = vine.getNodePosition(plant, arm, vine.getShootNodeCount(plant, arm) - 1);
    std::printf("cane tip at (%.2f, %.2f, %.2f) m; the wire runs along y = 0, z = 0.5\n", tip.x,
                tip.y, tip.z);

    const bool ok = maxX <= 0.12f && stats.softSteered > 0 && tip.x > 0.6f &&
                    std::abs(tip.z - 0.5f) < 0.03f && std::abs(tip.y) < 0.03f;
    return ok ? 0 : 1;
}
