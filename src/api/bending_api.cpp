// Shoots bending under load through the public API (plantarch/Bending.h): the solve itself is
// growth/bending.cpp; this file checks the arguments, measures the leaves from the plant's
// drawn geometry, finds the force a displacement takes and regenerates the geometry.

#include <cmath>
#include <string>
#include <vector>

#include "core/math.h"
#include "core/value_text.h"
#include "growth/bending.h"
#include "plantarch/Bending.h"
#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"

namespace plantarch {

namespace {

using glm::dvec3;

std::string shown(const vec3& v) {
    return text::formatFloat(v.x) + "," + text::formatFloat(v.y) + "," + text::formatFloat(v.z);
}

// The plant to bend. PlantArchitecture hands out its plants read-only; the bends are state
// this file owns (as growth does), set here and drawn by updateGeometry.
PlantInstance& plantToBend(PlantArchitecture& arch, unsigned plantID) {
    return const_cast<PlantInstance&>(arch.plant(plantID));
}

// Leaf areas as drawn (the sum of a leaf's objects' areas in the Context).
bending::LeafArea drawnLeafArea(const Context& ctx) {
    return [&ctx](const Phytomer&, const LeafOrgan& leaf) {
        double area = 0.0;
        for (ObjectID o : leaf.objects)
            if (ctx.doesObjectExist(o)) area += ctx.objectArea(o);
        return area;
    };
}

void checkNode(const PlantInstance& p, unsigned shootID, unsigned node) {
    if (shootID >= p.shoots.size() || p.shoots[shootID].removed)
        throw Error("no such shoot on the plant",
                    {.parameter = "shoot",
                     .value = std::to_string(shootID),
                     .validRange = p.shoots.empty() ? std::string("none: the plant has no shoots")
                                                    : "a shoot ID of the plant, 0 to " +
                                                          std::to_string(p.shoots.size() - 1) +
                                                          " (not pruned)"});
    const std::size_t n = p.shoots[shootID].phytomers.size();
    if (node >= n)
        throw Error("no such node on the shoot",
                    {.parameter = "node",
                     .value = std::to_string(node),
                     .validRange = n == 0 ? std::string("none: the shoot has no phytomers")
                                          : "0 to " + std::to_string(n - 1)});
}

void checkVector(const char* name, const vec3& v, float limit, const char* unit) {
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(v[i]) || std::abs(v[i]) > limit)
            throw Error(std::string("a ") + name + " component is not a finite number within range",
                        {.parameter = name,
                         .value = shown(v),
                         .validRange = "each component -" + text::formatFloat(limit) + " to " +
                                       text::formatFloat(limit) + " " + unit});
}

void checkSolved(const bending::Solution& s, const char* what, const vec3& v) {
    if (!s.converged)
        throw Error("the shoots find no equilibrium under that load",
                    {.parameter = what, .value = shown(v), .validRange = "a load they can carry"});
}

struct Bender {
    PlantArchitecture& arch;
    unsigned plantID;
    PlantInstance& plant;
    bending::LeafArea leafArea;

    Bender(PlantArchitecture& a, unsigned id)
        : arch(a), plantID(id), plant(plantToBend(a, id)), leafArea(drawnLeafArea(a.context())) {}

    bending::Solution solve(std::span<const bending::NodeForce> forces,
                            const bending::Solution& from) const {
        return bending::solve(plant, plant.phenology.mechanics, leafArea, forces, &from);
    }

    PullResult result(const bending::Solution& s, unsigned shootID, unsigned node, dvec3 force,
                      dvec3 reference) {
        bending::store(plant, s);
        arch.updateGeometry(plantID);
        PullResult r;
        const dvec3 at = s.nodes[shootID][node + 1];
        r.position = vec3(at);
        r.displacement = vec3(at - reference);
        r.force = vec3(force);
        r.nodeReaction = -r.force;
        r.baseForce = vec3(-s.baseForce[shootID]);
        r.baseMoment = vec3(-s.baseMoment[shootID]);
        dvec3 gf(0.0), gm(0.0);
        for (const Shoot& sh : plant.shoots)
            if (sh.parent < 0 && !sh.removed) {
                gf -= s.baseForce[sh.id];
                gm -= s.baseMoment[sh.id];
            }
        r.groundForce = vec3(gf);
        r.groundMoment = vec3(gm);
        r.iterations = s.iterations;
        return r;
    }
};

}  // namespace

void bendPlant(PlantArchitecture& arch, unsigned plantID) {
    Bender b(arch, plantID);
    const bending::Solution s = b.solve({}, bending::currentTurns(b.plant));
    checkSolved(s, "weight", vec3(0.0f));
    bending::store(b.plant, s);
    arch.updateGeometry(plantID);
}

void straightenPlant(PlantArchitecture& arch, unsigned plantID) {
    PlantInstance& p = plantToBend(arch, plantID);
    for (Shoot& s : p.shoots)
        for (Phytomer& ph : s.phytomers) ph.internode.bend.reset();
    arch.updateGeometry(plantID);
}

PullResult pullNode(PlantArchitecture& arch, unsigned plantID, unsigned shootID, unsigned node,
                    const vec3& force) {
    Bender b(arch, plantID);
    checkNode(b.plant, shootID, node);
    checkVector("force", force, 1e6f, "N");
    const bending::Solution rest = b.solve({}, bending::currentTurns(b.plant));
    checkSolved(rest, "weight", vec3(0.0f));
    const bending::NodeForce f{shootID, node, dvec3(force)};
    const bending::Solution s = b.solve({&f, 1}, rest);
    checkSolved(s, "force", force);
    return b.result(s, shootID, node, dvec3(force), rest.nodes[shootID][node + 1]);
}

