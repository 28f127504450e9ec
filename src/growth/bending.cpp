// Shoots bending under load: a geometrically exact chain of elastic joints, solved by a
// damped fixed point (docs/measured-plants.md, "Shoots bending under load").
//
// Each internode is a straight rigid segment; its flexibility, integral of ds / EI over the
// rod, is lumped into the joints at its ends: joint i (node i, the base of internode i) takes
// the compliance of the half internodes on either side of it (the first joint, at the shoot's
// base, the lower half of the first internode only). Joint i turns the shoot above it, in
// world coordinates, by c_i M_i, M_i the moment about node i of every load above it
// (internode weights at their middles, node loads, the shoots growing from those nodes, outside
// forces), taken from the deformed positions, less its component along the shoot (torsion is
// not modelled: internodes are torsionally rigid). That is the midpoint rule of the elastica,
// exact as the internodes get short (second order in their length), for large turns as well as
// small. A shoot's base joint is clamped to the internode it grows from (the ground for a base
// stem), so a parent carries its children's weight and turns them with it.

#include "growth/bending.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/quaternion.hpp>
#include <numbers>

#include "core/math.h"

namespace plantarch::bending {

namespace {

using glm::dquat;
using glm::dvec3;

const dvec3 kDown{0.0, 0.0, -1.0};
constexpr unsigned kMaxIterations = 5000;
constexpr double kTolerance = 1e-11;  // radians, largest change of a joint turn

dquat turnOf(dvec3 w) {
    const double a = glm::length(w);
    if (a < 1e-300) return dquat(1.0, 0.0, 0.0, 0.0);
    return glm::angleAxis(a, w / a);
}

dvec3 vectorOf(dquat q) {
    if (q.w < 0.0) q = -q;
    const dvec3 v(q.x, q.y, q.z);
    const double s = glm::length(v);
    if (s < 1e-300) return dvec3(0.0);
    return v / s * (2.0 * std::atan2(s, q.w));
}

// One shoot as rods.
struct Rod {
    unsigned id = 0;
    int parent = -1;      // index of the parent's rod, -1: the ground
    unsigned attach = 0;  // the parent's internode it grows from (its top node)
    std::vector<dvec3> rest;
    std::vector<double> length, compliance;
    std::vector<dvec3> weight;  // each internode's own weight (at its middle)
    std::vector<dvec3> load;    // at node i + 1 (the top of internode i)
    std::vector<std::pair<unsigned, unsigned>> children;  // (rod, internode), by internode
    std::vector<dvec3> theta;                             // joint turns (world rotation vectors)
    std::vector<dquat> q;                                 // whole turn of each internode
    std::vector<dvec3> pos;                               // nodes 0..n
    std::vector<dvec3> moment;
    dvec3 force{0.0}, baseMoment{0.0};
};

double tubeMass(double density, double radius, double length) {
    return density * std::numbers::pi * radius * radius * length;
}

// What a node's organs weigh, N (downward).
double nodeWeight(const MechanicsParameters& m, const LeafArea& leafArea, const Phytomer& ph) {
    double mass = 0.0;
    auto floral = [&](const FloralBud& fb) {
        const bool visible = fb.stage == FloralStage::FlowerClosed ||
                             fb.stage == FloralStage::FlowerOpen || fb.stage == FloralStage::Fruit;
        if (!visible) return;
        mass += tubeMass(m.stem_density, fb.peduncleRadius, fb.peduncleLength);
        for (const FlowerOrgan& fl : fb.flowers) {
            const double size = currentFloralSize(fb, fl);
            if (fb.stage == FloralStage::Fruit)
                mass += m.fruit_density * std::numbers::pi / 6.0 * size * size * size;
            else
                mass += m.leaf_mass_per_area * size * size;
        }
    };
    for (const Petiole& pt : ph.petioles) {
        const bool bare =
            !pt.leaves.empty() && std::all_of(pt.leaves.begin(), pt.leaves.end(),
                                              [](const LeafOrgan& l) { return l.removed; });
        if (!bare)
            mass += tubeMass(m.stem_density, double(pt.radius) * ph.leafFraction,
                             double(pt.length) * ph.leafFraction);
        for (const LeafOrgan& l : pt.leaves)
            if (!l.removed && hasSize(currentLeafSize(ph, l)))
                mass += m.leaf_mass_per_area * leafArea(ph, l);
        for (const FloralBud& fb : pt.floralBuds) floral(fb);
    }
    return mass * kGravity;
}

struct Solver {
    const PlantInstance& plant;
    const MechanicsParameters& m;
    std::vector<Rod> rods;   // parents before children
    std::vector<int> rodOf;  // shoot ID -> rod, -1: none
    std::vector<dvec3> jointsScratch;

