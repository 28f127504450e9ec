// The organ library's family table, parameter validation, registration and the part
// collector that applies the prototype convention (OrganLibrary.h).

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "geometry/organ_library_internal.h"
#include "plantarch/Error.h"
#include "plantarch/NumberRange.h"

namespace plantarch {

namespace organs {

namespace {

const std::vector<Family>& familyTable() {
    static const std::vector<Family> table = [] {
        std::vector<Family> all;
        for (auto* group : {&flowerFamilies, &fruitFamilies, &podAndDrupeFamilies, &cerealFamilies})
            for (Family& f : group()) all.push_back(std::move(f));
        return all;
    }();
    return table;
}

const Family* findFamily(std::string_view name) {
    for (const Family& f : familyTable())
        if (f.info.name == name) return &f;
    return nullptr;
}

std::string number(float v) {
    return fmt::format("{}", v);
}

std::string familyNames() {
    std::string s = "one of:";
    for (const Family& f : familyTable()) s += " " + f.info.name;
    return s;
}

std::string parameterNames(const FloralFamilyInfo& info) {
    std::string s = "one of:";
    for (const FloralParameterInfo& p : info.parameters) s += " " + p.name;
    return s;
}

const Family& requireFamily(std::string_view name) {
    if (const Family* f = findFamily(name)) return *f;
    throw Error(
        "unknown flower/fruit prototype family",
        {.parameter = "prototype family", .value = std::string(name), .validRange = familyNames()});
}

void validate(const FloralFamilyInfo& info, const std::map<std::string, float>& given) {
    for (const auto& [name, value] : given) {
        const FloralParameterInfo* p = info.parameter(name);
        if (!p)
            throw Error(
                "not a parameter of the " + info.name + " prototype family",
                {.parameter = name, .value = number(value), .validRange = parameterNames(info)});
        const std::string range =
            rangeText({.min = p->min, .max = p->max, .whole = p->integer, .single = true});
        if (!std::isfinite(value) || value < p->min || value > p->max)
            throw Error("out of range for the " + info.name + " prototype family",
                        {.parameter = name, .value = number(value), .validRange = range});
        if (p->integer && value != std::round(value))
            throw Error("must be a whole number for the " + info.name + " prototype family",
                        {.parameter = name,
                         .value = number(value),
                         .validRange = "whole numbers from " + range});
    }
}

}  // namespace

// ---- parameters ---------------------------------------------------------------------------

Params::Params(const FloralFamilyInfo& info, const std::map<std::string, float>& given)
    : info_(&info), given_(&given) {
    validate(info, given);
}

float Params::operator()(std::string_view name) const {
    const FloralParameterInfo* p = info_->parameter(name);
    if (!p)
        throw std::logic_error("organ library: " + info_->name + " reads undeclared parameter " +
                               std::string(name));
    const auto it = given_->find(std::string(name));
    return it == given_->end() ? p->defaultValue : it->second;
}

int Params::count(std::string_view name) const {
    return int(std::lround((*this)(name)));
}

vec3 Params::color(std::string_view prefix) const {
    const std::string p(prefix);
    return {(*this)(p + "_r"), (*this)(p + "_g"), (*this)(p + "_b")};
}

FloralParameterInfo real(const char* name, float def, float min, float max, const char* doc) {
    return {name, def, min, max, false, doc};
}

FloralParameterInfo whole(const char* name, int def, int min, int max, const char* doc) {
    return {name, float(def), float(min), float(max), true, doc};
}

void addColor(std::vector<FloralParameterInfo>& table, const char* prefix, vec3 def,
              const char* what) {
    const char* channel[3] = {"_r", "_g", "_b"};
    const char* label[3] = {"red", "green", "blue"};
    for (int i = 0; i < 3; ++i)
        table.push_back({std::string(prefix) + channel[i], def[i], 0.0f, 1.0f, false,
                         std::string(what) + " colour, " + label[i] + " (sRGB 0..1)"});
}

unsigned resolution(unsigned subdivisions, float perStep, unsigned base) {
    const unsigned s = std::max(2u, subdivisions);
    return base + unsigned(std::lround(perStep * float(s)));
}

// ---- parts ---------------------------------------------------------------------------------

void PartSet::declare(const std::string& name, vec3 color) {
    parts_.push_back({Mesh{}, Material{glm::clamp(color, vec3(0.0f), vec3(1.0f)), "", name}});
}

void PartSet::add(const std::string& name, const Mesh& mesh) {
    for (PrototypePart& p : parts_)
        if (p.material.name == name) {
            p.mesh.append(mesh);
            return;
        }
    throw std::logic_error("organ library: undeclared part " + name);
}

namespace {

// Drops triangles that repeat a vertex or have (almost) no area; they add nothing to the
// surface and upset normals in renderers and exporters.
void dropDegenerate(Mesh& m) {
    std::vector<std::uint32_t> kept;
    kept.reserve(m.indices.size());
    for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
        const std::uint32_t a = m.indices[t], b = m.indices[t + 1], c = m.indices[t + 2];
        if (a == b || b == c || a == c) continue;
        const glm::dvec3 pa = m.positions[a], pb = m.positions[b], pc = m.positions[c];
        if (glm::length(glm::cross(pb - pa, pc - pa)) < 2e-12) continue;
        kept.insert(kept.end(), {a, b, c});
    }
    m.indices = std::move(kept);
}

}  // namespace

OrganPrototype PartSet::finish() {
    OrganPrototype out;
    AABB box;
    for (PrototypePart& p : parts_)
        if (!p.mesh.empty()) {
            for (const vec3& v : p.mesh.positions) box.add(v);
            out.push_back(std::move(p));
        }
    parts_.clear();
    const float length = box.max.x - box.min.x;
    if (out.empty() || !(length > 0.0f))
        throw std::logic_error("organ library: a prototype with no length along x");
    for (PrototypePart& p : out) {
        for (vec3& v : p.mesh.positions)
            v = {(v.x - box.min.x) / length, v.y / length, v.z / length};
        dropDegenerate(p.mesh);
    }
    return out;
}

}  // namespace organs

