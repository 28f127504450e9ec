#pragma once
// The organ prototypes every PlantArchitecture starts with (builtin_prototypes.cpp).

namespace plantarch {

class PlantArchitecture;

/// Registers the procedural leaf, the organ library's flower and fruit families and the
/// simple builtin flower and fruit with `arch`.
void registerBuiltinPrototypes(PlantArchitecture& arch);

}  // namespace plantarch
