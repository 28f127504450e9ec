// Plants built on measured skeletons (reconstructPlants) and plants written as skeletons
// (plantSkeleton): axes found from the node tree, each made a shoot through its points.

#include <algorithm>
#include <cmath>
#include <deque>
#include <map>
#include <optional>

#include "geometry/tessellate.h"
#include "plantarch/Error.h"
#include "plantarch/Skeleton.h"

namespace plantarch {

namespace {

// One axis: the node it starts at (a node of its parent axis, or the root) and its own nodes.
struct Axis {
    std::vector<std::size_t> nodes;  ///< [0]: where it starts; then one per internode
    int parentAxis = -1;             ///< -1: the base stem
    bool continues = false;          ///< continues its parent's tip (a new type)
    bool tiller = false;             ///< a branch from the root
    std::string type;
};

void checkOptions(const ReconstructOptions& o) {
    auto bad = [](const char* name, float v, const char* range) {
        throw Error(std::string(name) + " out of range",
                    {.parameter = name, .value = std::to_string(v), .validRange = range});
    };
    if (!(o.age >= 0.0f && o.age <= 100000.0f)) bad("age", o.age, "0 to 100000 days");
    if (!(o.spacing >= 0.0f && o.spacing <= 10.0f)) bad("spacing", o.spacing, "0 to 10 m");
    if (!(o.unit > 0.0f && o.unit <= 1000.0f)) bad("unit", o.unit, "> 0 and <= 1000 m per unit");
}

class Builder {
public:
    Builder(PlantArchitecture& arch, const Skeleton& sk, const ReconstructOptions& o)
        : arch_(arch), sk_(sk), o_(o) {
        for (std::size_t i = 0; i < sk.nodes.size(); ++i) index_[sk.nodes[i].id] = i;
        children_.resize(sk.nodes.size());
        for (std::size_t i = 0; i < sk.nodes.size(); ++i)
            if (sk.nodes[i].parent >= 0) children_[index_.at(sk.nodes[i].parent)].push_back(i);
    }

    unsigned build(std::size_t root) {
        const SkeletonNode& r = sk_.nodes[root];
        if (children_[root].empty())
            fail(r, "a root with no nodes: a plant needs at least one internode", "");
        plant_ = arch_.addPlantInstance(r.position * o_.unit, o_.age);
        std::vector<Axis> axes;
        std::deque<std::size_t> queue;
        // The base stem: the root's continuing child; its other children are tillers.
        const std::size_t first = continuing(root).value_or(children_[root].front());
        Axis base;
        base.nodes = {root};
        base.type = !sk_.nodes[first].shootType.empty() ? sk_.nodes[first].shootType
                    : !o_.baseShootType.empty()         ? o_.baseShootType
                                                        : arch_.getBaseStemShootType();
        if (base.type.empty())
            fail(sk_.nodes[first],
                 "no shoot type for the base stem: name it on its first node (shoot_type) or "
                 "load a species",
                 "a shoot type of the loaded species");
        axes.push_back(base);
        walk(axes, 0, first, queue);
        for (std::size_t c : children_[root])
            if (c != first) queue.push_back(newBranch(axes, 0, root, c, true));
        make(axes, 0);
        while (!queue.empty()) {
            const std::size_t a = queue.front();
            queue.pop_front();
            walk(axes, a, axes[a].nodes[1], queue);
            make(axes, a);
        }
        for (const auto& [node, place] : place_) {
            for (const std::string& organ : sk_.nodes[node].organs)
                if (organ == "flower" || organ == "fruit")
                    arch_.addFloralBud(
                        plant_, place.first, place.second,
                        organ == "fruit" ? FloralStage::Fruit : FloralStage::FlowerOpen);
        }
        return plant_;
    }

private:
    [[noreturn]] void fail(const SkeletonNode& n, const std::string& message,
                           const std::string& range) const {
        throw Error(message, {.file = sk_.source,
                              .line = n.line,
                              .parameter = "node " + std::to_string(n.id),
                              .validRange = range});
    }

    // The child that continues node i's axis: an explicit one, else the first unmarked one.
    std::optional<std::size_t> continuing(std::size_t i) const {
        for (std::size_t c : children_[i])
            if (sk_.nodes[c].link == SkeletonLink::Continue) return c;
        for (std::size_t c : children_[i])
            if (sk_.nodes[c].link == SkeletonLink::Auto) return c;
        return std::nullopt;
    }

    std::size_t newBranch(std::vector<Axis>& axes, std::size_t parentAxis, std::size_t at,
                          std::size_t child, bool tiller) {
        Axis b;
        b.nodes = {at, child};
        b.parentAxis = int(parentAxis);
        b.tiller = tiller;
        b.type = sk_.nodes[child].shootType;
        axes.push_back(b);
        return axes.size() - 1;
    }

