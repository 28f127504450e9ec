// A species' shoot types and <build> steps run through the facade: the shoots of a plant's
// initial structure made by addBaseStemShoot, appendShoot and addChildShoot
// (plantarch/SpeciesBuild.h).

#include <cmath>
#include <limits>

#include "core/math.h"
#include "core/value_text.h"
#include "library/expression.h"
#include "library/species_xml.h"
#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/SpeciesBuild.h"
#include "plantarch/SpeciesIO.h"

namespace plantarch {

namespace {

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

}  // namespace

void defineSpeciesShootTypes(PlantArchitecture& arch, const SpeciesModel& species) {
    for (const auto& [label, params] : speciesShootTypes(species)) {
        try {
            arch.defineShootType(label, params);
        } catch (const Error& e) {
            throw e.withFile(species.sourceFile, species.lineOf(e.parameter()));
        }
    }
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
