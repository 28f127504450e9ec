// PlantArchitecture's collision avoidance and attraction point methods.

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>
#include <type_traits>

#include "api/facade_impl.h"
#include "collision/attraction.h"
#include "collision/collision_world.h"
#include "collision/growth_driver.h"
#include "core/value_text.h"
#include "plantarch/Error.h"

namespace plantarch {

namespace {

// A value is reported as it was given: a float option in its shortest float form (0.2, not
// the double nearest the float 0.2).
template <typename T>
void checkRange(const char* name, T v, double lo, double hi, bool openLow, const char* range) {
    const double d = v;
    const bool ok = std::isfinite(d) && (openLow ? d > lo : d >= lo) && d <= hi;
    if (!ok) {
        const std::string shown =
            std::is_same_v<T, float> ? text::formatFloat(float(v)) : text::formatDouble(d);
        throw Error("collision option out of range",
                    {.parameter = name, .value = shown, .validRange = range});
    }
}

void checkAngle(const char* name, float v) {
    if (!(std::isfinite(v) && v > 0.0f && v < 180.0f))
        throw Error("collision option out of range", {.parameter = name,
                                                      .value = text::formatFloat(v),
                                                      .validRange = "> 0 and < 180 degrees"});
}

void checkRays(const char* name, unsigned n) {
    if (n < 8 || n > 16384)
        throw Error("collision option out of range",
                    {.parameter = name, .value = std::to_string(n), .validRange = "8 to 16384"});
}

void checkObjects(const Context& ctx, const std::vector<ObjectID>& ids, const char* name) {
    for (ObjectID id : ids)
        if (!ctx.doesObjectExist(id))
            throw Error("no such object in the Context", {.parameter = name,
                                                          .value = std::to_string(id),
                                                          .validRange = "IDs of existing objects"});
}

void checkPoints(const std::vector<vec3>& points) {
    for (std::size_t i = 0; i < points.size(); ++i)
        if (!std::isfinite(points[i].x) || !std::isfinite(points[i].y) ||
            !std::isfinite(points[i].z))
            throw Error("attraction point is not finite",
                        {.parameter = "attraction_points[" + std::to_string(i) + "]",
                         .validRange = "finite coordinates in m"});
}

// Shoot types are labels (as plant structure files spell them, separated by spaces).
void checkShootTypes(const std::vector<std::string>& types) {
    for (const std::string& t : types) {
        if (!text::isLabel(t))
            throw Error("attraction shoot type is not a shoot type label",
                        {.parameter = "shoot_types",
                         .value = t,
                         .validRange = "letters, digits, '_' or '-'"});
    }
}

void validate(const AttractionPoints& a) {
    checkPoints(a.points);
    checkShootTypes(a.shootTypes);
    checkAngle("view_half_angle_deg", a.halfAngle);
    checkRange("look_ahead_distance", a.lookAhead, 0.0, 100.0, true, "> 0 and <= 100 m");
    checkRange("inertia", a.inertia, 0.0, 1.0, false, "0 to 1");
}

}  // namespace

void PlantArchitecture::enableSoftCollisionAvoidance(const SoftCollisionOptions& o) {
    checkAngle("view_half_angle_deg", o.cone.halfAngle);
    checkRange("look_ahead_distance", o.cone.lookAhead, 0.0, 100.0, true, "> 0 and <= 100 m");
    checkRays("ray_count", o.cone.rays);
    checkRange("inertia", o.cone.inertia, 0.0, 1.0, false, "0 to 1");
    checkRange("update_interval", o.updateInterval, 1.0 / 1024.0, 365.0, false,
               "1/1024 to 365 days");
    checkObjects(*context_, o.objects, "obstacle_objects");
    collision::World& w = collision::worldOf(impl_->collision);
    const bool wasOn = w.soft().has_value();
    w.setSoft(o, *context_);
    if (!wasOn) w.clock = 0.0;
    // Plants are (re)read at the next growth call: obstacle kinds may have changed.
    for (const auto& [id, plant] : impl_->store.plants) w.stale[id] = true;
}

void PlantArchitecture::disableSoftCollisionAvoidance() {
    if (impl_->collision.world) impl_->collision.world->setSoft(std::nullopt, *context_);
}

void PlantArchitecture::setCollisionRelevantOrgans(const CollisionOrgans& organs) {
    if (!impl_->collision.world || !impl_->collision.world->soft())
        throw Error("soft collision avoidance is not enabled",
                    {.parameter = "setCollisionRelevantOrgans",
                     .validRange = "call enableSoftCollisionAvoidance first"});
    SoftCollisionOptions o = *impl_->collision.world->soft();
    o.obstacles = organs;
    enableSoftCollisionAvoidance(o);
}

void PlantArchitecture::enableSolidObstacleAvoidance(const SolidObstacleOptions& o) {
    if (o.obstacles.empty())
        throw Error("no solid obstacles given",
                    {.parameter = "obstacle_IDs", .validRange = "at least one object ID"});
    checkObjects(*context_, o.obstacles, "obstacle_IDs");
    checkRange("avoidance_distance", o.avoidanceDistance, 0.0, 100.0, true, "> 0 and <= 100 m");
    checkAngle("view_half_angle_deg", o.coneHalfAngle);
    checkRays("ray_count", o.rays);
    collision::World& w = collision::worldOf(impl_->collision);
    w.setSolid(o, *context_);
}

void PlantArchitecture::disableSolidObstacleAvoidance() {
    if (impl_->collision.world) impl_->collision.world->setSolid(std::nullopt, *context_);
}

void PlantArchitecture::enableAttractionPoints(const AttractionPoints& a) {
    validate(a);
    collision::worldOf(impl_->collision).globalAttraction =
        std::make_shared<collision::AttractionIndex>(a);
}

// A plant's own points are its state (saved with it); the index is built when it grows.
void PlantArchitecture::enableAttractionPoints(unsigned plantID, const AttractionPoints& a) {
    PlantInstance& plant = impl_->store.plant(plantID);
    validate(a);
    plant.attraction = a;
}

namespace {

AttractionPoints current(const std::shared_ptr<const collision::AttractionIndex>& index,
                         const std::string& which) {
    if (!index)
        throw Error(
            "attraction points are not enabled" + which,
            {.parameter = "attraction_points", .validRange = "call enableAttractionPoints first"});
    return index->options();
}

AttractionPoints ownPoints(const PlantInstance& plant) {
    if (!plant.attraction)
        throw Error("attraction points are not enabled for plant " + std::to_string(plant.id),
                    {.parameter = "attraction_points",
                     .validRange = "call enableAttractionPoints(plantID, ...) first"});
    return *plant.attraction;
}

}  // namespace

void PlantArchitecture::updateAttractionPoints(const std::vector<vec3>& points) {
    AttractionPoints a =
        current(impl_->collision.world ? impl_->collision.world->globalAttraction : nullptr, "");
    a.points = points;
    enableAttractionPoints(a);
}

void PlantArchitecture::updateAttractionPoints(unsigned plantID, const std::vector<vec3>& points) {
    AttractionPoints a = ownPoints(impl_->store.plant(plantID));
    a.points = points;
    enableAttractionPoints(plantID, a);
}

void PlantArchitecture::appendAttractionPoints(const std::vector<vec3>& points) {
    AttractionPoints a =
        current(impl_->collision.world ? impl_->collision.world->globalAttraction : nullptr, "");
    a.points.insert(a.points.end(), points.begin(), points.end());
    enableAttractionPoints(a);
}

void PlantArchitecture::appendAttractionPoints(unsigned plantID, const std::vector<vec3>& points) {
    AttractionPoints a = ownPoints(impl_->store.plant(plantID));
    a.points.insert(a.points.end(), points.begin(), points.end());
    enableAttractionPoints(plantID, a);
}

void PlantArchitecture::disableAttractionPoints() {
    if (impl_->collision.world) impl_->collision.world->globalAttraction.reset();
}

void PlantArchitecture::disableAttractionPoints(unsigned plantID) {
    impl_->store.plant(plantID).attraction.reset();
    impl_->collision.attractionIndexes.erase(plantID);
}

std::vector<vec3> PlantArchitecture::getAttractionPoints(unsigned plantID) const {
    const PlantInstance& plant = impl_->store.plant(plantID);
    if (plant.attraction) return plant.attraction->points;
    const collision::World* w = impl_->collision.world.get();
    return w && w->globalAttraction ? w->globalAttraction->options().points : std::vector<vec3>{};
}

CollisionStats PlantArchitecture::getCollisionStats() const {
    return impl_->collision.world ? impl_->collision.world->snapshotStats() : CollisionStats{};
}

void PlantArchitecture::resetCollisionStats() {
    if (impl_->collision.world) impl_->collision.world->resetStats();
}

}  // namespace plantarch
