// A species' build parameters and the structures its expressions place around a plant
// (attraction points, trellis); the <build> steps themselves run in api/species_steps.cpp.

#include <cmath>
#include <limits>

#include "core/math.h"
#include "core/value_text.h"
#include "geometry/tube.h"
#include "library/expression.h"
#include "library/species_xml.h"
#include "plantarch/Error.h"
#include "plantarch/NumberRange.h"
#include "plantarch/SpeciesIO.h"

namespace plantarch {

namespace {

std::vector<std::string> buildParameterNames(const SpeciesModel& s) {
    std::vector<std::string> names;
    for (const BuildParameter& p : s.buildParameters) names.push_back(p.name);
    return names;
}

// Evaluates the expressions of a species element (<attraction_points>, <trellis>) with the
// build parameters; errors name the element and the attribute.
class ElementEvaluator {
public:
    ElementEvaluator(const SpeciesModel& s, std::string element,
                     const std::map<std::string, float>& parameters, Rng rng)
        : species_(s), element_(std::move(element)), rng_(rng) {
        for (const auto& [name, value] : parameters) variables_[name] = value;
    }

    double number(int line, const std::string& parameter, const std::string& text) {
        try {
            return expr::evaluate(text, variables_, rng_);
        } catch (const Error& e) {
            ErrorContext c = e.context();
            c.file = species_.sourceFile;
            c.line = line;
            c.parameter = element_ + "." + parameter;
            throw Error(e.message(), c);
        }
    }

    vec3 vector(int line, const std::string& parameter, const std::string& text) {
        const std::vector<std::string> parts = species_xml::splitVector(text);
        if (parts.size() != 3)
            throw Error("expected three expressions x, y, z separated by commas",
                        {.file = species_.sourceFile,
                         .line = line,
                         .parameter = element_ + "." + parameter,
                         .value = text,
                         .validRange = "e.g. \"0, 0, wire_height\""});
        return {float(number(line, parameter, parts[0])), float(number(line, parameter, parts[1])),
                float(number(line, parameter, parts[2]))};
    }

