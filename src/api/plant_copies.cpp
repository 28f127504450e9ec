// PlantArchitecture: copies of plants and plants moved (the state carried by
// model/plant_move.h, geometry made again from it).

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <string>

#include "api/facade_impl.h"
#include "core/math.h"
#include "core/value_text.h"
#include "model/plant_move.h"
#include "plant_io/plant_structure.h"
#include "plantarch/Error.h"

namespace plantarch {

namespace {

void checkFinite(const vec3& v, const char* parameter) {
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
        throw Error("must be finite", {.parameter = parameter,
                                       .value = text::formatVec3(v),
                                       .validRange = "finite numbers, m"});
}

// The rotation that turns the vertical and x into the frame of a base stem turned by `r`.
glm::mat3 frameRotation(const AxisRotation& r) {
    for (float a : {r.pitch, r.yaw, r.roll})
        if (!std::isfinite(a))
            throw Error("must be finite", {.parameter = "rotation",
                                           .value = text::formatFloat(a),
                                           .validRange = "finite angles, degrees"});
    const AxisFrame f = turnedFrame({vec3(0, 0, 1), vec3(1, 0, 0)}, r.pitch, r.yaw, r.roll);
    return glm::mat3(f.reference, glm::cross(f.axis, f.reference), f.axis);
}

}  // namespace

unsigned PlantArchitecture::duplicatePlantInstance(unsigned plantID, const vec3& base_position,
                                                   const AxisRotation& rotation, float age) {
    const PlantInstance& source = impl_->store.plant(plantID);
    checkFinite(base_position, "base_position");
    if (!(age >= 0.0f) || !std::isfinite(age))
        throw Error(
            "invalid plant age",
            {.parameter = "age", .value = text::formatFloat(age), .validRange = ">= 0 days"});
    PlantInstance copy = source;
    plant_io::clearObjectIDs(copy);
    movePlant(copy, {frameRotation(rotation), base_position, double(age)});
    PlantStore& store = impl_->store;
    copy.id = context_->reservePlantIDs(1);
    copy.stream = store.nextStream++;
    copy.rng = Rng::forPlant(seed_, copy.stream);
    const unsigned id = copy.id;
    store.plants.emplace(id, std::move(copy));
    try {
        updateGeometry(id);
    } catch (...) {
        deletePlantInstance(id);
        throw;
    }
    return id;
}

void PlantArchitecture::setPlantBasePosition(unsigned plantID, const vec3& base_position) {
    PlantInstance& p = impl_->store.plant(plantID);
    checkFinite(base_position, "base_position");
    const vec3 shift = base_position - p.base;
    movePlant(p, {glm::mat3(1.0f), base_position, p.age});
    updateGeometry(plantID);
    if (const auto t = impl_->trellis.find(plantID); t != impl_->trellis.end())
        for (ObjectID id : t->second)
            if (context_->doesObjectExist(id))
                context_->transformObject(id, glm::translate(mat4(1.0f), shift));
}

std::string PlantArchitecture::getPlantName(unsigned plantID) const {
    return impl_->store.plant(plantID).name;
}

}  // namespace plantarch
