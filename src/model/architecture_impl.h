#pragma once
// The declarations the per-phytomer functions of the library species
// (library/species_functions*.cpp) build on: the facade and the plant state. The facade's own
// state lives in api/facade_impl.h.

#include "plantarch/PlantArchitecture.h"
#include "plantarch/Species.h"
