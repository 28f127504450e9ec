// --leaf-angles FAMILY[,NAME=VALUE...]: the phenology's leaf_angles group of the species,
// edited through editSpecies so every value gets the checks a species file's value gets.

#include "leaf_angle_option.h"

#include <map>
#include <sstream>

#include "plantarch/Error.h"
#include "plantarch/SpeciesIO.h"

namespace plantarch::cli {

void addLeafAngleOption(CLI::App& app, std::string& spec) {
    app.add_option("--leaf-angles", spec,
                   "Leaf angle distribution instead of the species': FAMILY[,NAME=VALUE...], e.g. "
                   "spherical, ellipsoidal,ellipsoidal_x=2, beta,beta_mean=40,beta_sd=15 "
                   "(names: the phenology's leaf_angles fields, docs/parameters.md)");
}

void loadSpeciesWithLeafAngles(PlantArchitecture& arch, const std::string& species,
                               const std::string& spec) {
    if (spec.empty()) {
        arch.loadPlantModelFromLibrary(species);
        return;
    }
    std::map<std::string, std::string> changes;
    std::istringstream in(spec);
    bool first = true;
    for (std::string item; std::getline(in, item, ',');) {
        const auto eq = item.find('=');
        if (first && eq == std::string::npos) {
            changes["phenology.leaf_angles.inclination"] = item;
        } else if (eq == std::string::npos || eq == 0) {
            throw Error("a leaf angle setting is written NAME=VALUE after the family",
                        {.parameter = "--leaf-angles",
                         .value = item,
                         .validRange = "FAMILY[,NAME=VALUE...]"});
        } else {
            const std::string key = "phenology.leaf_angles." + item.substr(0, eq);
            if (!changes.emplace(key, item.substr(eq + 1)).second)
                throw Error(
                    "a leaf angle setting is given twice",
                    {.parameter = "--leaf-angles", .value = item, .validRange = "each name once"});
        }
        first = false;
    }
    if (changes.empty())
        throw Error(
            "--leaf-angles needs a family",
            {.parameter = "--leaf-angles", .value = spec, .validRange = "FAMILY[,NAME=VALUE...]"});
    arch.loadPlantModel(editSpecies(loadSpecies(species), changes));
}

}  // namespace plantarch::cli