    void build(const LeafArea& leafArea, std::span<const NodeForce> forces) {
        // Parents before children: breadth first from the base stems.
        rodOf.assign(plant.shoots.size(), -1);
        std::vector<unsigned> order;
        for (const Shoot& s : plant.shoots)
            if (s.parent < 0 && !s.removed) order.push_back(s.id);
        for (std::size_t k = 0; k < order.size(); ++k)
            for (unsigned c : plant.shoots[order[k]].children)
                if (c < plant.shoots.size() && !plant.shoots[c].removed &&
                    plant.shoots[c].parent == int(order[k]))
                    order.push_back(c);
        const double E = m.elastic_modulus;
        for (unsigned id : order) {
            const Shoot& s = plant.shoots[id];
            Rod r;
            r.id = id;
            if (s.parent >= 0) {
                const int p = rodOf[unsigned(s.parent)];
                if (p < 0 || rods[unsigned(p)].rest.empty()) continue;
                r.parent = p;
                r.attach = std::min<unsigned>(unsigned(std::max(s.parentNode, 0)),
                                              unsigned(rods[unsigned(p)].rest.size()) - 1);
            }
            const std::size_t n = s.phytomers.size();
            r.rest.resize(n);
            r.length.resize(n);
            r.compliance.assign(n, 0.0);
            r.weight.resize(n);
            r.load.resize(n);
            std::vector<double> half(n, 0.0);  // length / (2 E I) of each internode
            for (std::size_t i = 0; i < n; ++i) {
                const Phytomer& ph = s.phytomers[i];
                const Internode& in = ph.internode;
                r.rest[i] = glm::normalize(dvec3(in.direction));
                r.length[i] = double(in.length) * ph.internodeFraction;
                const double radius = in.radius;
                r.weight[i] = kDown * (tubeMass(m.stem_density, radius, r.length[i]) * kGravity);
                r.load[i] = kDown * nodeWeight(m, leafArea, ph);
                // A measured internode is held as measured (its shape is the loaded one):
                // it adds no flexibility to the joints on either side.
                if (radius > 0.0 && r.length[i] > 0.0 && !ph.measured) {
                    const double I = std::numbers::pi / 4.0 * radius * radius * radius * radius;
                    half[i] = r.length[i] / (2.0 * E * I);
                }
            }
            for (std::size_t i = 0; i < n; ++i)
                r.compliance[i] = half[i] + (i > 0 ? half[i - 1] : 0.0);
            if (n > 0)
                for (const FloralBud& fb : s.terminalFloralBuds) {
                    Phytomer tip;  // the terminal buds' weight, on the last node
                    tip.petioles.resize(1);
                    tip.petioles[0].floralBuds.push_back(fb);
                    r.load[n - 1] += kDown * nodeWeight(m, leafArea, tip);
                }
            r.theta.assign(n, dvec3(0.0));
            r.q.assign(n, dquat(1.0, 0.0, 0.0, 0.0));
            r.pos.assign(n + 1, dvec3(0.0));
            r.moment.assign(n, dvec3(0.0));
            if (n == 0) continue;  // nothing to carry or bend
            rodOf[id] = int(rods.size());
            if (r.parent >= 0)
                rods[unsigned(r.parent)].children.push_back({unsigned(rods.size()), r.attach});
            rods.push_back(std::move(r));
        }
        for (Rod& r : rods)
            std::stable_sort(r.children.begin(), r.children.end(),
                             [](const auto& a, const auto& b) { return a.second < b.second; });
        for (const NodeForce& f : forces) {
            const int k = f.shoot < rodOf.size() ? rodOf[f.shoot] : -1;
            if (k >= 0 && f.node < rods[unsigned(k)].load.size())
                rods[unsigned(k)].load[f.node] += f.force;
        }
    }

    void start(const Solution& from) {
        for (Rod& r : rods) {
            if (r.id >= from.turns.size()) continue;
            const std::vector<dvec3>& t = from.turns[r.id];
            dquat below = r.parent >= 0 && r.attach < from.turns[rods[unsigned(r.parent)].id].size()
                              ? turnOf(from.turns[rods[unsigned(r.parent)].id][r.attach])
                              : dquat(1.0, 0.0, 0.0, 0.0);
            for (std::size_t i = 0; i < r.theta.size() && i < t.size(); ++i) {
                const dquat q = turnOf(t[i]);
                r.theta[i] = vectorOf(q * glm::inverse(below));
                below = q;
            }
        }
    }

    void place() {
        for (Rod& r : rods) {
            dquat below(1.0, 0.0, 0.0, 0.0);
            r.pos[0] = dvec3(plant.base);
            if (r.parent >= 0) {
                const Rod& p = rods[unsigned(r.parent)];
                below = p.q[r.attach];
                r.pos[0] = p.pos[r.attach + 1];
            }
            for (std::size_t i = 0; i < r.rest.size(); ++i) {
                r.q[i] = glm::normalize(turnOf(r.theta[i]) * below);
                r.pos[i + 1] = r.pos[i] + (r.q[i] * r.rest[i]) * r.length[i];
                below = r.q[i];
            }
        }
    }

