// PlantArchitecture: pruning, removal, harvest, registries, queries and geometry updates.

#include <algorithm>
#include <cmath>
#include <functional>

#include "api/facade_impl.h"
#include "collision/collision_world.h"
#include "geometry/tessellate.h"
#include "growth/growth.h"
#include "plantarch/Error.h"

namespace plantarch {

namespace {

// A node index of shoot `s`, or an error naming the valid range.
void checkNode(const Shoot& s, unsigned node) {
    if (node >= s.phytomers.size())
        throw Error("node out of range",
                    {.parameter = "node",
                     .value = std::to_string(node),
                     .validRange = "0 to " + std::to_string(s.phytomers.size() - 1)});
}

template <class F>
void forEachPhytomer(PlantInstance& p, F&& f) {
    for (Shoot& s : p.shoots)
        if (!s.removed)
            for (Phytomer& ph : s.phytomers) f(s, ph);
}

template <class F>
void forEachPhytomer(const PlantInstance& p, F&& f) {
    for (const Shoot& s : p.shoots)
        if (!s.removed)
            for (const Phytomer& ph : s.phytomers) f(s, ph);
}

// Every floral bud of the plant, axillary and terminal.
template <class P, class F>
void forEachFloralBud(P& p, F&& f) {
    for (auto& s : p.shoots) {
        if (s.removed) continue;
        for (auto& ph : s.phytomers)
            for (auto& pt : ph.petioles)
                for (auto& fb : pt.floralBuds) f(fb);
        for (auto& fb : s.terminalFloralBuds) f(fb);
    }
}

void collect(std::vector<ObjectID>& out, ObjectID id) {
    if (id != kNoObject) out.push_back(id);
}

}  // namespace

// ---- removal ---------------------------------------------------------------------------

void PlantArchitecture::pruneBranch(unsigned plantID, unsigned shootID, unsigned node) {
    PlantInstance& p = impl_->store.plant(plantID);
    Shoot& s = PlantStore::shoot(p, shootID);
    checkNode(s, node);
    // Shoots growing from the removed nodes (or from the tip, for appended shoots) go too.
    std::function<void(unsigned)> removeShoot = [&](unsigned id) {
        Shoot& victim = p.shoots[id];
        for (unsigned child : victim.children) removeShoot(child);
        deleteShootObjects(*context_, victim);
        victim.phytomers.clear();
        victim.terminalFloralBuds.clear();
        victim.children.clear();
        victim.removed = true;
    };
    std::vector<unsigned> keep;
    for (unsigned child : s.children) {
        const Shoot& c = p.shoots[child];
        if (c.parentNode >= int(node))
            removeShoot(child);
        else
            keep.push_back(child);
    }
    s.children = keep;
    for (std::size_t i = node; i < s.phytomers.size(); ++i)
        deletePhytomerObjects(*context_, s.phytomers[i]);
    s.phytomers.erase(s.phytomers.begin() + node, s.phytomers.end());
    for (FloralBud& fb : s.terminalFloralBuds) {
        if (fb.peduncleObject != kNoObject) context_->deleteObject(fb.peduncleObject);
        for (FlowerOrgan& fl : fb.flowers)
            for (ObjectID id : fl.objects) context_->deleteObject(id);
    }
    s.terminalFloralBuds.clear();
    s.apicalBud.state = BudState::Dead;  // a cut shoot no longer grows from its tip
    if (s.phytomers.empty()) {
        s.removed = true;
        if (s.parent >= 0) {
            auto& siblings = p.shoots[unsigned(s.parent)].children;
            siblings.erase(std::remove(siblings.begin(), siblings.end(), s.id), siblings.end());
        }
    }
    updateGeometry(plantID);
}

void PlantArchitecture::removePlantLeaves(unsigned plantID) {
    PlantInstance& p = impl_->store.plant(plantID);
    forEachPhytomer(p, [](Shoot&, Phytomer& ph) {
        for (Petiole& pt : ph.petioles)
            for (LeafOrgan& l : pt.leaves) l.removed = true;
    });
    updateGeometry(plantID);
}

void PlantArchitecture::removeShootLeaves(unsigned plantID, unsigned shootID) {
    PlantInstance& p = impl_->store.plant(plantID);
    Shoot& s = PlantStore::shoot(p, shootID);
    for (Phytomer& ph : s.phytomers)
        for (Petiole& pt : ph.petioles) {
            for (LeafOrgan& l : pt.leaves) l.removed = true;
            // A petiole of zero size is not drawn; its node keeps its buds.
            pt.length = 0.0f;
            pt.radius = 0.0f;
        }
    updateGeometry(plantID);
}

void PlantArchitecture::removeShootVegetativeBuds(unsigned plantID, unsigned shootID) {
    removeShootAxillaryVegetativeBuds(plantID, shootID);
    removeShootApex(plantID, shootID);
}

void PlantArchitecture::removeShootAxillaryVegetativeBuds(unsigned plantID, unsigned shootID) {
    PlantInstance& p = impl_->store.plant(plantID);
    Shoot& s = PlantStore::shoot(p, shootID);
    for (Phytomer& ph : s.phytomers)
        for (Petiole& pt : ph.petioles)
            for (VegetativeBud& b : pt.vegetativeBuds)
                if (b.state != BudState::Broken) b.state = BudState::Dead;
}

void PlantArchitecture::removeShootApex(unsigned plantID, unsigned shootID) {
    PlantInstance& p = impl_->store.plant(plantID);
    Shoot& s = PlantStore::shoot(p, shootID);
    s.apicalBud.state = BudState::Dead;
    s.nextPhytomerTime = -1.0;
}

void PlantArchitecture::removeShootFloralBuds(unsigned plantID, unsigned shootID) {
    PlantInstance& p = impl_->store.plant(plantID);
    Shoot& s = PlantStore::shoot(p, shootID);
    auto kill = [](FloralBud& fb) {
        if (fb.stage == FloralStage::Bud) {
            fb.state = BudState::Dead;
            fb.stage = FloralStage::Removed;
        }
    };
    for (Phytomer& ph : s.phytomers)
        for (Petiole& pt : ph.petioles)
            for (FloralBud& fb : pt.floralBuds) kill(fb);
    for (FloralBud& fb : s.terminalFloralBuds) kill(fb);
}

void PlantArchitecture::removePlantFlowers(unsigned plantID) {
    PlantInstance& p = impl_->store.plant(plantID);
    forEachFloralBud(p, [](FloralBud& fb) {
        if (fb.stage != FloralStage::Bud && fb.stage != FloralStage::Removed) {
            fb.stage = FloralStage::Removed;
            fb.state = BudState::Dead;
        }
    });
    updateGeometry(plantID);
}

unsigned PlantArchitecture::harvestPlant(unsigned plantID) {
    PlantInstance& p = impl_->store.plant(plantID);
    unsigned fruit = 0;
    forEachFloralBud(p, [&](FloralBud& fb) {
        if (fb.stage == FloralStage::Fruit) {
            fruit += unsigned(fb.flowers.size());
            fb.stage = FloralStage::Removed;
            fb.state = BudState::Dead;
        }
    });
    updateGeometry(plantID);
    return fruit;
}

unsigned PlantArchitecture::addFloralBud(unsigned plantID, unsigned shootID, unsigned node,
                                         FloralStage stage, unsigned petioleIndex) {
    PlantInstance& p = impl_->store.plant(plantID);
    Shoot& s = PlantStore::shoot(p, shootID);
    checkNode(s, node);
    Phytomer& ph = s.phytomers[node];
    if (petioleIndex >= ph.petioles.size())
        throw Error("petiole index out of range",
                    {.parameter = "petiole_index",
                     .value = std::to_string(petioleIndex),
                     .validRange = "0 to " + std::to_string(ph.petioles.size()) + " (exclusive)"});
    if (stage == FloralStage::Bud || stage == FloralStage::Removed)
        throw Error("a hand-added floral bud must be a flower or fruit",
                    {.parameter = "stage",
                     .value = floralStageName(stage),
                     .validRange = "flower_closed, flower_open, fruit"});
    const ShootParameters& type = impl_->store.shootTypeFor(p, ph.parametersLabel);
    const PhytomerParameters& pp = type.phytomer_parameters;
    FloralBud fb;
    fb.stage = stage;
    fb.state = BudState::Broken;
    fb.stageTime = p.age;
    realizeInflorescence(p, fb, pp);
    const unsigned count = unsigned(fb.flowers.size());
    ph.petioles[petioleIndex].floralBuds.push_back(fb);
    updateGeometry(plantID);
    return count;
}

// ---- registries ------------------------------------------------------------------------

void PlantArchitecture::registerLeafPrototype(const std::string& name, LeafPrototypeFunction fn) {
    if (name.empty() || !fn)
        throw Error("a leaf prototype needs a name and a function",
                    {.parameter = "name", .value = name});
    impl_->functions.leafPrototypes[name] = std::move(fn);
    impl_->functions.userLeafPrototypes.insert(name);
    impl_->prototypes.clear();
    impl_->collision.proxies.reset();
}

void PlantArchitecture::registerFloralPrototype(const std::string& name,
                                                FloralPrototypeFunction fn) {
    if (name.empty() || !fn)
        throw Error("a flower/fruit prototype needs a name and a function",
                    {.parameter = "name", .value = name});
    impl_->functions.floralPrototypes[name] = std::move(fn);
    impl_->functions.userFloralPrototypes.insert(name);
    impl_->prototypes.clear();
    impl_->collision.proxies.reset();
}

bool PlantArchitecture::hasLeafPrototype(const std::string& name) const {
    return impl_->functions.leafPrototypes.count(name) > 0;
}

bool PlantArchitecture::hasFloralPrototype(const std::string& name) const {
    return impl_->functions.floralPrototypes.count(name) > 0;
}

// ---- geometry --------------------------------------------------------------------------

void PlantArchitecture::updateGeometry(unsigned plantID) {
    if (impl_->geometryDeferred) return;
    tessellatePlant(impl_->store, impl_->prototypes, *context_, impl_->store.plant(plantID));
    // An edit outside growth: the soft collision scene reads the plant again at the next
    // call. (Without soft avoidance canopy workers share the scene: nothing is written.)
    collision::World* world = impl_->collision.world.get();
    if (world && world->soft()) world->stale[plantID] = true;
}

// ---- queries ---------------------------------------------------------------------------

std::vector<unsigned> PlantArchitecture::getAllPlantIDs() const {
    std::vector<unsigned> ids;
    for (const auto& [id, p] : impl_->store.plants) ids.push_back(id);
    return ids;
}

const PlantInstance& PlantArchitecture::plant(unsigned plantID) const {
    return impl_->store.plant(plantID);
}

vec3 PlantArchitecture::getPlantBasePosition(unsigned plantID) const {
    return impl_->store.plant(plantID).base;
}

float PlantArchitecture::getPlantAge(unsigned plantID) const {
    return impl_->store.plant(plantID).age;
}

float PlantArchitecture::getPlantHeight(unsigned plantID) const {
    const PlantInstance& p = impl_->store.plant(plantID);
    float top = p.base.z;
    for (ObjectID id : getAllPlantObjectIDs(plantID))
        top = std::max(top, context_->objectBoundingBox(id).max.z);
    return top - p.base.z;
}

float PlantArchitecture::getPlantStemHeight(unsigned plantID) const {
    const PlantInstance& p = impl_->store.plant(plantID);
    if (p.shoots.empty() || p.shoots[0].removed) return 0.0f;
    // Follow appended shoots: they continue the stem.
    unsigned id = 0;
    for (bool more = true; more;) {
        more = false;
        for (unsigned c : p.shoots[id].children)
            if (p.shoots[c].rank == p.shoots[id].rank) {
                id = c;
                more = true;
                break;
            }
    }
    return shootNodePositions(p, id).back().z - p.base.z;
}

unsigned PlantArchitecture::getPlantLeafCount(unsigned plantID) const {
    unsigned n = 0;
    forEachPhytomer(impl_->store.plant(plantID), [&](const Shoot&, const Phytomer& ph) {
        for (const Petiole& pt : ph.petioles)
            for (const LeafOrgan& l : pt.leaves)
                n += !l.removed && hasSize(currentLeafSize(ph, l)) ? 1 : 0;
    });
    return n;
}

float PlantArchitecture::getPlantLeafArea(unsigned plantID) const {
    double area = 0.0;
    for (ObjectID id : getPlantObjectIDs(plantID, OrganKind::Leaf))
        area += context_->objectArea(id);
    return float(area);
}

float PlantArchitecture::sumPlantLeafArea(const std::vector<unsigned>& plantIDs) const {
    for (unsigned id : plantIDs) impl_->store.plant(id);  // an unknown plant is an error
    double area = 0.0;
    for (unsigned id : plantIDs) area += getPlantLeafArea(id);
    return float(area);
}

std::vector<ObjectID> PlantArchitecture::getPlantObjectIDs(unsigned plantID, OrganKind kind) const {
    const PlantInstance& p = impl_->store.plant(plantID);
    std::vector<ObjectID> ids;
    switch (kind) {
        case OrganKind::Internode:
            forEachPhytomer(
                p, [&](const Shoot&, const Phytomer& ph) { collect(ids, ph.internode.object); });
            break;
        case OrganKind::Petiole:
            forEachPhytomer(p, [&](const Shoot&, const Phytomer& ph) {
                for (const Petiole& pt : ph.petioles) collect(ids, pt.object);
            });
            break;
        case OrganKind::Leaf:
            forEachPhytomer(p, [&](const Shoot&, const Phytomer& ph) {
                for (const Petiole& pt : ph.petioles)
                    for (const LeafOrgan& l : pt.leaves)
                        for (ObjectID id : l.objects) collect(ids, id);
            });
            break;
        case OrganKind::Peduncle:
            forEachFloralBud(p, [&](const FloralBud& fb) {
                if (fb.stage != FloralStage::Bud && fb.stage != FloralStage::Removed)
                    collect(ids, fb.peduncleObject);
            });
            break;
        case OrganKind::FlowerClosed:
        case OrganKind::FlowerOpen:
        case OrganKind::Fruit: {
            const FloralStage stage = kind == OrganKind::FlowerClosed ? FloralStage::FlowerClosed
                                      : kind == OrganKind::FlowerOpen ? FloralStage::FlowerOpen
                                                                      : FloralStage::Fruit;
            forEachFloralBud(p, [&](const FloralBud& fb) {
                if (fb.stage == stage)
                    for (const FlowerOrgan& fl : fb.flowers)
                        for (ObjectID id : fl.objects) collect(ids, id);
            });
            break;
        }
    }
    return ids;
}

std::vector<ObjectID> PlantArchitecture::getAllPlantObjectIDs(unsigned plantID) const {
    std::vector<ObjectID> ids;
    for (OrganKind kind :
         {OrganKind::Internode, OrganKind::Petiole, OrganKind::Leaf, OrganKind::Peduncle,
          OrganKind::FlowerClosed, OrganKind::FlowerOpen, OrganKind::Fruit}) {
        const std::vector<ObjectID> part = getPlantObjectIDs(plantID, kind);
        ids.insert(ids.end(), part.begin(), part.end());
    }
    std::sort(ids.begin(), ids.end());
    return ids;
}

std::vector<ObjectID> PlantArchitecture::getAllObjectIDs() const {
    std::vector<ObjectID> ids;
    for (const auto& [id, p] : impl_->store.plants) {
        auto part = getAllPlantObjectIDs(id);
        ids.insert(ids.end(), part.begin(), part.end());
    }
    std::sort(ids.begin(), ids.end());
    return ids;
}

unsigned PlantArchitecture::getShootCount(unsigned plantID) const {
    unsigned n = 0;
    for (const Shoot& s : impl_->store.plant(plantID).shoots) n += s.removed ? 0 : 1;
    return n;
}

unsigned PlantArchitecture::getShootNodeCount(unsigned plantID, unsigned shootID) const {
    const PlantInstance& p = impl_->store.plant(plantID);
    return unsigned(PlantStore::shoot(p, shootID).phytomers.size());
}

int PlantArchitecture::getShootParent(unsigned plantID, unsigned shootID) const {
    const PlantInstance& p = impl_->store.plant(plantID);
    return PlantStore::shoot(p, shootID).parent;
}

unsigned PlantArchitecture::getShootRank(unsigned plantID, unsigned shootID) const {
    const PlantInstance& p = impl_->store.plant(plantID);
    return PlantStore::shoot(p, shootID).rank;
}

std::vector<unsigned> PlantArchitecture::getShootChildren(unsigned plantID,
                                                          unsigned shootID) const {
    const PlantInstance& p = impl_->store.plant(plantID);
    return PlantStore::shoot(p, shootID).children;
}

std::vector<unsigned> PlantArchitecture::getShootDescendants(unsigned plantID,
                                                             unsigned shootID) const {
    const PlantInstance& p = impl_->store.plant(plantID);
    std::vector<unsigned> out, stack = PlantStore::shoot(p, shootID).children;
    while (!stack.empty()) {
        const unsigned id = stack.back();
        stack.pop_back();
        out.push_back(id);
        for (unsigned c : p.shoots[id].children) stack.push_back(c);
    }
    std::sort(out.begin(), out.end());
    return out;
}

std::vector<unsigned> PlantArchitecture::getTerminalShoots(unsigned plantID) const {
    std::vector<unsigned> out;
    for (const Shoot& s : impl_->store.plant(plantID).shoots)
        if (!s.removed && s.children.empty()) out.push_back(s.id);
    return out;
}

std::vector<unsigned> PlantArchitecture::getShootPathToRoot(unsigned plantID,
                                                            unsigned shootID) const {
    const PlantInstance& p = impl_->store.plant(plantID);
    PlantStore::shoot(p, shootID);
    std::vector<unsigned> path;
    for (int id = int(shootID); id >= 0; id = p.shoots[unsigned(id)].parent)
        path.push_back(unsigned(id));
    return path;
}

vec3 PlantArchitecture::getNodePosition(unsigned plantID, unsigned shootID, unsigned node) const {
    const PlantInstance& p = impl_->store.plant(plantID);
    const Shoot& s = PlantStore::shoot(p, shootID);
    checkNode(s, node);
    return shootNodePositions(p, shootID)[node + 1];
}

}  // namespace plantarch