PullResult displaceNode(PlantArchitecture& arch, unsigned plantID, unsigned shootID, unsigned node,
                        const vec3& displacement) {
    Bender b(arch, plantID);
    checkNode(b.plant, shootID, node);
    checkVector("displacement", displacement, 100.0f, "m");
    const bending::Solution rest = b.solve({}, bending::currentTurns(b.plant));
    checkSolved(rest, "weight", vec3(0.0f));
    const dvec3 reference = rest.nodes[shootID][node + 1];
    // Internodes do not stretch: the force is found across the pulled internode (its two
    // directions u, v perpendicular to it where the weight alone holds it), to move the node
    // by the displacement's part across it; along it the node goes where the bending takes it.
    const std::vector<dvec3>& at0 = rest.nodes[shootID];
    const dvec3 span = at0[node + 1] - at0[node];
    const dvec3 t =
        glm::length(span) > 1e-12
            ? glm::normalize(span)
            : glm::normalize(dvec3(b.plant.shoots[shootID].phytomers[node].internode.direction));
    const dvec3 u = glm::normalize(std::abs(t.z) < 0.9 ? glm::cross(dvec3(0, 0, 1), t)
                                                       : glm::cross(dvec3(1, 0, 0), t));
    const dvec3 v = glm::cross(t, u);
    const dvec3 target = reference + dvec3(displacement);
    const double tolerance = 1e-9 + 1e-6 * glm::length(dvec3(displacement));
    auto residualOf = [&](const bending::Solution& s) {
        const dvec3 miss = target - s.nodes[shootID][node + 1];
        return glm::dvec2(glm::dot(miss, u), glm::dot(miss, v));
    };
    auto solveWith = [&](glm::dvec2 f, const bending::Solution& from) {
        const bending::NodeForce nf{shootID, node, f.x * u + f.y * v};
        bending::Solution s = b.solve({&nf, 1}, from);
        checkSolved(s, "displacement", displacement);
        return s;
    };
    // The node's compliance across the internode (m per N), by finite differences from the
    // weight alone, each probe force moving it about 1e-4 of the displacement asked.
    const double want = std::max(1e-4 * glm::length(dvec3(displacement)), 1e-9);
    const glm::dvec2 r0 = residualOf(rest);
    glm::dmat2 J(0.0);  // d(position across) / d(force across)
    for (int k = 0; k < 2; ++k) {
        double h = 1e-3;
        for (int tries = 0; tries < 4; ++tries) {
            glm::dvec2 probe(0.0);
            probe[k] = h;
            const glm::dvec2 moved = r0 - residualOf(solveWith(probe, rest));
            J[k] = moved / h;
            const double len = glm::length(moved);
            if (len > 0.1 * want && len < 10.0 * want) break;
            h = len > 0.0 ? std::clamp(h * want / len, 1e-12, 1e6) : h * 1e3;
        }
    }
    // Newton steps on the force, the compliance updated by Broyden's rule.
    glm::dvec2 f(0.0);
    bending::Solution s = rest;
    glm::dvec2 residual = r0;
    for (int it = 0; it < 60 && glm::length(residual) > tolerance; ++it) {
        if (!(std::abs(glm::determinant(J)) > 0.0)) break;
        const glm::dvec2 df = glm::inverse(J) * residual;
        if (!(glm::length(f + df) < 1e7)) break;
        s = solveWith(f + df, s);
        f += df;
        const glm::dvec2 next = residualOf(s);
        J += glm::outerProduct((residual - next) - J * df, df) / glm::dot(df, df);
        residual = next;
    }
    if (!(glm::length(residual) <= tolerance))
        throw Error("the shoots cannot bend to move the node so",
                    {.parameter = "displacement",
                     .value = shown(displacement),
                     .validRange = "a displacement within the shoots' reach"});
    const dvec3 force = f.x * u + f.y * v;
    return b.result(s, shootID, node, force, reference);
}

std::vector<vec3> bentNodePositions(const PlantArchitecture& arch, unsigned plantID,
                                    unsigned shootID) {
    const PlantInstance& p = arch.plant(plantID);
    checkNode(p, shootID, 0);
    // Down to the base stem, then up: each shoot from its parent's node, as tessellation
    // places it (the same float arithmetic).
    std::vector<unsigned> chain{shootID};
    while (p.shoots[chain.back()].parent >= 0)
        chain.push_back(unsigned(p.shoots[chain.back()].parent));
    std::vector<vec3> nodes;
    vec3 base = p.base;
    for (std::size_t k = chain.size(); k-- > 0;) {
        const Shoot& s = p.shoots[chain[k]];
        if (k + 1 < chain.size())
            base = nodes[std::min<std::size_t>(std::size_t(std::max(s.parentNode, 0)) + 1,
                                               nodes.size() - 1)];
        nodes.assign(1, base);
        for (const Phytomer& ph : s.phytomers) {
            const Internode& in = ph.internode;
            vec3 d = in.direction;
            if (in.bend && in.bend->angle != 0.0f)
                d = unitOr(rotateAbout(d, in.bend->axis, in.bend->angle * kDeg), d);
            nodes.push_back(nodes.back() + d * in.length * ph.internodeFraction);
        }
    }
    return nodes;
}

}  // namespace plantarch
