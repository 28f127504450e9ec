// Solid obstacle clearance of side organs: petioles with their leaves and peduncles with their
// flowers (organClearance), fruit (fruitAdjustment). An organ whose bounds cross an obstacle
// is turned about its attachment point, away from the obstacle in 10-degree steps until
// clear, then back toward it one degree at a time while still clear. The turn is recomputed
// from the unturned organ at the end of every growth step, so it is a function of the plant's
// shape alone, whatever the step size.

#include "collision/clearance.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>

#include "collision/collision_world.h"
#include "collision/proxies.h"
#include "core/math.h"
#include "geometry/tessellate.h"
#include "geometry/tube.h"

namespace plantarch::collision {

namespace {

// Overlap of less than this counts as touching, not crossing (m).
constexpr float kTolerance = 1e-5f;

class Clearer {
public:
    Clearer(const Worker& worker, const World& world, PlantInstance& plant)
        : worker_(worker), world_(world), plant_(plant), sink_(worker.proxies) {
        nodes_.resize(plant.shoots.size());
        for (const Shoot& s : plant.shoots)
            if (!s.removed) nodes_[s.id] = shootNodePositions(plant, s.id);
    }

    void run() {
        const SolidObstacleOptions& o = *world_.solid();
        for (Shoot& s : plant_.shoots) {
            if (s.removed) continue;
            for (unsigned k = 0; k < s.phytomers.size(); ++k) {
                Phytomer& ph = s.phytomers[k];
                const vec3 top = nodes_[s.id][k + 1];
                for (unsigned j = 0; j < ph.petioles.size(); ++j) {
                    Petiole& pt = ph.petioles[j];
                    if (o.organClearance) clearPetiole(s, k, j, pt, ph.leafFraction, top);
                    for (unsigned b = 0; b < pt.floralBuds.size(); ++b)
                        clearBud(s, k, j, b, false, pt.floralBuds[b], top, o);
                }
            }
            if (!s.phytomers.empty())
                for (unsigned b = 0; b < s.terminalFloralBuds.size(); ++b)
                    clearBud(s, 0, 0, b, true, s.terminalFloralBuds[b], nodes_[s.id].back(), o);
        }
    }

private:
    OrganPlacer& placer() {
        if (!placer_)
            placer_ = std::make_unique<OrganPlacer>(worker_.store, worker_.prototypes, plant_);
        return *placer_;
    }

    bool near(vec3 p, float radius) {
        world_.solidTrianglesNear(p, radius, candidates_);
        return !candidates_.empty();
    }

    // Whether what the sink holds crosses a solid obstacle.
    bool crosses() {
        if (sink_.bounds.empty()) return false;
        const vec3 c = sink_.bounds.center();
        world_.solidTrianglesNear(c, 0.5f * glm::length(sink_.bounds.extent()) + kTolerance,
                                  candidates_);
        for (unsigned i : candidates_) {
            const auto& t = world_.solidTriangle(i);
            for (const OrientedBox& b : sink_.boxes)
                if (boxTriangleOverlap(b, t[0], t[1], t[2], kTolerance)) return true;
            for (std::size_t k = 0; k + 2 < sink_.triangles.size(); k += 3)
                if (triangleTriangleOverlap(t, sink_.triangles[k], sink_.triangles[k + 1],
                                            sink_.triangles[k + 2], kTolerance))
                    return true;
        }
        return false;
    }