    // Follows axis a from its node `from` (already its nodes[1] for a queued axis) to its end,
    // queuing the axes that start along it.
    void walk(std::vector<Axis>& axes, std::size_t a, std::size_t from,
              std::deque<std::size_t>& queue) {
        if (axes[a].nodes.size() == 1) axes[a].nodes.push_back(from);
        std::size_t cur = from;
        for (;;) {
            const std::optional<std::size_t> next = continuing(cur);
            for (std::size_t c : children_[cur])
                if (c != next) queue.push_back(newBranch(axes, a, cur, c, false));
            if (!next) break;
            const std::string& t = sk_.nodes[*next].shootType;
            if (!t.empty() && t != axes[a].type) {  // the axis goes on as another type
                Axis c;
                c.nodes = {cur, *next};
                c.parentAxis = int(a);
                c.continues = true;
                c.type = t;
                axes.push_back(c);
                queue.push_back(axes.size() - 1);
                break;
            }
            axes[a].nodes.push_back(*next);
            cur = *next;
        }
    }

    std::string branchType(const Axis& axis, unsigned parentShoot) const {
        if (!axis.type.empty()) return axis.type;
        if (!o_.branchShootType.empty()) return o_.branchShootType;
        const std::string& parentType = arch_.plant(plant_).shoots[parentShoot].type;
        const ShootParameters& pt = arch_.plant(plant_).shootTypes.at(parentType);
        std::string best = parentType;
        float p = -1.0f;
        for (const auto& [label, probability] : pt.child_shoot_types)
            if (probability > p) {
                p = probability;
                best = label;
            }
        return best;
    }

    // Makes axis a a shoot (its parent is made already).
    void make(std::vector<Axis>& axes, std::size_t a) {
        Axis& axis = axes[a];
        const SkeletonNode& firstNode = sk_.nodes[axis.nodes[1]];
        int parentShoot = -1;
        unsigned parentNode = 0;
        MeasuredShootOptions so = o_.shoot;
        so.bareNodes.clear();
        so.leaves.clear();
        if (axis.parentAxis >= 0) {
            if (axis.tiller) {
                parentShoot = int(shootOf_.at(0));
                parentNode = 0;
            } else {
                const auto [shoot, node] = place_.at(axis.nodes[0]);
                parentShoot = int(shoot);
                parentNode = node;
            }
            axis.type = axis.continues ? axis.type : branchType(axis, unsigned(parentShoot));
            so.continueParent = axis.continues;
            if (!axis.continues) {
                const unsigned petioles = unsigned(arch_.plant(plant_)
                                                       .shoots[unsigned(parentShoot)]
                                                       .phytomers[parentNode]
                                                       .petioles.size());
                so.petioleIndex =
                    petioles ? branchesAt_[{unsigned(parentShoot), parentNode}]++ % petioles : 0;
            }
        }
        const ShootParameters& type = arch_.plant(plant_).shootTypes.count(axis.type)
                                          ? arch_.plant(plant_).shootTypes.at(axis.type)
                                          : arch_.shootType(axis.type);
        const float defaultRadius = type.phytomer_parameters.internode.radius_initial.mean();
        // Points and radii (m), resampled when asked.
        std::vector<vec3> points;
        std::vector<float> radii;
        for (std::size_t k = 0; k < axis.nodes.size(); ++k) {
            const SkeletonNode& n = sk_.nodes[axis.nodes[k]];
            points.push_back(n.position * o_.unit);
            radii.push_back(n.radius > 0.0f ? n.radius * o_.unit : defaultRadius);
        }
        // A shoot starts where its parent's node stands (a tiller: the base stem's first).
        if (parentShoot >= 0 && (axis.tiller || o_.spacing > 0.0f))
            points[0] = arch_.getNodePosition(plant_, unsigned(parentShoot), parentNode);
        std::vector<std::size_t> nodeAt(axis.nodes.size());  // node k -> its phytomer + 1
        for (std::size_t k = 0; k < nodeAt.size(); ++k) nodeAt[k] = k;
        if (o_.spacing > 0.0f) resample(points, radii, nodeAt);
        for (std::size_t k = 1; k < axis.nodes.size(); ++k)
            for (const std::string& organ : sk_.nodes[axis.nodes[k]].organs)
                if (organ == "bare") so.bareNodes.push_back(unsigned(nodeAt[k] - 1));
        for (std::size_t k = 1; k < axis.nodes.size(); ++k) {
            const SkeletonNode& n = sk_.nodes[axis.nodes[k]];
            if (n.leafNormal || n.leafLength > 0.0f)
                so.leaves.push_back(
                    {unsigned(nodeAt[k] - 1), n.leafNormal, n.leafLength * o_.unit});
        }
        std::sort(so.bareNodes.begin(), so.bareNodes.end());
        so.bareNodes.erase(std::unique(so.bareNodes.begin(), so.bareNodes.end()),
                           so.bareNodes.end());
        unsigned shoot = 0;
        try {
            shoot = arch_.addShootFromNodePositions(plant_, parentShoot, parentNode, points, radii,
                                                    axis.type, so);
        } catch (const Error& e) {
            throw Error(e.message() + " (the shoot from node " + std::to_string(firstNode.id) + ")",
                        {.file = sk_.source,
                         .line = firstNode.line,
                         .parameter = e.parameter(),
                         .value = e.value(),
                         .validRange = e.validRange()});
        }
        shootOf_[a] = shoot;
        for (std::size_t k = 1; k < axis.nodes.size(); ++k)
            place_[axis.nodes[k]] = {shoot, unsigned(nodeAt[k] - 1)};
    }

