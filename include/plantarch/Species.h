#pragma once
// A species: everything needed to build plants of one kind, read from a species file under
// species/ (or a user's own file). Species are data; behaviour that parameters cannot
// express is a named function registered in C++ and referred to by name.

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "plantarch/Parameters.h"

namespace plantarch {

/// A user-adjustable number of a species' initial structure (trunk height, number of
/// scaffolds, ...), with its default and valid range.
struct BuildParameter {
    std::string name;
    float value = 0.0f;  ///< default in the file; the chosen value once resolved
    float min = 0.0f;
    float max = 0.0f;
    std::string unit;
    std::string doc;
};

/// One step of the initial structure: a base stem, an appended shoot or a child shoot.
/// Numeric fields are expressions over the build parameters (e.g. "trunk_height / 0.05",
/// "uniform(0, 360)"); they are evaluated when a plant is built.
struct BuildStep {
    enum class Kind { BaseStem, Append, Child } kind = Kind::BaseStem;
    std::string id;      ///< name later steps use to refer to the shoots it makes
    std::string parent;  ///< id of the parent step (Append, Child)
    std::string shootType;
    std::string nodes = "1";                         ///< phytomers to create
    std::string parentNode = "0";                    ///< Child: node on the parent
    std::string petiole = "0";                       ///< Child: petiole on that node
    std::string pitch = "0", yaw = "0", roll = "0";  ///< degrees
    std::string radius;                ///< internode radius, m (empty: the type's radius_initial)
    std::string internodeLength;       ///< full internode length, m (empty: type's maximum)
    std::string internodeScale = "1";  ///< current / full internode length
    std::string leafScale = "1";       ///< current / full leaf size
    std::string taper = "0";
    /// Number of copies (Child only); "i" in expressions is the copy index (0-based). When
    /// the parent step made several shoots, the step runs once per parent shoot and
    /// "parent_i" is that shoot's copy index.
    std::string repeat = "1";
    /// What the new shoot keeps: its leaves (false: leaves and petioles removed, bare nodes),
    /// its axillary vegetative and floral buds, its apical bud (false: the shoot never grows
    /// longer).
    bool leaves = true;
    bool vegetativeBuds = true;
    bool floralBuds = true;
    bool apex = true;
    int line = 0;  ///< line in the species file, for errors
};

/// Attraction points every plant of the species gets when built (trellis wires, a post):
/// expressions over the build parameters, coordinates relative to the plant's base (m).
/// A vector is three expressions separated by commas, e.g. "0, -cordon_length, wire_height".
struct SpeciesAttraction {
    struct Wire {
        std::string from, to;          ///< end points
        std::string spacing = "0.05";  ///< distance between points along the wire, m
        int line = 0;
    };
    struct Point {
        std::string at;
        int line = 0;
    };
    std::vector<Wire> wires;
    std::vector<Point> points;
    std::string halfAngle = "80";         ///< perception cone half-angle, degrees
    std::string lookAhead = "0.1";        ///< m
    std::string inertia = "0.4";          ///< 0 to 1
    std::vector<std::string> shootTypes;  ///< attracted shoot types (empty: all)
    int line = 0;
};

/// A trellis drawn with the plant (<trellis>): posts and wires as Context objects labelled
/// "trellis", made when a plant is built from the library. Every number is an expression
/// over the build parameters; positions are relative to the plant's base (m).
struct SpeciesTrellis {
    struct Post {
        std::string at;               ///< "x, y": the foot of the post, on the ground
        std::string height;           ///< m
        std::string radius = "0.04";  ///< m
        int line = 0;
    };
    struct Wire {
        std::string from, to;          ///< end points "x, y, z"
        std::string radius = "0.002";  ///< m
        int line = 0;
    };
    std::vector<Post> posts;
    std::vector<Wire> wires;
    int line = 0;
};

struct SpeciesModel {
    std::string name;  ///< library name, e.g. "bean"
    std::string commonName;
    std::string latinName;
    std::string plantType;  ///< herbaceous, weed or tree
    std::string description;
    std::string sourceFile;  ///< file it was read from
    float recommendedAgeMin = 0.0f;
    float recommendedAgeMax = 0.0f;
    float recommendedAge = 0.0f;
    float maxHeight = 0.0f;  ///< plausible bounds used by tests, m (0: unchecked)
    std::map<std::string, ShootParameters> shootTypes;
    PhenologyParameters phenology;
    std::vector<BuildParameter> buildParameters;
    std::vector<BuildStep> build;
    /// The plant's own attraction points (<attraction_points>), if the species declares any.
    std::optional<SpeciesAttraction> attraction;
    /// The trellis drawn with each plant (<trellis>), if the species declares one.
    std::optional<SpeciesTrellis> trellis;
    /// Line in sourceFile of each value read, by parameter path ("trifoliate.max_nodes",
    /// "phenology.max_age"), so later errors about a value can point at it. Empty for a
    /// model made in code.
    std::map<std::string, int> lines;

    /// The line of `path` in sourceFile, or of the nearest enclosing path it has one for
    /// ("trifoliate.phytomer.leaf.pitch", then "trifoliate.phytomer.leaf", ...); 0 if none.
    int lineOf(std::string path) const;
};

}  // namespace plantarch
