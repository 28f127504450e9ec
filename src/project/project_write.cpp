// Writing project files: every field, numbers in their shortest form that reads back the same.

#include <cmath>
#include <nlohmann/json.hpp>

#include "core/value_text.h"
#include "plantarch/Error.h"
#include "plantarch/OutputFiles.h"
#include "plantarch/Project.h"
#include "project/project_fields.h"

namespace plantarch {

namespace {

// Keys in the order written (a project file reads as its blocks were built).
using OrderedJson = nlohmann::ordered_json;

// A float as the shortest decimal that reads back to it (0.3, not 0.30000001192092896), and
// whole values as integers.
OrderedJson num(float v) {
    if (v == std::floor(v) && std::fabs(v) < 1e15f) return std::int64_t(v);
    return std::stod(text::formatFloat(v));
}

OrderedJson pair(const vec2& v) {
    return OrderedJson::array({num(v.x), num(v.y)});
}

OrderedJson point(const vec3& v) {
    return OrderedJson::array({num(v.x), num(v.y), num(v.z)});
}

OrderedJson block(const ProjectBlock& b) {
    OrderedJson j;
    j["name"] = b.name;
    j["species"] = b.species;
    j["layout"] = layoutName(b.layout);
    j["origin"] = point(b.origin);
    if (b.layout == ProjectBlock::Layout::Grid) {
        j["count"] = OrderedJson::array({b.count.x, b.count.y});
        j["spacing"] = pair(b.spacing);
    }
    if (b.layout == ProjectBlock::Layout::Scatter) {
        j["count"] = b.plants;
        j["area"] = pair(b.area);
    }
    if (b.layout == ProjectBlock::Layout::Skeleton)
        j["skeleton"] = {{"file", b.skeleton},
                         {"unit", num(b.skeletonUnit)},
                         {"spacing", num(b.skeletonSpacing)}};
    if (b.layout == ProjectBlock::Layout::Grid || b.layout == ProjectBlock::Layout::Scatter)
        j["germination"] = num(b.germination);
    if (b.age) j["age"] = num(*b.age);
    if (b.seed) j["seed"] = *b.seed;
    if (b.layout != ProjectBlock::Layout::Skeleton) {
        OrderedJson params = OrderedJson::object();
        for (const auto& [name, value] : b.parameters) params[name] = num(value);
        j["parameters"] = params;
        j["trellis"] = b.trellis;
    }
    OrderedJson edits = OrderedJson::object();
    for (const auto& [name, value] : b.speciesParameters) edits[name] = value;
    j["species_parameters"] = edits;
    j["bend"] = b.bend;
    j["elastic_modulus"] = b.elasticModulus ? num(*b.elasticModulus) : OrderedJson(nullptr);
    return j;
}

}  // namespace

std::string writeProjectString(const Project& p) {
    OrderedJson j;
    j["plantarch_project"] = kProjectVersion;
    j["name"] = p.name;
    j["seed"] = p.seed;
    j["mesh_detail"] = num(p.meshDetail);
    j["ground"] =
        p.ground ? OrderedJson{{"size", pair(p.ground->size)}, {"center", pair(p.ground->center)}}
                 : OrderedJson(nullptr);
    j["soft_collision"] = {
        {"enabled", p.softCollision},
        {"cone", OrderedJson::array({num(p.softCone.halfAngle), num(p.softCone.lookAhead),
                                     p.softCone.rays, num(p.softCone.inertia)})}};
    j["obstacles"] = {{"files", p.obstacleFiles},
                      {"avoid_distance", num(p.avoidDistance)},
                      {"fruit_adjustment", p.fruitAdjustment}};
    OrderedJson points = OrderedJson::array();
    for (const vec3& v : p.attractionPoints) points.push_back(point(v));
    j["attraction"] = {
        {"enabled", p.attraction},
        {"points", points},
        {"file", p.attractionFile.empty() ? OrderedJson(nullptr) : OrderedJson(p.attractionFile)},
        {"cone",
         OrderedJson::array({num(p.attractionCone.halfAngle), num(p.attractionCone.lookAhead),
                             num(p.attractionCone.inertia)})}};
    OrderedJson blocks = OrderedJson::array();
    for (const ProjectBlock& b : p.blocks) blocks.push_back(block(b));
    j["blocks"] = blocks;
    if (p.physiology) {
        const PhysiologySeason& s = p.physiology->season;
        OrderedJson events = OrderedJson::array();
        for (const Fertilisation& f : s.fertilise)
            events.push_back(OrderedJson::array({num(float(f.age)), num(float(f.grams))}));
        const bool clear = p.physiology->weatherFile.empty();
        j["physiology"] = {
            {"carbon", s.carbon},
            {"nitrogen", s.nitrogen},
            {"location", OrderedJson::array({s.location.latitude, s.location.longitude})},
            {"start",
             clear ? OrderedJson(formatUTCTime(s.start).substr(0, 10)) : OrderedJson(nullptr)},
            {"weather", clear ? OrderedJson(nullptr) : OrderedJson(p.physiology->weatherFile)},
            {"clearness", s.clearness},
            {"light_every", s.lightEvery},
            {"days", p.physiology->days},
            {"fertilise", events}};
    }
    return j.dump(2) + "\n";
}

void writeProjectFile(const Project& project, const std::string& path) {
    writeFileAtomically(path, writeProjectString(project));
}

}  // namespace plantarch
