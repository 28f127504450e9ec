#pragma once
// The named functions shoot types refer to: organ prototype builders and per-phytomer rules.
// A PlantArchitecture owns one; threads growing plants read it and never change it.

#include <map>
#include <set>
#include <string>

#include "plantarch/OrganFunctions.h"

namespace plantarch {

struct FunctionRegistry {
    std::map<std::string, LeafPrototypeFunction> leafPrototypes;
    std::map<std::string, FloralPrototypeFunction> floralPrototypes;
    std::map<std::string, PhytomerCreationFunction> creationFunctions;
    std::map<std::string, PhytomerCallbackFunction> callbackFunctions;
    /// Prototype functions registered by the user (over the library's or beside them): their
    /// shapes are this registry's own, never shared with other PlantArchitectures.
    std::set<std::string> userLeafPrototypes, userFloralPrototypes;

    /// The creation function `name` that shoot type `shootType` names; throws if none is
    /// registered under that name.
    const PhytomerCreationFunction& creation(const std::string& name,
                                             const std::string& shootType) const;
    /// The same for a phytomer callback function.
    const PhytomerCallbackFunction& callback(const std::string& name,
                                             const std::string& shootType) const;
};

}  // namespace plantarch
