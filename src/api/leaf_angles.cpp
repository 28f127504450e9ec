// Leaf angles of plants and canopies, and the distributions leaves draw from
// (plantarch/LeafAngles.h).

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "core/value_text.h"
#include "model/leaf_angle_distribution.h"
#include "plantarch/Error.h"
#include "plantarch/LeafAngles.h"
#include "plantarch/ParameterCheck.h"
#include "plantarch/ParameterTable.h"
#include "plantarch/PlantArchitecture.h"

namespace plantarch {

namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;

void checkEdges(const std::vector<double>& edges) {
    auto fail = [&](std::size_t i, const std::string& why) {
        throw Error(why, {.parameter = "edges[" + std::to_string(i) + "]",
                          .value = i < edges.size() ? text::formatDouble(edges[i]) : "",
                          .validRange = "increasing, from 0 to 90 degrees, at least two"});
    };
    if (edges.size() < 2) fail(edges.size(), "a histogram needs at least two edges");
    for (std::size_t i = 0; i < edges.size(); ++i) {
        if (!(edges[i] >= 0.0 && edges[i] <= 90.0)) fail(i, "a bin edge is out of range");
        if (i > 0 && !(edges[i] > edges[i - 1])) fail(i, "bin edges must increase");
    }
}

// Every field of `p` in its declared range, then the checks across them.
struct AngleFieldCheck {
    template <class T>
    void field(const params::FieldInfo& f, const T& member) const {
        params::checkField(f, "leaf_angles", member);
    }
};

void checkParameters(const LeafAngleParameters& p) {
    const AngleFieldCheck check;
    params::describeParameters(p, check);
    leaf_angles::check(p, "leaf_angles");
}

// The bin of an inclination, or -1 outside every bin.
int binOf(const std::vector<double>& edges, double angle) {
    if (angle < edges.front() || angle > edges.back()) return -1;
    const auto it = std::upper_bound(edges.begin(), edges.end(), angle);
    const std::size_t i = std::size_t(it - edges.begin());
    return int(std::min(i, edges.size() - 1)) - 1;
}

}  // namespace

std::vector<double> defaultInclinationEdges() {
    std::vector<double> edges;
    for (int i = 0; i <= 9; ++i) edges.push_back(10.0 * i);
    return edges;
}

LeafInclinationHistogram leafInclinationHistogram(const PlantArchitecture& arch,
                                                  const std::vector<unsigned>& plantIDs,
                                                  const std::vector<double>& edges) {
    checkEdges(edges);
    const Context& ctx = arch.context();
    LeafInclinationHistogram h;
    h.edges = edges;
    std::vector<double> area(edges.size() - 1, 0.0);
    double total = 0.0, weighted = 0.0;
    for (unsigned plantID : plantIDs) {
        for (ObjectID id : arch.getPlantObjectIDs(plantID, OrganKind::Leaf)) {
            const ObjectView o = ctx.object(id);
            for (std::size_t t = 0; t + 2 < o.indices.size(); t += 3) {
                const glm::dvec3 a = o.positions[o.indices[t]], b = o.positions[o.indices[t + 1]],
                                 c = o.positions[o.indices[t + 2]];
                const glm::dvec3 n = glm::cross(b - a, c - a);
                const double twice = glm::length(n);
                if (!(twice > 0.0)) continue;
                const double angle = std::acos(std::min(1.0, std::abs(n.z) / twice)) * kDegPerRad;
                const double s = 0.5 * twice;
                total += s;
                weighted += s * angle;
                const int bin = binOf(edges, angle);
                if (bin >= 0) area[std::size_t(bin)] += s;
            }
        }
    }
    h.leafArea = total;
    h.fractions.assign(area.size(), 0.0);
    if (total > 0.0) {
        for (std::size_t i = 0; i < area.size(); ++i) h.fractions[i] = area[i] / total;
        h.meanInclination = weighted / total;
    }
    return h;
}

LeafInclinationHistogram leafInclinationHistogram(const PlantArchitecture& arch, unsigned plantID,
                                                  const std::vector<double>& edges) {
    arch.plant(plantID);  // throws for a plant that does not exist
    return leafInclinationHistogram(arch, std::vector<unsigned>{plantID}, edges);
}

double meanLeafInclination(const PlantArchitecture& arch, unsigned plantID) {
    return leafInclinationHistogram(arch, plantID).meanInclination;
}

double meanLeafInclination(const PlantArchitecture& arch, const std::vector<unsigned>& plantIDs) {
    for (unsigned id : plantIDs) arch.plant(id);
    return leafInclinationHistogram(arch, plantIDs).meanInclination;
}

std::vector<double> leafInclinationFractions(const LeafAngleParameters& p,
                                             const std::vector<double>& edges) {
    checkEdges(edges);
    checkParameters(p);
    std::vector<double> out(edges.size() - 1, 0.0);
    if (p.inclination == LeafInclinationDistribution::None) return out;
    const leaf_angles::Sampler s(p);
    for (std::size_t i = 0; i + 1 < edges.size(); ++i)
        out[i] = s.probability(edges[i], edges[i + 1]);
    return out;
}

double leafInclinationDensity(const LeafAngleParameters& p, double degrees) {
    checkParameters(p);
    return leaf_angles::inclinationDensity(p, degrees);
}

LeafAngleTarget drawLeafAngle(const LeafAngleParameters& p, Rng& rng) {
    checkParameters(p);
    if (p.inclination == LeafInclinationDistribution::None)
        throw Error("the distribution 'none' draws no leaf angles",
                    {.parameter = "leaf_angles.inclination",
                     .value = "none",
                     .validRange = "a distribution other than none"});
    return leaf_angles::sampler(p).draw(rng);
}

double leafProjection(const LeafAngleParameters& p, double zenith) {
    checkParameters(p);
    if (!(zenith >= 0.0 && zenith < 90.0))
        throw Error("a beam's zenith angle is out of range",
                    {.parameter = "zenith",
                     .value = text::formatDouble(zenith),
                     .validRange = ">= 0 and < 90 (degrees)"});
    if (p.inclination == LeafInclinationDistribution::None) return 0.0;
    // Ross (1981): a leaf inclined tl seen from zenith angle t projects cos t cos tl when
    // t + tl <= 90 degrees, else cos t cos tl (1 + (2/pi)(tan a - a)), a = acos(cot t cot tl),
    // averaged over uniform azimuths; summed over cells of 0.05 degrees of inclination.
    const leaf_angles::Sampler s(p);
    const double t = zenith / kDegPerRad, ct = std::cos(t);
    constexpr int kSteps = 1800;
    double g = 0.0;
    for (int i = 0; i < kSteps; ++i) {
        const double lo = 90.0 * i / kSteps, hi = 90.0 * (i + 1) / kSteps;
        const double tl = 0.5 * (lo + hi) / kDegPerRad;
        double psi = ct * std::cos(tl);
        if (t + tl > std::numbers::pi / 2.0) {
            const double a = std::acos(std::clamp(1.0 / (std::tan(t) * std::tan(tl)), -1.0, 1.0));
            psi *= 1.0 + 2.0 / std::numbers::pi * (std::tan(a) - a);
        }
        g += s.probability(lo, hi) * psi;
    }
    return g;
}

}  // namespace plantarch
