#include "model/plant_store.h"

#include <utility>

#include "plantarch/Error.h"

namespace plantarch {

PlantInstance& PlantStore::plant(unsigned id) {
    return const_cast<PlantInstance&>(std::as_const(*this).plant(id));
}

const PlantInstance& PlantStore::plant(unsigned id) const {
    auto it = plants.find(id);
    if (it == plants.end()) {
        std::string range = plants.empty() ? "no plants exist"
                                           : std::to_string(plants.begin()->first) + " to " +
                                                 std::to_string(plants.rbegin()->first);
        throw Error("no such plant",
                    {.parameter = "plantID", .value = std::to_string(id), .validRange = range});
    }
    return it->second;
}

Shoot& PlantStore::shoot(PlantInstance& p, unsigned id) {
    return const_cast<Shoot&>(shoot(std::as_const(p), id));
}

const Shoot& PlantStore::shoot(const PlantInstance& p, unsigned id) {
    if (id >= p.shoots.size() || p.shoots[id].removed)
        throw Error(
            "no such shoot on plant " + std::to_string(p.id),
            {.parameter = "shootID",
             .value = std::to_string(id),
             .validRange = p.shoots.empty() ? "the plant has no shoots"
                                            : "0 to " + std::to_string(p.shoots.size() - 1)});
    return p.shoots[id];
}

const ShootParameters& PlantStore::shootTypeFor(PlantInstance& p, const std::string& label) const {
    auto it = p.shootTypes.find(label);
    if (it != p.shootTypes.end()) return it->second;
    auto global = shootTypes.find(label);
    if (global == shootTypes.end()) {
        std::string known;
        for (const auto& [name, params] : shootTypes) known += (known.empty() ? "" : ", ") + name;
        throw Error("unknown shoot type",
                    {.parameter = "shoot_type_label",
                     .value = label,
                     .validRange = known.empty() ? "no shoot types defined" : "one of: " + known});
    }
    return p.shootTypes.emplace(label, global->second).first->second;
}

}  // namespace plantarch