// ---- public API ------------------------------------------------------------------------------

const FloralParameterInfo* FloralFamilyInfo::parameter(std::string_view name) const {
    for (const FloralParameterInfo& p : parameters)
        if (p.name == name) return &p;
    return nullptr;
}

const std::vector<FloralFamilyInfo>& floralFamilies() {
    static const std::vector<FloralFamilyInfo> infos = [] {
        std::vector<FloralFamilyInfo> v;
        for (const organs::Family& f : organs::familyTable()) v.push_back(f.info);
        return v;
    }();
    return infos;
}

bool isFloralFamily(std::string_view name) {
    return organs::findFamily(name) != nullptr;
}

const FloralFamilyInfo& floralFamily(std::string_view name) {
    const organs::Family& f = organs::requireFamily(name);
    return floralFamilies()[std::size_t(&f - organs::familyTable().data())];
}

void validateFloralParameters(std::string_view family,
                              const std::map<std::string, float>& parameters) {
    organs::validate(organs::requireFamily(family).info, parameters);
}

OrganPrototype buildFloralPrototype(std::string_view family, const FloralPrototypeRequest& request,
                                    Rng& rng) {
    const organs::Family& f = organs::requireFamily(family);
    const organs::Params params(f.info, request.parameters);
    return f.build(request, params, rng);
}

std::vector<std::pair<std::string, FloralPrototypeFunction>> floralFamilyFunctions() {
    std::vector<std::pair<std::string, FloralPrototypeFunction>> functions;
    for (const organs::Family& f : organs::familyTable()) {
        const organs::Family* family = &f;  // the table lives for the whole program
        functions.emplace_back(f.info.name,
                               [family](const FloralPrototypeRequest& request, Rng& rng) {
                                   const organs::Params params(family->info, request.parameters);
                                   return family->build(request, params, rng);
                               });
    }
    return functions;
}

}  // namespace plantarch
