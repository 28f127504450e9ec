#pragma once
// plantarch organ library: procedural, parametric flower and fruit prototype families.
//
// Every family builds an OrganPrototype that follows the prototype convention: the organ's
// axis runs along +x from its attachment point at the origin, its bounding box spans x = 0
// to x = 1 exactly, +z is up. The plant model scales it by the species' prototype_scale
// (metres per unit of organ length) and places it.
//
// A family is one kind of organ (a petal flower, a legume pod, a spike...) whose shape
// comes from a few named parameters (the `flower_prototype_parameters` and
// `fruit_prototype_parameters` of a species). Each family declares its parameters once, with
// a default, a valid range and a one-line description; that table (floralFamilies()) validates
// species files and documents them. Lengths inside a family are fractions of the organ's
// length unless the description says otherwise; angles are degrees.
//
// The first part of every prototype is the main part, coloured by the request's colour
// (the species' flower_color or fruit_color); the other parts (calyx, stem, centre, seeds...)
// have their own botanical colours, some of them set by parameters named <part>_r, _g, _b.
// `subdivisions` is the mesh resolution (values below 2 act as 2): every family's triangle
// count grows with it. A family builds its own kind of organ whatever request.fruit says.
// Flower families build an open flower or a closed bud (FloralPrototypeRequest::open); fruit
// families ignore `open` except where documented (a tassel sheds pollen when open).
// A bud is normalised to unit length like the open flower, so both take the same
// prototype_scale: the bud is as long along its axis as the open flower is deep.
// Random variation (berry packing, small petal irregularities) is drawn from the Rng passed
// in, so the same generator state always gives the same mesh.

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "plantarch/Mesh.h"
#include "plantarch/OrganFunctions.h"
#include "plantarch/Random.h"

namespace plantarch {

/// One shape parameter of a family.
struct FloralParameterInfo {
    std::string name;
    float defaultValue = 0.0f;
    float min = 0.0f;      ///< smallest valid value (inclusive)
    float max = 0.0f;      ///< largest valid value (inclusive)
    bool integer = false;  ///< a count or a switch: the value must be a whole number
    std::string doc;       ///< one line, with the unit where there is one
};

/// What a family builds and the parameters it reads.
struct FloralFamilyInfo {
    std::string name;         ///< registered prototype name, e.g. "petal_flower"
    bool fruit = false;       ///< builds a fruit (or a cereal head); else a flower with a bud
    std::string description;  ///< one or two sentences: what it looks like, what it covers
    vec3 defaultColor{1.0f};  ///< suggested main colour (sRGB, 0..1)
    /// Material names of the parts it can produce, main part first. A part whose geometry
    /// is empty for the given parameters (no sepals, no husk) is left out.
    std::vector<std::string> parts;
    std::vector<FloralParameterInfo> parameters;

    /// The parameter named `name`, or nullptr.
    const FloralParameterInfo* parameter(std::string_view name) const;
};

/// Every family, in a fixed order (flowers first, then fruit, then cereal heads).
const std::vector<FloralFamilyInfo>& floralFamilies();

/// True when `name` is a family of this library (not a custom or OBJ prototype).
bool isFloralFamily(std::string_view name);

/// The family named `name`; throws plantarch::Error listing the family names.
const FloralFamilyInfo& floralFamily(std::string_view name);

/// Checks shape parameters against a family's table: an unknown family or parameter name, a
/// value outside the valid range, a fractional value for a whole-number parameter or a
/// non-finite value throws plantarch::Error naming the family, the parameter and the valid
/// range (or the valid names). Species files call this when they are read.
void validateFloralParameters(std::string_view family,
                              const std::map<std::string, float>& parameters);

/// Builds one prototype of a family (validating the request's parameters first).
OrganPrototype buildFloralPrototype(std::string_view family, const FloralPrototypeRequest& request,
                                    Rng& rng);

/// Every family's prototype function, under its name (floralFamilies()[i].name): what every
/// PlantArchitecture registers as its flower and fruit families.
std::vector<std::pair<std::string, FloralPrototypeFunction>> floralFamilyFunctions();

}  // namespace plantarch