    void moments() {
        for (std::size_t k = rods.size(); k-- > 0;) {
            Rod& r = rods[k];
            dvec3 F(0.0), M(0.0);
            std::size_t c = r.children.size();
            for (std::size_t i = r.rest.size(); i-- > 0;) {
                // What node i + 1 carries (M is about it here).
                F += r.load[i];
                while (c > 0 && r.children[c - 1].second == i) {
                    const Rod& child = rods[r.children[--c].first];
                    F += child.force;
                    M += child.baseMoment;
                }
                const dvec3 arm = r.pos[i + 1] - r.pos[i];
                M += glm::cross(arm, F) + glm::cross(0.5 * arm, r.weight[i]);
                F += r.weight[i];
                r.moment[i] = M;
            }
            r.force = F;
            r.baseMoment = M;
        }
    }

    // One damped step toward the joints' equilibrium turns; the largest change it asked for.
    double step(double omega) {
        double residual = 0.0;
        for (Rod& r : rods)
            for (std::size_t i = 0; i < r.rest.size(); ++i) {
                dvec3 t = r.q[i] * r.rest[i];
                if (i > 0) t = glm::normalize(t + r.q[i - 1] * r.rest[i - 1]);
                const dvec3 bending = r.moment[i] - glm::dot(r.moment[i], t) * t;
                const dvec3 change = r.compliance[i] * bending - r.theta[i];
                residual = std::max(residual, glm::length(change));
                r.theta[i] += omega * change;
            }
        return residual;
    }
};

}  // namespace

Solution solve(const PlantInstance& plant, const MechanicsParameters& mechanics,
               const LeafArea& leafArea, std::span<const NodeForce> forces, const Solution* start) {
    Solver s{plant, mechanics, {}, {}, {}};
    s.build(leafArea, forces);
    if (start) s.start(*start);
    Solution out;
    double omega = 1.0, last = std::numeric_limits<double>::infinity();
    for (out.iterations = 0; out.iterations < kMaxIterations; ++out.iterations) {
        s.place();
        s.moments();
        const double residual = s.step(omega);
        if (!std::isfinite(residual)) break;
        if (residual < kTolerance) {
            out.converged = true;
            break;
        }
        // Damping: halved when the change grows (the turns overshoot), raised while it shrinks.
        omega = residual > last ? std::max(omega * 0.5, 0.02) : std::min(omega * 1.1, 1.0);
        last = residual;
    }
    s.place();
    s.moments();
    const std::size_t n = plant.shoots.size();
    out.nodes.resize(n);
    out.turns.resize(n);
    out.baseForce.assign(n, dvec3(0.0));
    out.baseMoment.assign(n, dvec3(0.0));
    for (const Rod& r : s.rods) {
        out.nodes[r.id] = r.pos;
        out.baseForce[r.id] = r.force;
        out.baseMoment[r.id] = r.baseMoment;
        out.turns[r.id].resize(r.q.size());
        for (std::size_t i = 0; i < r.q.size(); ++i) out.turns[r.id][i] = vectorOf(r.q[i]);
    }
    return out;
}

void store(PlantInstance& plant, const Solution& solution) {
    for (Shoot& s : plant.shoots)
        for (std::size_t i = 0; i < s.phytomers.size(); ++i) {
            Internode& in = s.phytomers[i].internode;
            const bool has = s.id < solution.turns.size() && i < solution.turns[s.id].size();
            const dvec3 w = has ? solution.turns[s.id][i] : dvec3(0.0);
            const double a = glm::length(w);
            if (!has || !std::isfinite(a)) {  // a solve that failed bends nothing
                in.bend.reset();
                continue;
            }
            InternodeBend b;
            if (a > 0.0 && std::isfinite(a)) {
                b.axis = vec3(w / a);
                b.angle = float(a * 180.0 / std::numbers::pi);
            }
            in.bend = b;
        }
}

LeafArea prototypeLeafArea(const PlantStore& store, PrototypeCache& prototypes,
                           PlantInstance& plant) {
    return [&store, &prototypes, &plant](const Phytomer& ph, const LeafOrgan& leaf) {
        const LeafParameters& lp =
            store.shootTypeFor(plant, ph.parametersLabel).phytomer_parameters.leaf;
        const double size = currentLeafSize(ph, leaf);
        return prototypes.leafPrototypeArea(lp, leaf) * size * size;
    };
}

void bendPlant(const PlantStore& store, PrototypeCache& prototypes, PlantInstance& plant) {
    const Solution from = currentTurns(plant);
    bending::store(plant, solve(plant, plant.phenology.mechanics,
                                prototypeLeafArea(store, prototypes, plant), {}, &from));
}

Solution currentTurns(const PlantInstance& plant) {
    Solution out;
    out.turns.resize(plant.shoots.size());
    for (const Shoot& s : plant.shoots)
        for (const Phytomer& ph : s.phytomers) {
            const std::optional<InternodeBend>& b = ph.internode.bend;
            out.turns[s.id].push_back(b ? dvec3(glm::normalize(b->axis)) * radians(double(b->angle))
                                        : dvec3(0.0));
        }
    return out;
}

}  // namespace plantarch::bending
