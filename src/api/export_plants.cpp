// The plants of a PlantArchitecture as exporters describe them (plantarch/ExportPlants.h).

#include "plantarch/ExportPlants.h"

namespace plantarch {

std::vector<GltfPlant> exportPlants(const PlantArchitecture& arch) {
    std::vector<GltfPlant> plants;
    for (unsigned id : arch.getAllPlantIDs())
        plants.push_back({std::int32_t(id), arch.plant(id).name, arch.getPlantBasePosition(id),
                          arch.plant(id).age, arch.seed()});
    return plants;
}

}  // namespace plantarch
