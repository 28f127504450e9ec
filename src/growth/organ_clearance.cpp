// Clearance of side organs: petioles with their leaves and peduncles with their flowers, and
// fruit one by one. An organ that crosses an obstacle, or goes below its plant's ground, is
// turned about its attachment point away from it in 10-degree steps until clear, then back
// toward it one degree at a time while still clear. The turn is recomputed from the unturned
// organ at the end of every growth step, so it is a function of the plant's shape alone,
// whatever the step size. Internodes are never turned here.
//
// The ground is the plane z = the plant's base z, tested analytically against the organ's own
// vertices (leaves, flowers and fruit exactly; a petiole or peduncle tube may reach its base
// radius below it, as a stem resting on the soil does). Stems themselves are kept above it as
// they grow (shoot_builder.cpp): a stem that meets the ground lies along it. Organs whose reach
// from their node cannot touch an obstacle are never placed, so a plant high above its ground pays
// only for its node positions.

#include "growth/organ_clearance.h"

#include <algorithm>
#include <optional>

#include "core/math.h"

namespace plantarch {

// ---- trial sink --------------------------------------------------------------------------

void TrialSink::setWanted(std::initializer_list<OrganKind> kinds) {
    std::fill(std::begin(kinds_), std::end(kinds_), false);
    for (OrganKind k : kinds) kinds_[int(k)] = true;
}

void TrialSink::write(ObjectID&, const Mesh& mesh, const Material&, const OrganLabels&) {
    for (std::uint32_t i : mesh.indices) triangles.push_back(mesh.positions[i]);
}

void TrialSink::writeParts(std::vector<ObjectID>& objects, const OrganPrototype& prototype,
                           const mat4& transform, const OrganLabels&) {
    parts.push_back({&prototype, transform, &objects});
}

void TrialSink::clear() {
    triangles.clear();
    parts.clear();
}

void TrialSink::keepOnly(const std::vector<ObjectID>* owner) {
    triangles.clear();
    std::erase_if(parts, [&](const Part& p) { return p.owner != owner; });
}

namespace {

// Overlap of less than this counts as touching, not crossing (m).
constexpr float kTolerance = 1e-5f;

// The ground below a plant: the plane z = `z`, with up as its normal.
class GroundPlane final : public OrganObstacle {
public:
    explicit GroundPlane(float z) : z_(z) {}

    bool near(vec3 p, float reach) override { return p.z - reach <= z_; }

    bool crosses(const TrialSink& trial) override {
        const float tubeFloor = std::min(z_, trial.tubeStart.z) - trial.tubeRadius - kTolerance;
        for (const vec3& q : trial.triangles)
            if (q.z < tubeFloor) return true;
        const float floor = z_ - kTolerance;
        for (const TrialSink::Part& part : trial.parts) {
            // z of transform x (p, 1): the third row of the column-major matrix.
            const mat4& m = part.transform;
            for (const PrototypePart& piece : *part.prototype)
                for (const vec3& p : piece.mesh.positions)
                    if (m[0][2] * p.x + m[1][2] * p.y + m[2][2] * p.z + m[3][2] < floor)
                        return true;
        }
        return false;
    }

