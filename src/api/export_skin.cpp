// A wind-ready skeleton of each plant (plantarch/ExportPlants.h, exportSkeletons): a root
// joint at the plant's base and one joint per internode at its base, parented along the
// shoots and from a branch's first internode to the internode of its parent that carries it;
// the objects bound to them. Internode tubes blend between the joints of the internodes they
// join, so they bend smoothly at the nodes; every other organ (petioles, leaves, flowers, fruit) is
// rigid on the joint of its node's internode, as the shoots' bending under load turns it.
//
// The bind pose is the geometry as it stands: node positions as drawn (bends applied),
// joint orientations from the drawn internode and its roll reference turned by the bend.

#include <algorithm>
#include <cmath>
#include <glm/gtc/quaternion.hpp>
#include <string>
#include <vector>

#include "core/math.h"
#include "geometry/tessellate.h"
#include "plantarch/Error.h"
#include "plantarch/ExportPlants.h"

namespace plantarch {

namespace {

constexpr std::size_t kMaxJoints = 65535;  // JOINTS_0 as unsigned short

// A vector of the rest shape turned by the internode's bend, as the tessellation turns it.
vec3 bent(vec3 v, const Internode& in) {
    if (!in.bend || in.bend->angle == 0.0f) return v;
    return unitOr(rotateAbout(v, in.bend->axis, in.bend->angle * kDeg), v);
}

std::array<float, 4> quaternionOf(vec3 x, vec3 y, vec3 z) {
    const glm::quat q = glm::normalize(glm::quat_cast(glm::mat3(x, y, z)));
    return {q.x, q.y, q.z, q.w};
}

// The blend of an internode tube's vertex at fraction t (0 at its base node, 1 at its tip
// node) of the internode: half on each neighbour at the nodes, all on its own joint midway.
GltfInfluence tubeInfluence(float t, std::uint16_t self, int below, int above) {
    GltfInfluence g;
    auto two = [&](int other, float w) {
        if (other < 0 || !(w > 0.0f)) {
            g.joints[0] = self;
            g.weights[0] = 1.0f;
            return;
        }
        g.joints[0] = self;
        g.joints[1] = std::uint16_t(other);
        g.weights[1] = w;
        g.weights[0] = 1.0f - w;
    };
    if (t < 0.5f)
        two(below, 0.5f - t);
    else
        two(above, t - 0.5f);
    return g;
}

GltfSkeleton skeletonOf(const PlantInstance& p, const Context& ctx,
                        const std::vector<ObjectID>& ids) {
    GltfSkeleton sk;
    sk.plant = std::int32_t(p.id);
    const std::string prefix = "plant" + std::to_string(p.id) + "_";
    sk.joints.push_back({prefix + "root", -1, p.base, {0.0f, 0.0f, 0.0f, 1.0f}, -1, -1});

    // Shoots parents first: the base stems, then each shoot's children in order.
    std::vector<unsigned> order;
    for (const Shoot& s : p.shoots)
        if (s.parent < 0 && !s.removed) order.push_back(s.id);
    for (std::size_t k = 0; k < order.size(); ++k)
        for (unsigned c : p.shoots[order[k]].children)
            if (c < p.shoots.size() && !p.shoots[c].removed && p.shoots[c].parent == int(order[k]))
                order.push_back(c);

    std::vector<std::vector<std::uint16_t>> jointOf(p.shoots.size());
    std::vector<GltfSkinnedObject> objects;
    for (unsigned id : order) {
        const Shoot& s = p.shoots[id];
        if (s.phytomers.empty()) continue;
        if (sk.joints.size() + s.phytomers.size() > kMaxJoints)
            throw Error(
                "too many internodes for a skinned plant",
                {.parameter = "skin",
                 .value = "plant " + std::to_string(p.id) + ": more than " +
                          std::to_string(kMaxJoints) + " internodes",
                 .validRange = "at most " + std::to_string(kMaxJoints) + " internodes per plant"});
        int parent = 0;
        if (s.parent >= 0) {
            const std::vector<std::uint16_t>& on = jointOf[unsigned(s.parent)];
            if (!on.empty())
                parent = on[std::min<std::size_t>(std::size_t(std::max(s.parentNode, 0)),
                                                  on.size() - 1)];
        }
        const std::vector<vec3> nodes = shootNodePositions(p, id);
        for (std::size_t i = 0; i < s.phytomers.size(); ++i) {
            const Internode& in = s.phytomers[i].internode;
            const vec3 span = nodes[i + 1] - nodes[i];
            const vec3 y = unitOr(span, unitOr(bent(in.direction, in), vec3(0.0f, 0.0f, 1.0f)));
            const vec3 roll = bent(in.rollReference, in);
            const vec3 x = unitOr(roll - glm::dot(roll, y) * y, anyPerpendicular(y));
            const vec3 z = glm::cross(x, y);
            jointOf[id].push_back(std::uint16_t(sk.joints.size()));
            sk.joints.push_back(
                {prefix + "shoot" + std::to_string(id) + "_node" + std::to_string(i), parent,
                 nodes[i], quaternionOf(x, y, z), std::int32_t(id), std::int32_t(i)});
            parent = int(jointOf[id].back());
        }
        // The tubes: each vertex by where it lies along its internode.
        for (std::size_t i = 0; i < s.phytomers.size(); ++i) {
            const ObjectID o = s.phytomers[i].internode.object;
            if (o == kNoObject || !ctx.doesObjectExist(o)) continue;
            const std::uint16_t self = jointOf[id][i];
            // A shoot's tube starts square to its first internode: its base ring on that
            // joint alone; inner rings face between the internodes they join.
            const int below = i > 0 ? int(jointOf[id][i - 1]) : -1;
            const int above = i + 1 < s.phytomers.size() ? int(jointOf[id][i + 1]) : -1;
            const vec3 span = nodes[i + 1] - nodes[i];
            const float length2 = glm::dot(span, span);
            GltfSkinnedObject so{o, self, {}};
            so.vertices.reserve(ctx.object(o).positions.size());
            for (const vec3& v : ctx.object(o).positions) {
                const float t = length2 > 0.0f
                                    ? std::clamp(glm::dot(v - nodes[i], span) / length2, 0.0f, 1.0f)
                                    : 0.5f;
                so.vertices.push_back(tubeInfluence(t, self, below, above));
            }
            objects.push_back(std::move(so));
        }
    }
    // Every other organ: rigid on the joint of its node's internode (by its labels).
    std::vector<ObjectID> tubes;
    for (const GltfSkinnedObject& so : objects) tubes.push_back(so.object);
    std::sort(tubes.begin(), tubes.end());
    for (ObjectID o : ids) {
        if (std::binary_search(tubes.begin(), tubes.end(), o)) continue;
        const std::int32_t shoot = ctx.objectDataInt(o, "shootID").value_or(-1);
        const std::int32_t node = ctx.objectDataInt(o, "node").value_or(-1);
        std::uint16_t joint = 0;
        if (shoot >= 0 && std::size_t(shoot) < jointOf.size() &&
            !jointOf[std::size_t(shoot)].empty()) {
            const std::vector<std::uint16_t>& on = jointOf[std::size_t(shoot)];
            joint = on[std::min<std::size_t>(std::size_t(std::max(node, 0)), on.size() - 1)];
        }
        if (joint != 0) objects.push_back({o, joint, {}});
    }
    std::sort(
        objects.begin(), objects.end(),
        [](const GltfSkinnedObject& a, const GltfSkinnedObject& b) { return a.object < b.object; });
    sk.objects = std::move(objects);
    return sk;
}

}  // namespace

std::vector<GltfSkeleton> exportSkeletons(const PlantArchitecture& arch) {
    std::vector<GltfSkeleton> out;
    const Context& ctx = arch.context();
    for (unsigned id : arch.getAllPlantIDs())
        out.push_back(skeletonOf(arch.plant(id), ctx, arch.getAllPlantObjectIDs(id)));
    return out;
}

}  // namespace plantarch