    // A length: finite and within (0, max] m.
    float length(int line, const std::string& parameter, const std::string& text, double max) {
        const double v = number(line, parameter, text);
        if (!(v > 0.0 && v <= max))
            throw Error("out of range",
                        {.file = species_.sourceFile,
                         .line = line,
                         .parameter = element_ + "." + parameter,
                         .value = text::formatDouble(v),
                         .validRange = "> 0 and <= " + text::formatDouble(max) + " m"});
        return float(v);
    }

private:
    const SpeciesModel& species_;
    std::string element_;
    Rng rng_;
    std::map<std::string, double> variables_;
};

}  // namespace

AttractionPoints speciesAttractionPoints(const SpeciesModel& species, std::uint64_t seed,
                                         unsigned plantID, const vec3& base,
                                         const std::map<std::string, float>& overrides) {
    if (!species.attraction)
        throw Error("species declares no attraction points",
                    {.file = species.sourceFile, .parameter = "attraction_points"});
    const SpeciesAttraction& a = *species.attraction;
    ElementEvaluator ev(species, "attraction_points", resolveBuildParameters(species, overrides),
                        Rng::forPlant(seed, 3 * (std::uint64_t(1) << 61) + plantID));
    AttractionPoints out;
    out.halfAngle = float(ev.number(a.line, "half_angle", a.halfAngle));
    out.lookAhead = float(ev.number(a.line, "look_ahead", a.lookAhead));
    out.inertia = float(ev.number(a.line, "inertia", a.inertia));
    out.shootTypes = a.shootTypes;
    auto outOfRange = [&](const char* what, double v, const char* range) {
        throw Error("out of range", {.file = species.sourceFile,
                                     .line = a.line,
                                     .parameter = std::string("attraction_points.") + what,
                                     .value = text::formatDouble(v),
                                     .validRange = range});
    };
    if (!(out.halfAngle > 0.0f && out.halfAngle < 180.0f))
        outOfRange("half_angle", out.halfAngle, "> 0 and < 180 degrees");
    if (!(out.lookAhead > 0.0f && out.lookAhead <= 100.0f))
        outOfRange("look_ahead", out.lookAhead, "> 0 and <= 100 m");
    if (!(out.inertia >= 0.0f && out.inertia <= 1.0f)) outOfRange("inertia", out.inertia, "0 to 1");
    for (std::size_t w = 0; w < a.wires.size(); ++w) {
        const SpeciesAttraction::Wire& wire = a.wires[w];
        const std::string path = "wire[" + std::to_string(w + 1) + "]";
        const vec3 from = base + ev.vector(wire.line, path + ".from", wire.from);
        const vec3 to = base + ev.vector(wire.line, path + ".to", wire.to);
        const double spacing = ev.number(wire.line, path + ".spacing", wire.spacing);
        const double length = glm::length(to - from);
        if (!(spacing > 0.0) || length / spacing > 1e6)
            throw Error("wire point spacing out of range",
                        {.file = species.sourceFile,
                         .line = wire.line,
                         .parameter = "attraction_points." + path + ".spacing",
                         .value = text::formatDouble(spacing),
                         .validRange = "> 0 m and at most 1e6 points per wire"});
        const int segments = std::max(1, int(std::ceil(length / spacing - 1e-4)));
        for (int k = 0; k <= segments; ++k)
            out.points.push_back(glm::mix(from, to, float(k) / float(segments)));
    }
    for (std::size_t p = 0; p < a.points.size(); ++p)
        out.points.push_back(base + ev.vector(a.points[p].line,
                                              "point[" + std::to_string(p + 1) + "].at",
                                              a.points[p].at));
    return out;
}

std::vector<TrellisPart> speciesTrellis(const SpeciesModel& species, std::uint64_t seed,
                                        unsigned plantID, const vec3& base,
                                        const std::map<std::string, float>& overrides) {
    if (!species.trellis)
        throw Error("species declares no trellis",
                    {.file = species.sourceFile, .parameter = "trellis"});
    const SpeciesTrellis& t = *species.trellis;
    ElementEvaluator ev(species, "trellis", resolveBuildParameters(species, overrides),
                        Rng::forPlant(seed, 5 * (std::uint64_t(1) << 60) + plantID));
    auto tube = [](vec3 a, vec3 b, float radius, unsigned sides) {
        const std::vector<vec3> points = {a, b};
        const std::vector<float> radii = {radius, radius};
        const std::vector<geometry::Ring> rings =
            geometry::tubeRings(points, radii, anyPerpendicular(glm::normalize(b - a)));
        return geometry::tubeMesh(rings, 0, rings.size() - 1, sides);
    };
    std::vector<TrellisPart> out;
    for (std::size_t i = 0; i < t.posts.size(); ++i) {
        const SpeciesTrellis::Post& p = t.posts[i];
        const std::string path = "post[" + std::to_string(i + 1) + "]";
        const std::vector<std::string> xy = species_xml::splitVector(p.at);
        const vec3 foot = base + vec3(float(ev.number(p.line, path + ".at", xy.at(0))),
                                      float(ev.number(p.line, path + ".at", xy.at(1))), 0.0f);
        const float height = ev.length(p.line, path + ".height", p.height, 100.0);
        const float radius = ev.length(p.line, path + ".radius", p.radius, 1.0);
        out.push_back({TrellisPart::Kind::Post, tube(foot, foot + vec3(0, 0, height), radius, 12)});
    }
    for (std::size_t i = 0; i < t.wires.size(); ++i) {
        const SpeciesTrellis::Wire& w = t.wires[i];
        const std::string path = "wire[" + std::to_string(i + 1) + "]";
        const vec3 from = base + ev.vector(w.line, path + ".from", w.from);
        const vec3 to = base + ev.vector(w.line, path + ".to", w.to);
        const float radius = ev.length(w.line, path + ".radius", w.radius, 1.0);
        if (!(glm::length(to - from) > 1e-4f))
            throw Error("a wire needs two different ends",
                        {.file = species.sourceFile,
                         .line = w.line,
                         .parameter = "trellis." + path,
                         .value = w.from + " to " + w.to,
                         .validRange = "ends at least 0.1 mm apart"});
        out.push_back({TrellisPart::Kind::Wire, tube(from, to, radius, 6)});
    }
    return out;
}

std::map<std::string, float> resolveBuildParameters(const SpeciesModel& species,
                                                    const std::map<std::string, float>& overrides) {
    std::map<std::string, float> values;
    for (const BuildParameter& p : species.buildParameters) values[p.name] = p.value;
    const std::vector<std::string> names = buildParameterNames(species);
    for (const auto& [name, value] : overrides) {
        const BuildParameter* found = nullptr;
        for (const BuildParameter& p : species.buildParameters)
            if (p.name == name) found = &p;
        if (!found) {
            const std::string near = text::closestMatch(name, names);
            throw Error("unknown build parameter of species '" + species.name + "'" +
                            (near.empty() ? "" : ", did you mean '" + near + "'?"),
                        {.parameter = name,
                         .value = text::formatFloat(value),
                         .validRange = names.empty() ? "the species has no build parameters"
                                                     : "one of: " + text::joinNames(names)});
        }
        if (!std::isfinite(value) || value < found->min || value > found->max)
            throw Error(
                "build parameter out of range",
                {.parameter = name,
                 .value = text::formatFloat(value),
                 .validRange = rangeText({.min = found->min, .max = found->max, .single = true}) +
                               (found->unit.empty() ? "" : " " + found->unit)});
        values[name] = value;
    }
    return values;
}

}  // namespace plantarch