    // First about the horizontal axis across the direction from the attachment to the organ's
    // middle, so that the organ rises; then about the horizontal axes 45, 90, ... 315 degrees
    // from it (an organ held sideways, such as a flower facing down at right angles to its
    // peduncle along a stem on the ground, clears by rolling about its reach).
    void turnAxes(const TrialSink& trial, vec3 attachment, std::vector<vec3>& axes) override {
        AABB bounds;
        for (const vec3& q : trial.triangles) bounds.add(q);
        for (const TrialSink::Part& part : trial.parts)
            for (const PrototypePart& piece : *part.prototype)
                for (const vec3& p : piece.mesh.positions)
                    bounds.add(vec3(part.transform * glm::vec4(p, 1.0f)));
        const vec3 up(0.0f, 0.0f, 1.0f);
        const vec3 out = bounds.empty() ? up : bounds.center() - attachment;
        const vec3 cross = glm::cross(out, up);
        const vec3 axis = glm::length(cross) > 1e-4f * glm::length(out) ? glm::normalize(cross)
                                                                        : anyPerpendicular(up);
        axes.clear();
        for (int k = 0; k < 8; ++k) axes.push_back(rotateAbout(axis, up, float(k) * 45.0f * kDeg));
    }

private:
    float z_;
};

// Visits the side organs of every shoot of the plant that is there, with its node positions
// from `placer`: shoot(s, nodes) once per shoot, then petiole(s, k, j, petiole, phytomer,
// top) for each petiole and bud(s, k, j, b, terminal, bud, top, stemRadius) for each of its
// floral buds, then the shoot's terminal floral buds (`top` the node the organ hangs from).
template <class ShootFn, class PetioleFn, class BudFn>
void forEachSideOrgan(PlantInstance& plant, OrganPlacer& placer, ShootFn&& shoot,
                      PetioleFn&& petiole, BudFn&& bud) {
    for (Shoot& s : plant.shoots) {
        if (s.removed) continue;
        const std::vector<vec3>& nodes = placer.nodes(s.id);
        shoot(s, nodes);
        for (unsigned k = 0; k < s.phytomers.size(); ++k) {
            Phytomer& ph = s.phytomers[k];
            const vec3 top = nodes[k + 1];
            for (unsigned j = 0; j < ph.petioles.size(); ++j) {
                Petiole& pt = ph.petioles[j];
                petiole(s, k, j, pt, ph, top);
                for (unsigned b = 0; b < pt.floralBuds.size(); ++b)
                    bud(s, k, j, b, false, pt.floralBuds[b], top, ph.internode.radius);
            }
        }
        if (s.phytomers.empty()) continue;
        const float radius = s.phytomers.back().internode.radius;
        for (unsigned b = 0; b < s.terminalFloralBuds.size(); ++b)
            bud(s, 0u, 0u, b, true, s.terminalFloralBuds[b], nodes.back(), radius);
    }
}

class Clearer {
public:
    Clearer(const PlantStore& store, PrototypeCache& prototypes, PlantInstance& plant,
            std::span<OrganObstacle* const> obstacles, ClearanceCounts& counts)
        : placer_(store, prototypes, plant, 1.0f), plant_(plant), counts_(counts) {
        if (plant.groundClearance) ground_.emplace(plant.base.z);
        obstacles_.assign(obstacles.begin(), obstacles.end());
        if (ground_) obstacles_.push_back(&*ground_);
    }

    void run() {
        forEachSideOrgan(
            plant_, placer_, [](Shoot&, const std::vector<vec3>&) {},
            [&](Shoot& s, unsigned k, unsigned j, Petiole& pt, Phytomer& ph, vec3 top) {
                clearPetiole(s, k, j, pt, ph, top);
            },
            [&](Shoot& s, unsigned k, unsigned j, unsigned b, bool terminal, FloralBud& fb,
                vec3 top,
                float stemRadius) { clearBud(s, k, j, b, terminal, fb, top, stemRadius); });
    }

private:
    enum class Kind { Organ, Flower, Fruit };
    // The obstacles that keep organs of this kind out and that an organ attached at `top`
    // reaching `reach` may touch.
    std::span<OrganObstacle* const> nearOnes(vec3 top, float reach, Kind kind) {
        near_.clear();
        for (OrganObstacle* o : obstacles_) {
            const bool keeps = kind == Kind::Organ    ? o->organs
                               : kind == Kind::Flower ? o->flowers
                                                      : o->fruit;
            if (keeps && o->near(top, reach)) near_.push_back(o);
        }
        return near_;
    }

    // Finds the smallest turn (whole degrees) that keeps the organ placed by `place` (only the
    // parts of `owner`, when given) out of `obstacles`.
    template <class Place>
    void clear(OrganTurn& turn, vec3 attachment, const Place& place,
               const std::vector<ObjectID>* owner, std::span<OrganObstacle* const> obstacles) {
        turn = OrganTurn{};
        auto crossed = [&]() -> OrganObstacle* {
            trial_.clear();
            place();
            if (owner) trial_.keepOnly(owner);
            for (OrganObstacle* o : obstacles)
                if (o->crosses(trial_)) return o;
            return nullptr;
        };
        OrganObstacle* first = crossed();
        if (!first) return;
        first->turnAxes(trial_, attachment, axes_);
        for (const vec3& axis : axes_) {
            turn.axis = axis;
            for (int angle = 10; angle <= 180; angle += 10) {
                turn.angle = float(angle);
                if (crossed()) continue;
                // Back toward the obstacle while still clear.
                for (int back = angle - 1; back > angle - 10; --back) {
                    turn.angle = float(back);
                    if (crossed()) {
                        turn.angle = float(back + 1);
                        break;
                    }
                }
                ++counts_.turned;
                return;
            }
        }
        turn = OrganTurn{};
        ++counts_.unresolved;
    }

