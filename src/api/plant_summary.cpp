// summarizePlant: one pass over a plant's state and its objects' triangles.

#include <algorithm>
#include <cmath>
#include <numbers>

#include "plantarch/PlantArchitecture.h"
#include "plantarch/PlantSummary.h"

namespace plantarch {

namespace {

// The largest horizontal extent over every whole degree of direction, and the extent square
// to it.
void ownAxes(const std::vector<vec3>& points, PlantSummary& s) {
    double longest = -1.0, across = 0.0;
    for (int degree = 0; degree < 180; ++degree) {
        const double a = degree * std::numbers::pi / 180.0, c = std::cos(a), sn = std::sin(a);
        double l0 = HUGE_VAL, l1 = -HUGE_VAL, w0 = HUGE_VAL, w1 = -HUGE_VAL;
        for (const vec3& q : points) {
            const double along = c * q.x + sn * q.y, square = c * q.y - sn * q.x;
            l0 = std::min(l0, along);
            l1 = std::max(l1, along);
            w0 = std::min(w0, square);
            w1 = std::max(w1, square);
        }
        if (l1 - l0 > longest) {
            longest = l1 - l0;
            across = w1 - w0;
        }
    }
    s.widthLong = points.empty() ? 0.0f : float(longest);
    s.widthShort = points.empty() ? 0.0f : float(across);
}

void countFloral(const FloralBud& fb, PlantSummary& s) {
    const bool flower =
        fb.stage == FloralStage::FlowerClosed || fb.stage == FloralStage::FlowerOpen;
    if (!flower && fb.stage != FloralStage::Fruit) return;
    // A fruit at the moment it sets has no size yet, so no geometry: not counted.
    for (const FlowerOrgan& fl : fb.flowers)
        if (hasSize(currentFloralSize(fb, fl))) ++(flower ? s.flowers : s.fruit);
}

void leafInclination(const Context& ctx, const std::vector<ObjectID>& leaves, PlantSummary& s) {
    std::array<double, 9> area{};
    for (ObjectID id : leaves) {
        const ObjectView o = ctx.object(id);
        for (std::size_t t = 0; t + 2 < o.indices.size(); t += 3) {
            const vec3 a = o.positions[o.indices[t]], b = o.positions[o.indices[t + 1]],
                       c = o.positions[o.indices[t + 2]];
            const vec3 n = glm::cross(b - a, c - a);
            const double twice = glm::length(n);
            if (!(twice > 0.0)) continue;
            const double angle =
                std::acos(std::min(1.0, std::abs(double(n.z)) / twice)) * 180.0 / std::numbers::pi;
            area[std::min<std::size_t>(8, std::size_t(angle / 10.0))] += 0.5 * twice;
        }
    }
    double total = 0.0;
    for (double v : area) total += v;
    if (total > 0.0)
        for (std::size_t i = 0; i < area.size(); ++i) s.leafInclination[i] = float(area[i] / total);
}

}  // namespace

PlantSummary summarizePlant(const PlantArchitecture& arch, unsigned plantID) {
    const PlantInstance& p = arch.plant(plantID);
    const Context& ctx = arch.context();
    PlantSummary s;
    s.height = arch.getPlantHeight(plantID);
    s.leafArea = arch.getPlantLeafArea(plantID);
    s.leaves = arch.getPlantLeafCount(plantID);
    for (const Shoot& shoot : p.shoots) {
        if (shoot.removed) continue;
        if (s.shootsByRank.size() <= shoot.rank) {
            s.shootsByRank.resize(shoot.rank + 1, 0);
            s.phytomersByRank.resize(shoot.rank + 1, 0);
        }
        ++s.shootsByRank[shoot.rank];
        s.phytomersByRank[shoot.rank] += unsigned(shoot.phytomers.size());
        for (const Phytomer& ph : shoot.phytomers)
            for (const Petiole& pt : ph.petioles)
                for (const FloralBud& fb : pt.floralBuds) countFloral(fb, s);
        for (const FloralBud& fb : shoot.terminalFloralBuds) countFloral(fb, s);
    }
    if (!p.shoots.empty() && !p.shoots[0].removed)
        s.mainNodes = unsigned(p.shoots[0].phytomers.size());
    std::vector<vec3> points;
    vec3 lo(HUGE_VALF), hi(-HUGE_VALF);
    for (ObjectID id : arch.getAllPlantObjectIDs(plantID)) {
        const ObjectView o = ctx.object(id);
        s.triangles += o.triangleCount();
        for (const vec3& q : o.positions) {
            points.push_back(q);
            lo = glm::min(lo, q);
            hi = glm::max(hi, q);
        }
    }
    if (!points.empty()) {
        s.widthX = hi.x - lo.x;
        s.widthY = hi.y - lo.y;
    }
    ownAxes(points, s);
    leafInclination(ctx, arch.getPlantObjectIDs(plantID, OrganKind::Leaf), s);
    return s;
}

}  // namespace plantarch
