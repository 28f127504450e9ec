#pragma once
// Organ prototypes from OBJ files: a leaf, flower or fruit modelled in other software.
//
// The prototype convention: the organ's axis runs along +x from its attachment point at the
// origin to x = 1, with +z up. A model that does not follow it is rejected with an error
// saying what is off, unless normalization is asked for, which moves its base (smallest x)
// to the origin, centres it on the x axis there and scales it to unit length.

#include <string>

#include "plantarch/OrganFunctions.h"

namespace plantarch {

/// Reads an OBJ model (materials kept: one part per material run) as a prototype.
/// Throws plantarch::Error for a missing or malformed file, a model with no triangles, or
/// (without `normalize`) one whose extent along x is not 0 to 1 within 1 % of its length.
OrganPrototype loadOBJPrototype(const std::string& path, bool normalize);

/// True when a prototype function name refers to an OBJ file (ends in ".obj").
bool isOBJPrototypeName(const std::string& name);

}  // namespace plantarch