    void clearPetiole(Shoot& s, unsigned k, unsigned j, Petiole& pt, const Phytomer& ph, vec3 top) {
        pt.clearance = OrganTurn{};
        float leaf = 0.0f;
        for (const LeafOrgan& l : pt.leaves) leaf = std::max(leaf, l.scale);
        // The petiole starts half its internode's radius off the node.
        const float reach = (pt.length + 1.5f * leaf) * ph.leafFraction + pt.radius +
                            0.5f * ph.internode.radius + 0.01f;
        const auto obstacles = nearOnes(top, reach, Kind::Organ);
        if (obstacles.empty()) return;
        trial_.setWanted({OrganKind::Petiole, OrganKind::Leaf});
        trial_.tubeStart = placer_.petioleStart(s.id, k, j);
        trial_.tubeRadius = pt.radius * ph.leafFraction;
        clear(
            pt.clearance, top, [&] { placer_.petiole(trial_, s.id, k, j); }, nullptr, obstacles);
    }

    void clearBud(Shoot& s, unsigned k, unsigned j, unsigned b, bool terminal, FloralBud& fb,
                  vec3 top, float stemRadius) {
        fb.peduncleClearance = OrganTurn{};
        for (FlowerOrgan& fl : fb.flowers) fl.clearance = OrganTurn{};
        const bool fruit = fb.stage == FloralStage::Fruit;
        const bool flower =
            fb.stage == FloralStage::FlowerClosed || fb.stage == FloralStage::FlowerOpen;
        if (!fruit && !flower) return;
        float organ = 0.0f;
        for (const FlowerOrgan& fl : fb.flowers)
            organ = std::max({organ, fl.flowerScale, fl.fruitScale});
        const float reach =
            fb.peduncleLength + 1.5f * organ + fb.peduncleRadius + stemRadius + 0.01f;
        auto place = [&] { placer_.floralBud(trial_, s.id, k, j, b, terminal); };
        if (const auto obstacles = nearOnes(top, reach, Kind::Organ); !obstacles.empty()) {
            trial_.setWanted({OrganKind::Peduncle, OrganKind::FlowerClosed, OrganKind::FlowerOpen});
            trial_.tubeStart = top;
            trial_.tubeRadius = fb.peduncleRadius;
            clear(fb.peduncleClearance, top, place, nullptr, obstacles);
        }
        // Then each flower or fruit on its own, about its place on the (turned) peduncle.
        const auto obstacles = nearOnes(top, reach, fruit ? Kind::Fruit : Kind::Flower);
        if (obstacles.empty()) return;
        if (fruit)
            trial_.setWanted({OrganKind::Fruit});
        else
            trial_.setWanted({OrganKind::FlowerClosed, OrganKind::FlowerOpen});
        for (FlowerOrgan& fl : fb.flowers) clear(fl.clearance, top, place, &fl.objects, obstacles);
    }

    OrganPlacer placer_;
    PlantInstance& plant_;
    ClearanceCounts& counts_;
    std::optional<GroundPlane> ground_;
    std::vector<OrganObstacle*> obstacles_, near_;
    std::vector<vec3> axes_;
    TrialSink trial_;
};

// No obstacle: no organ is turned.
void resetTurns(PlantInstance& plant) {
    auto reset = [](FloralBud& fb) {
        fb.peduncleClearance = OrganTurn{};
        for (FlowerOrgan& fl : fb.flowers) fl.clearance = OrganTurn{};
    };
    for (Shoot& s : plant.shoots) {
        for (Phytomer& ph : s.phytomers)
            for (Petiole& pt : ph.petioles) {
                pt.clearance = OrganTurn{};
                for (FloralBud& fb : pt.floralBuds) reset(fb);
            }
        for (FloralBud& fb : s.terminalFloralBuds) reset(fb);
    }
}

// Ground clipping: what reaches below z = height goes (growth.h, clipBelowGround).
class Clipper {
public:
    Clipper(const PlantStore& store, PrototypeCache& prototypes, PlantInstance& plant, float height)
        : placer_(store, prototypes, plant, 1.0f), plant_(plant), height_(height) {}

