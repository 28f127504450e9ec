// Shoots on measured points (PlantArchitecture::addShootFromNodePositions): the shoot is made
// as growth makes one, then each internode is laid along its measured segment and marked
// measured, so growth leaves it as it is.

#include <cmath>
#include <string>

#include "api/facade_impl.h"
#include "core/math.h"
#include "geometry/tessellate.h"
#include "growth/growth.h"
#include "plantarch/Error.h"
#include "plantarch/PhytomerActions.h"

namespace plantarch {

namespace {

std::string pointText(const vec3& p) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%.6g, %.6g, %.6g)", double(p.x), double(p.y), double(p.z));
    return buf;
}

void checkOptions(const MeasuredShootOptions& o) {
    if (!(o.leafScale > 0.0f && o.leafScale <= 1.0f))
        throw Error("leaf scale out of range", {.parameter = "leaf_scale",
                                                .value = std::to_string(o.leafScale),
                                                .validRange = "> 0 and <= 1"});
    if (!(o.attachTolerance >= 0.0f && o.attachTolerance <= 10.0f))
        throw Error("attach tolerance out of range", {.parameter = "attach_tolerance",
                                                      .value = std::to_string(o.attachTolerance),
                                                      .validRange = "0 to 10 m"});
}

// Points finite, within reach, no two in a row at one place; radii finite and > 0.
void checkPoints(const std::vector<vec3>& points, const std::vector<float>& radii) {
    if (points.size() < 2 || points.size() > 100001)
        throw Error("a measured shoot needs 2 to 100001 points (its start and one per node)",
                    {.parameter = "node_positions",
                     .value = std::to_string(points.size()) + " points",
                     .validRange = "2 to 100001 points"});
    for (std::size_t i = 0; i < points.size(); ++i) {
        const vec3& p = points[i];
        if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) ||
            glm::length(p) > 1e5f)
            throw Error("node position not finite or too far",
                        {.parameter = "node_positions[" + std::to_string(i) + "]",
                         .value = pointText(p),
                         .validRange = "finite coordinates within 100 km of the origin, m"});
        if (i > 0 && !(glm::length(p - points[i - 1]) > 1e-6f))
            throw Error("two successive node positions coincide: an internode needs a length",
                        {.parameter = "node_positions[" + std::to_string(i) + "]",
                         .value = pointText(p),
                         .validRange = "more than 1e-6 m from the point before"});
    }
    if (!radii.empty() && radii.size() != points.size())
        throw Error("one radius per node position, or none",
                    {.parameter = "node_radii",
                     .value = std::to_string(radii.size()) + " radii for " +
                              std::to_string(points.size()) + " points",
                     .validRange = std::to_string(points.size()) + " values, or empty"});
    for (std::size_t i = 1; i < radii.size(); ++i)  // radii[0], where it starts, is not used
        if (!(radii[i] > 0.0f && radii[i] <= 10.0f))
            throw Error("node radius out of range",
                        {.parameter = "node_radii[" + std::to_string(i) + "]",
                         .value = std::to_string(radii[i]),
                         .validRange = "> 0 and <= 10 m"});
}

// A node's leaves as measured: their blades facing `m.normal` (inclination from the zenith,
// azimuth clockwise from +y, as LeafAngleTarget says), the largest `m.length` long.
void poseLeaves(Phytomer& ph, const MeasuredLeaf& m) {
    float largest = 0.0f;
    for (const Petiole& pt : ph.petioles)
        for (const LeafOrgan& l : pt.leaves) largest = std::max(largest, l.scale);
    for (Petiole& pt : ph.petioles)
        for (LeafOrgan& l : pt.leaves) {
            if (m.normal) {
                // A blade's plane is what is posed: a normal pointing down counts as its
                // opposite (inclinations are 0 to 90 degrees).
                vec3 n = glm::normalize(*m.normal);
                if (n.z < 0.0f) n = -n;
                float azimuth = std::atan2(n.x, n.y) / kDeg;
                if (azimuth < 0.0f) azimuth += 360.0f;
                l.angleTarget =
                    LeafAngleTarget{std::acos(std::clamp(n.z, -1.0f, 1.0f)) / kDeg, azimuth};
            }
            if (m.length > 0.0f && largest > 0.0f) l.scale *= m.length / largest;
        }
}

}  // namespace