    // Equal steps of about o_.spacing along the polyline; node k maps to the nearest step.
    void resample(std::vector<vec3>& points, std::vector<float>& radii,
                  std::vector<std::size_t>& nodeAt) const {
        std::vector<double> arc(points.size(), 0.0);
        for (std::size_t k = 1; k < points.size(); ++k)
            arc[k] = arc[k - 1] + double(glm::length(points[k] - points[k - 1]));
        const double total = arc.back();
        const std::size_t steps =
            std::max<std::size_t>(1, std::size_t(std::llround(total / o_.spacing)));
        if (steps > 100000)
            throw Error("resampling makes too many internodes",
                        {.file = sk_.source,
                         .parameter = "spacing",
                         .value = std::to_string(o_.spacing),
                         .validRange = "at most 100000 internodes per axis"});
        std::vector<vec3> p{points[0]};
        std::vector<float> r{radii.size() > 1 ? radii[1] : radii[0]};
        std::size_t seg = 1;
        for (std::size_t s = 1; s <= steps; ++s) {
            const double at = total * double(s) / double(steps);
            while (seg + 1 < points.size() && arc[seg] < at) ++seg;
            const double len = arc[seg] - arc[seg - 1];
            const float f =
                len > 0.0 ? float(std::clamp((at - arc[seg - 1]) / len, 0.0, 1.0)) : 1.0f;
            p.push_back(glm::mix(points[seg - 1], points[seg], f));
            r.push_back(glm::mix(radii[seg - 1], radii[seg], f));
        }
        p.back() = points.back();
        for (std::size_t k = 1; k < nodeAt.size(); ++k)
            nodeAt[k] = std::clamp<std::size_t>(
                std::size_t(std::llround(arc[k] / total * double(steps))), 1, steps);
        points = std::move(p);
        radii = std::move(r);
    }

    PlantArchitecture& arch_;
    const Skeleton& sk_;
    const ReconstructOptions& o_;
    unsigned plant_ = 0;
    std::map<long, std::size_t> index_;
    std::vector<std::vector<std::size_t>> children_;
    std::map<std::size_t, unsigned> shootOf_;                       ///< axis -> shoot
    std::map<std::size_t, std::pair<unsigned, unsigned>> place_;    ///< node -> shoot, phytomer
    std::map<std::pair<unsigned, unsigned>, unsigned> branchesAt_;  ///< lateral shoots per node
};

}  // namespace

std::vector<unsigned> reconstructPlants(PlantArchitecture& arch, const Skeleton& skeleton,
                                        const ReconstructOptions& options) {
    checkOptions(options);
    checkSkeleton(skeleton);
    std::vector<unsigned> plants;
    const std::vector<unsigned> before = arch.getAllPlantIDs();
    try {
        for (std::size_t i = 0; i < skeleton.nodes.size(); ++i)
            if (skeleton.nodes[i].parent < 0) {
                Builder b(arch, skeleton, options);
                plants.push_back(b.build(i));
            }
    } catch (...) {
        // Nothing is added: the plants made so far go, and the one being made.
        for (unsigned id : arch.getAllPlantIDs())
            if (!std::binary_search(before.begin(), before.end(), id)) arch.deletePlantInstance(id);
        throw;
    }
    return plants;
}

Skeleton plantSkeleton(const PlantArchitecture& arch, const std::vector<unsigned>& plantIDs) {
    Skeleton sk;
    sk.source = "plants";
    long next = 0;
    for (unsigned id : plantIDs) {
        const PlantInstance& p = arch.plant(id);
        SkeletonNode root;
        root.id = next++;
        root.position = p.base;
        sk.nodes.push_back(root);
        // The node id of each (shoot, phytomer) tip.
        std::vector<std::vector<long>> ids(p.shoots.size());
        for (const Shoot& s : p.shoots) {
            if (s.removed || s.phytomers.empty()) continue;
            const std::vector<vec3> nodes = shootNodePositions(p, s.id);
            long parent = root.id;
            SkeletonLink link = SkeletonLink::Continue;
            if (s.parent >= 0) {
                const Shoot& ps = p.shoots[unsigned(s.parent)];
                parent = ids[unsigned(s.parent)].at(std::size_t(s.parentNode));
                const bool continues =
                    s.rank == ps.rank && std::size_t(s.parentNode) + 1 == ps.phytomers.size();
                link = continues ? SkeletonLink::Continue : SkeletonLink::Branch;
            }
            for (std::size_t k = 0; k < s.phytomers.size(); ++k) {
                SkeletonNode n;
                n.id = next++;
                n.parent = k == 0 ? parent : ids[s.id].back();
                n.position = nodes[k + 1];
                n.radius = s.phytomers[k].internode.radius;
                n.link = k == 0 ? link : SkeletonLink::Continue;
                if (k == 0) n.shootType = s.type;
                ids[s.id].push_back(n.id);
                sk.nodes.push_back(std::move(n));
            }
        }
    }
    return sk;
}

}  // namespace plantarch
