#pragma once
// The organ prototypes every PlantArchitecture starts with (builtin_prototypes.cpp).

#include <string>
#include <utility>
#include <vector>

#include "plantarch/OrganFunctions.h"

namespace plantarch {

struct BuiltinPrototypes {
    std::vector<std::pair<std::string, LeafPrototypeFunction>> leaves;
    std::vector<std::pair<std::string, FloralPrototypeFunction>> floral;
};

/// The procedural leaf, the organ library's flower and fruit families and the simple builtin
/// flower and fruit, by name, in the order a PlantArchitecture registers them.
BuiltinPrototypes builtinPrototypes();

}  // namespace plantarch