    // Finds the smallest turn (whole degrees) that clears the organ placed by `place`.
    void clear(OrganTurn& turn, vec3 attachment, const std::function<void()>& place,
               std::size_t box = std::size_t(-1)) {
        turn = OrganTurn{};
        auto crossesNow = [&] {
            sink_.clear();
            place();
            if (box != std::size_t(-1)) {  // one fruit of several: keep its box only
                if (box >= sink_.boxes.size()) return false;
                const OrientedBox b = sink_.boxes[box];
                sink_.clear();
                sink_.boxes.push_back(b);
                for (int i = 0; i < 8; ++i) {
                    vec3 corner = b.center;
                    for (int k = 0; k < 3; ++k)
                        corner += ((i >> k) & 1 ? 1.0f : -1.0f) * b.half[k] * b.axis[k];
                    sink_.bounds.add(corner);
                }
            }
            return crosses();
        };
        if (!crossesNow()) return;
        const vec3 out = glm::normalize(sink_.bounds.center() - attachment);
        const auto contact = world_.closestSolid(attachment, 1e3f);
        const vec3 n = contact ? contact->normal : vec3(0, 0, 1);
        vec3 axis = glm::cross(out, n);
        axis = glm::length(axis) > 1e-4f ? glm::normalize(axis) : anyPerpendicular(n);
        AtomicStats& st = world_.stats();
        turn.axis = axis;
        for (int angle = 10; angle <= 180; angle += 10) {
            turn.angle = float(angle);
            if (crossesNow()) continue;
            // Back toward the obstacle while still clear.
            for (int back = angle - 1; back > angle - 10; --back) {
                turn.angle = float(back);
                if (crossesNow()) {
                    turn.angle = float(back + 1);
                    break;
                }
            }
            st.organsTurned.fetch_add(1, std::memory_order_relaxed);
            return;
        }
        turn = OrganTurn{};
        st.organsUnresolved.fetch_add(1, std::memory_order_relaxed);
    }

    void clearPetiole(Shoot& s, unsigned k, unsigned j, Petiole& pt, float leafFraction, vec3 top) {
        pt.clearance = OrganTurn{};
        float leaf = 0.0f;
        for (const LeafOrgan& l : pt.leaves) leaf = std::max(leaf, l.scale);
        const float reach = (pt.length + 1.5f * leaf) * leafFraction + pt.radius + 0.01f;
        if (!near(top, reach)) return;
        sink_.setWanted({OrganKind::Petiole, OrganKind::Leaf});
        clear(pt.clearance, top, [&] { placer().petiole(sink_, s.id, k, j); });
    }

    void clearBud(Shoot& s, unsigned k, unsigned j, unsigned b, bool terminal, FloralBud& fb,
                  vec3 top, const SolidObstacleOptions& o) {
        fb.peduncleClearance = OrganTurn{};
        for (FlowerOrgan& fl : fb.flowers) fl.clearance = OrganTurn{};
        const bool fruit = fb.stage == FloralStage::Fruit;
        const bool flower =
            fb.stage == FloralStage::FlowerClosed || fb.stage == FloralStage::FlowerOpen;
        if (!fruit && !flower) return;
        float organ = 0.0f;
        for (const FlowerOrgan& fl : fb.flowers)
            organ = std::max({organ, fl.flowerScale, fl.fruitScale});
        const float reach = fb.peduncleLength + 1.5f * organ + fb.peduncleRadius + 0.01f;
        if (!near(top, reach)) return;
        auto place = [&] { placer().floralBud(sink_, s.id, k, j, b, terminal); };
        if (o.organClearance) {
            sink_.setWanted({OrganKind::Peduncle, OrganKind::FlowerClosed, OrganKind::FlowerOpen});
            clear(fb.peduncleClearance, top, place);
        }
        if (fruit && o.fruitAdjustment) {
            sink_.setWanted({OrganKind::Fruit});
            for (std::size_t i = 0; i < fb.flowers.size(); ++i)
                clear(fb.flowers[i].clearance, top, place, i);
        }
    }

    const Worker& worker_;
    const World& world_;
    PlantInstance& plant_;
    ShapeSink sink_;
    std::unique_ptr<OrganPlacer> placer_;
    std::vector<std::vector<vec3>> nodes_;
    std::vector<unsigned> candidates_;
};

}  // namespace

void clearOrgans(const Worker& worker, const World& world, PlantInstance& plant) {
    if (!world.solid() || !world.hasSolid()) return;
    const SolidObstacleOptions& o = *world.solid();
    if (!o.organClearance && !o.fruitAdjustment) return;
    Clearer(worker, world, plant).run();
}

}  // namespace plantarch::collision
