// From a species to a plant: defining its shoot types and building its initial structure
// from the <build> steps through the manual building API.

#include <cmath>
#include <limits>

#include "core/math.h"
#include "core/value_text.h"
#include "geometry/tube.h"
#include "library/expression.h"
#include "library/species_xml.h"
#include "plantarch/Error.h"
#include "plantarch/NumberRange.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/SpeciesIO.h"

namespace plantarch {

namespace {

std::vector<std::string> buildParameterNames(const SpeciesModel& s) {
    std::vector<std::string> names;
    for (const BuildParameter& p : s.buildParameters) names.push_back(p.name);
    return names;
}

// The manual building API names its arguments after the seed's listings; a step's attribute
// is what the species file calls the same value.
std::string attributeFor(const std::string& apiParameter) {
    static const std::map<std::string, std::string> names = {
        {"current_node_number", "nodes"},
        {"base_rotation", "pitch"},
        {"internode_radius", "radius"},
        {"internode_length_max", "internode_length"},
        {"internode_length_scale_factor_fraction", "internode_scale"},
        {"leaf_scale_factor_fraction", "leaf_scale"},
        {"radius_taper", "taper"},
        {"parent_node_index", "node"},
        {"petiole_index", "petiole"},
        {"shoot_type_label", "type"}};
    auto it = names.find(apiParameter);
    return it == names.end() ? "" : it->second;
}

class StepRunner {
public:
    StepRunner(PlantArchitecture& arch, unsigned plantID, const SpeciesModel& species,
               const std::map<std::string, float>& parameters)
        : arch_(arch),
          plantID_(plantID),
          species_(species),
          rng_(Rng::forPlant(arch.seed(), (std::uint64_t(1) << 62) + arch.plantStream(plantID))) {
        for (const auto& [name, value] : parameters) variables_[name] = value;
        variables_["i"] = 0.0;
        variables_["parent_i"] = 0.0;
    }

    std::vector<unsigned> run() {
        int index = 0;
        for (const BuildStep& step : species_.build) runStep(step, ++index);
        return created_;
    }

private:
    std::string stepPath(const BuildStep& step, int index) const {
        const std::string kind = species_xml::buildStepElement(step.kind);
        return "build." + (step.id.empty() ? kind + "[" + std::to_string(index) + "]" : step.id);
    }

    [[noreturn]] void fail(const BuildStep& step, const std::string& path,
                           const std::string& message, std::string value = "",
                           std::string validRange = "") const {
        throw Error(message, {.file = species_.sourceFile,
                              .line = step.line,
                              .parameter = path,
                              .value = std::move(value),
                              .validRange = std::move(validRange)});
    }

    double number(const BuildStep& step, const std::string& path, const std::string& attribute,
                  const std::string& expression) {
        try {
            return expr::evaluate(expression, variables_, rng_);
        } catch (const Error& e) {
            ErrorContext c = e.context();
            c.file = species_.sourceFile;
            c.line = step.line;
            c.parameter = path + "." + attribute;
            throw Error(e.message(), c);
        }
    }

    unsigned whole(const BuildStep& step, const std::string& path, const std::string& attribute,
                   const std::string& expression, int minimum) {
        const double v = std::round(number(step, path, attribute, expression));
        if (!(v >= double(minimum) && v <= 1000000.0)) {
            const std::string value = text::formatDouble(v);
            fail(step, path + "." + attribute, "out of range",
                 value == expression ? value : value + " (from '" + expression + "')",
                 std::to_string(minimum) + " to 1000000");
        }
        return unsigned(v);
    }

    float real(const BuildStep& step, const std::string& path, const std::string& attribute,
               const std::string& expression) {
        return float(number(step, path, attribute, expression));
    }

    void runStep(const BuildStep& step, int index) {
        const std::string path = stepPath(step, index);
        auto type = species_.shootTypes.find(step.shootType);
        if (type == species_.shootTypes.end())
            fail(step, path + ".type", "unknown shoot type", step.shootType);
        std::vector<int> parents = {-1};
        if (step.kind != BuildStep::Kind::BaseStem) {
            auto it = shootsByStep_.find(step.parent);
            if (it == shootsByStep_.end())
                fail(step, path + ".parent", "unknown parent step", step.parent,
                     "the id of an earlier step");
            parents.assign(it->second.begin(), it->second.end());
        }
        std::vector<unsigned>& made = shootsByStep_[step.id];
        for (std::size_t p = 0; p < parents.size(); ++p) {
            variables_["parent_i"] = double(p);
            variables_["i"] = 0.0;
            const unsigned copies = step.kind == BuildStep::Kind::Child
                                        ? whole(step, path, "repeat", step.repeat, 0)
                                        : 1u;
            for (unsigned i = 0; i < copies; ++i) {
                variables_["i"] = double(i);
                const unsigned id = makeShoot(step, path, type->second, parents[p]);
                made.push_back(id);
                created_.push_back(id);
            }
        }
        if (step.id.empty()) shootsByStep_.erase(step.id);
    }