unsigned PlantArchitecture::addShootFromNodePositions(unsigned plantID, int parentShootID,
                                                      unsigned parentNode,
                                                      const std::vector<vec3>& nodePositions,
                                                      const std::vector<float>& nodeRadii,
                                                      const std::string& shootType,
                                                      const MeasuredShootOptions& options) {
    PlantInstance& p = impl_->store.plant(plantID);
    checkOptions(options);
    checkPoints(nodePositions, nodeRadii);
    for (std::size_t i = 0; i < options.leaves.size(); ++i) {
        const MeasuredLeaf& m = options.leaves[i];
        const std::string at = "leaves[" + std::to_string(i) + "]";
        if (m.node + 1 >= nodePositions.size())
            throw Error("measured leaf's node out of range",
                        {.parameter = at + ".node",
                         .value = std::to_string(m.node),
                         .validRange = "0 to " + std::to_string(nodePositions.size() - 2)});
        if (m.normal && !(std::isfinite(m.normal->x) && std::isfinite(m.normal->y) &&
                          std::isfinite(m.normal->z) && glm::length(*m.normal) > 1e-6f))
            throw Error("measured leaf normal not a direction",
                        {.parameter = at + ".normal",
                         .value = pointText(*m.normal),
                         .validRange = "finite, of length > 0"});
        if (!(m.length >= 0.0f && m.length <= 10.0f))
            throw Error("measured leaf length out of range",
                        {.parameter = at + ".length",
                         .value = std::to_string(m.length),
                         .validRange = "0 to 10 m (0: the species')"});
    }
    for (unsigned k : options.bareNodes)
        if (k + 1 >= nodePositions.size())
            throw Error("bare node out of range",
                        {.parameter = "bare_nodes",
                         .value = std::to_string(k),
                         .validRange = "0 to " + std::to_string(nodePositions.size() - 2)});
    const ShootParameters& type = impl_->store.shootTypeFor(p, shootType);

    // Where the shoot starts, as the plant stands now.
    StartMode mode = StartMode::Base;
    vec3 start = p.base;
    if (parentShootID < 0) {
        if (parentShootID != -1)
            throw Error("parent shoot out of range",
                        {.parameter = "parentShootID",
                         .value = std::to_string(parentShootID),
                         .validRange = "-1 (the base stem) or a shoot ID of the plant"});
        if (!p.shoots.empty())
            throw Error("the plant already has a base stem",
                        {.parameter = "parentShootID", .value = "-1"});
    } else {
        const Shoot& parent = PlantStore::shoot(p, unsigned(parentShootID));
        if (parentNode >= parent.phytomers.size())
            throw Error("parent node out of range",
                        {.parameter = "parentNode",
                         .value = std::to_string(parentNode),
                         .validRange = "0 to " + std::to_string(parent.phytomers.size() - 1)});
        if (options.continueParent && parentNode + 1 != parent.phytomers.size())
            throw Error("a shoot continuing its parent starts at the parent's last node",
                        {.parameter = "parentNode",
                         .value = std::to_string(parentNode),
                         .validRange = std::to_string(parent.phytomers.size() - 1)});
        mode = options.continueParent ? StartMode::Append : StartMode::Child;
        start = shootNodePositions(p, unsigned(parentShootID))[parentNode + 1];
    }
    const float gap = glm::length(nodePositions[0] - start);
    if (!(gap <= options.attachTolerance))
        throw Error("the first point is not where the shoot starts",
                    {.parameter = "node_positions[0]",
                     .value = pointText(nodePositions[0]) + ", " + std::to_string(gap) +
                              " m from " + pointText(start),
                     .validRange = "within attach_tolerance (" +
                                   std::to_string(options.attachTolerance) + " m) of it"});

    const std::size_t n = nodePositions.size() - 1;
    const float radius0 =
        nodeRadii.empty() ? type.phytomer_parameters.internode.radius_initial.mean() : nodeRadii[1];
    ShootSpec spec;
    spec.shootType = shootType;
    spec.phytomers = unsigned(n);
    spec.size.internodeRadius = std::clamp(radius0, 1e-6f, 10.0f);
    spec.size.internodeLengthMax = std::min(glm::length(nodePositions[1] - start), 100.0f);
    spec.size.leafScale = options.leafScale;
    const unsigned id = createShoot(impl_->growth(), p, spec, mode, parentShootID, parentNode,
                                    options.petioleIndex);

    // Lay each internode along its segment; the roll reference is carried along with the
    // smallest turn, so the petioles keep their phyllotaxis around the measured axis.
    Shoot& s = p.shoots[id];
    vec3 reference = s.phytomers[0].internode.rollReference;
    vec3 from = start;
    for (std::size_t k = 0; k < n; ++k) {
        Phytomer& ph = s.phytomers[k];
        Internode& in = ph.internode;
        const vec3 to = nodePositions[k + 1];
        const vec3 d = glm::normalize(to - from);
        in.direction = in.guide = d;
        in.pitch = 0.0f;
        in.gravitropicTurn = in.walkZenith = in.walkYaw = 0.0f;
        reference -= glm::dot(reference, d) * d;
        reference =
            glm::length(reference) > 1e-6f ? glm::normalize(reference) : anyPerpendicular(d);
        in.rollReference = reference;
        in.length = glm::length(to - from);
        const float r = nodeRadii.empty() ? type.phytomer_parameters.internode.radius_initial.mean()
                                          : nodeRadii[k + 1];
        in.radius = r;
        ph.radiusInitial = r;
        ph.internodeFraction = ph.internodeFraction0 = 1.0f;
        ph.measured = MeasuredInternode{r};
        from = to;
    }
    for (unsigned k : options.bareNodes) removeLeaves(s.phytomers[k]);
    for (const MeasuredLeaf& m : options.leaves) poseLeaves(s.phytomers[m.node], m);
    // Internodes grown on from the tip take the type's length, not the first segment's.
    s.internodeLengthMax = std::max(type.internode_length_max.mean(), 0.0f);
    updateGeometry(plantID);
    return id;
}

std::string PlantArchitecture::getBaseStemShootType() const {
    if (!impl_->species) return {};
    for (const BuildStep& step : impl_->species->build)
        if (step.kind == BuildStep::Kind::BaseStem) return step.shootType;
    return {};
}

}  // namespace plantarch