    bool run() {
        forEachSideOrgan(
            plant_, placer_,
            [&](Shoot& s, const std::vector<vec3>& nodes) {
                if (s.rank > 0 && s.apicalBud.state != BudState::Dead &&
                    std::any_of(nodes.begin() + 1, nodes.end(),
                                [&](const vec3& p) { return p.z < height_; })) {
                    s.apicalBud.state = BudState::Dead;
                    s.nextPhytomerTime = -1.0;
                    changed_ = true;
                }
            },
            [&](Shoot& s, unsigned k, unsigned j, Petiole& pt, Phytomer& ph, vec3 top) {
                clipLeaves(s, k, j, pt, ph, top);
            },
            [&](Shoot& s, unsigned k, unsigned j, unsigned b, bool terminal, FloralBud& fb,
                vec3 top, float) { clipBud(s, k, j, b, terminal, fb, top); });
        return changed_;
    }

private:
    bool below(const TrialSink::Part& part) const {
        const mat4& m = part.transform;  // z of m x (p, 1): the third row
        for (const PrototypePart& piece : *part.prototype)
            for (const vec3& p : piece.mesh.positions)
                if (m[0][2] * p.x + m[1][2] * p.y + m[2][2] * p.z + m[3][2] < height_) return true;
        return false;
    }

    void clipLeaves(Shoot& s, unsigned k, unsigned j, Petiole& pt, const Phytomer& ph, vec3 top) {
        float leaf = 0.0f;
        for (const LeafOrgan& l : pt.leaves) leaf = std::max(leaf, l.scale);
        const float reach = (pt.length + 1.5f * leaf) * ph.leafFraction + pt.radius +
                            0.5f * ph.internode.radius + 0.01f;
        if (top.z - reach > height_) return;
        trial_.clear();
        trial_.setWanted({OrganKind::Leaf});
        placer_.petiole(trial_, s.id, k, j);
        for (LeafOrgan& l : pt.leaves) {
            if (l.removed) continue;
            for (const TrialSink::Part& part : trial_.parts)
                if (part.owner == &l.objects && below(part)) {
                    l.removed = true;
                    changed_ = true;
                    break;
                }
        }
    }

    void clipBud(Shoot& s, unsigned k, unsigned j, unsigned b, bool terminal, FloralBud& fb,
                 vec3 top) {
        if (fb.stage != FloralStage::FlowerClosed && fb.stage != FloralStage::FlowerOpen &&
            fb.stage != FloralStage::Fruit)
            return;
        float organ = 0.0f;
        for (const FlowerOrgan& fl : fb.flowers)
            organ = std::max({organ, fl.flowerScale, fl.fruitScale});
        if (top.z - (fb.peduncleLength + 1.5f * organ + fb.peduncleRadius + 0.01f) > height_)
            return;
        trial_.clear();
        trial_.setWanted({OrganKind::Peduncle, OrganKind::FlowerClosed, OrganKind::FlowerOpen,
                          OrganKind::Fruit});
        placer_.floralBud(trial_, s.id, k, j, b, terminal);
        const bool clipped = std::any_of(trial_.triangles.begin(), trial_.triangles.end(),
                                         [&](const vec3& p) { return p.z < height_; }) ||
                             std::any_of(trial_.parts.begin(), trial_.parts.end(),
                                         [&](const TrialSink::Part& part) { return below(part); });
        if (!clipped) return;
        fb.stage = FloralStage::Removed;
        fb.state = BudState::Dead;
        fb.nextTime = -1.0;
        changed_ = true;
    }

    OrganPlacer placer_;
    PlantInstance& plant_;
    float height_;
    TrialSink trial_;
    bool changed_ = false;
};

}  // namespace

bool clipBelowGround(const PlantStore& store, PrototypeCache& prototypes, PlantInstance& plant,
                     float height) {
    return Clipper(store, prototypes, plant, height).run();
}

void clearSideOrgans(const PlantStore& store, PrototypeCache& prototypes, PlantInstance& plant,
                     std::span<OrganObstacle* const> obstacles, ClearanceCounts* counts) {
    if (obstacles.empty() && !plant.groundClearance) return resetTurns(plant);
    ClearanceCounts ignored;
    Clearer(store, prototypes, plant, obstacles, counts ? *counts : ignored).run();
}

}  // namespace plantarch