    // Evaluates the step's attributes (in the documented order) and calls the building API.
    unsigned makeShoot(const BuildStep& step, const std::string& path, const ShootParameters& type,
                       int parent) {
        ShootSpec spec;
        spec.shootType = step.shootType;
        spec.phytomers = whole(step, path, "nodes", step.nodes, 1);
        unsigned node = 0;
        unsigned petiole = 0;
        if (step.kind == BuildStep::Kind::Child) {
            node = whole(step, path, "node", step.parentNode, 0);
            petiole = whole(step, path, "petiole", step.petiole, 0);
        }
        spec.baseRotation.pitch = real(step, path, "pitch", step.pitch);
        spec.baseRotation.yaw = real(step, path, "yaw", step.yaw);
        spec.baseRotation.roll = real(step, path, "roll", step.roll);
        spec.size.internodeRadius =
            step.radius.empty() ? type.phytomer_parameters.internode.radius_initial.sample(rng_)
                                : real(step, path, "radius", step.radius);
        spec.size.internodeLengthMax =
            step.internodeLength.empty()
                ? type.internode_length_max.sample(rng_)
                : real(step, path, "internode_length", step.internodeLength);
        spec.size.internodeLengthScale = real(step, path, "internode_scale", step.internodeScale);
        spec.size.leafScale = real(step, path, "leaf_scale", step.leafScale);
        spec.radiusTaper = real(step, path, "taper", step.taper);
        try {
            unsigned id = 0;
            switch (step.kind) {
                case BuildStep::Kind::BaseStem:
                    id = arch_.addBaseStemShoot(plantID_, spec);
                    break;
                case BuildStep::Kind::Append:
                    id = arch_.appendShoot(plantID_, unsigned(parent), spec);
                    break;
                case BuildStep::Kind::Child:
                    id = arch_.addChildShoot(plantID_, unsigned(parent), node, spec, petiole);
                    break;
            }
            if (!step.leaves) arch_.removeShootLeaves(plantID_, id);
            if (!step.vegetativeBuds) arch_.removeShootAxillaryVegetativeBuds(plantID_, id);
            if (!step.floralBuds) arch_.removeShootFloralBuds(plantID_, id);
            if (!step.apex) arch_.removeShootApex(plantID_, id);
            return id;
        } catch (const Error& e) {
            // A node rule's error (its parameter the rule's path) is placed at the rule's own
            // line, not at the step that made the node; an error naming its file keeps it.
            const auto line = species_.lines.find(e.parameter());
            if (e.file().empty() && e.parameter().find(".node_rules[") != std::string::npos &&
                line != species_.lines.end())
                throw e.withFile(species_.sourceFile, line->second);
            if (!e.file().empty()) throw;
            const std::string attribute = attributeFor(e.parameter());
            ErrorContext c = e.context();
            // An error about another file (an OBJ model, a leaf image) keeps naming it.
            std::string message = e.message();
            if (!c.file.empty() && c.file != species_.sourceFile)
                message =
                    c.file + (c.line > 0 ? ":" + std::to_string(c.line) : "") + ": " + message;
            c.file = species_.sourceFile;
            c.line = step.line;
            c.parameter = attribute.empty() ? path : path + "." + attribute;
            throw Error(message, c);
        }
        return 0;
    }

    PlantArchitecture& arch_;
    unsigned plantID_;
    const SpeciesModel& species_;
    Rng rng_;
    std::map<std::string, double> variables_;
    std::map<std::string, std::vector<unsigned>> shootsByStep_;
    std::vector<unsigned> created_;
};

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

void defineSpeciesShootTypes(PlantArchitecture& arch, const SpeciesModel& species) {
    for (const auto& [label, params] : speciesShootTypes(species)) {
        try {
            arch.defineShootType(label, params);
        } catch (const Error& e) {
            throw e.withFile(species.sourceFile, species.lineOf(e.parameter()));
        }
    }
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

std::vector<unsigned> buildInitialStructure(PlantArchitecture& arch, unsigned plantID,
                                            const SpeciesModel& species,
                                            const std::map<std::string, float>& overrides) {
    const std::map<std::string, float> parameters = resolveBuildParameters(species, overrides);
    if (species.build.empty())
        throw Error("species has no build steps",
                    {.file = species.sourceFile, .parameter = "build"});
    return StepRunner(arch, plantID, species, parameters).run();
}

}  // namespace plantarch
