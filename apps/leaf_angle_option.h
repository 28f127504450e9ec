#pragma once
// --leaf-angles of `build` and `canopy`: the species' leaf angle distribution set on the
// command line instead of in its file (docs/measured-plants.md, "Leaf angle distributions").

#include <CLI/CLI.hpp>
#include <string>

#include "plantarch/PlantArchitecture.h"

namespace plantarch::cli {

/// Adds --leaf-angles FAMILY[,NAME=VALUE...] to `app`, kept in `spec`.
void addLeafAngleOption(CLI::App& app, std::string& spec);

/// Loads `species` into `arch` as loadPlantModelFromLibrary does, with the leaf angle
/// distribution of `spec` (none given: the species' own). Throws plantarch::Error for a bad
/// spec, naming the parameter and its valid values.
void loadSpeciesWithLeafAngles(PlantArchitecture& arch, const std::string& species,
                               const std::string& spec);

}  // namespace plantarch::cli
