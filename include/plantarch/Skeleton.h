#pragma once
// Measured plant skeletons: the nodes of a plant's axes as a digitiser or a point-cloud
// skeletonisation gives them, read from a node table (.csv), a JSON file or an MTG file (the
// multiscale tree graphs of OpenAlea and phenotyping tools), and rebuilt into a plant whose
// internodes run through the points (docs/measured-plants.md). Plants are written back as
// node tables and MTG files too, so a plant can go to those tools and come back.

#include <optional>
#include <string>
#include <vector>

#include "plantarch/PlantArchitecture.h"

namespace plantarch {

/// How a node continues from its parent.
enum class SkeletonLink {
    Auto,      ///< not given: the parent's first such child continues its axis, others branch
    Continue,  ///< continues the parent's axis (MTG '<')
    Branch,    ///< starts a lateral axis (MTG '+')
};

/// One measured point. The root (parent -1) is the plant's base; every other node ends one
/// internode, from its parent's point to its own.
struct SkeletonNode {
    long id = 0;          ///< unique in the skeleton
    long parent = -1;     ///< id of its parent, -1 for the root
    vec3 position{0.0f};  ///< m
    float radius = 0.0f;  ///< radius of the internode ending here, m (0: not measured)
    SkeletonLink link = SkeletonLink::Auto;
    /// The shoot type of the axis this node starts (a branch, a continuation of another
    /// type, or the first node of the base stem); empty: chosen (reconstructPlant).
    std::string shootType;
    /// Organs measured at this node: "bare" (no petioles or leaves), "flower", "fruit".
    std::vector<std::string> organs;
    /// The way the blades of this node's leaves face, if measured (MeasuredLeaf::normal).
    std::optional<vec3> leafNormal;
    float leafLength = 0.0f;  ///< their largest blade's length, m (0: the species')
    int line = 0;             ///< line of the file it was read from (0: none)
};

/// A plant's measured nodes, parents before children or in any order.
struct Skeleton {
    std::vector<SkeletonNode> nodes;
    std::string source;  ///< the file (or name) it was read from, for errors
};

/// Reads a skeleton; the format is the file's extension: .csv (a node table), .json, or
/// .mtg. Every bad value throws plantarch::Error naming the file, line, column and the valid
/// range; the file must be a regular file of at most 256 MB.
Skeleton readSkeletonFile(const std::string& path);
/// The same from text: `format` is "csv", "json" or "mtg"; `name` stands for the file.
Skeleton readSkeletonString(const std::string& text, const std::string& format,
                            const std::string& name);
/// Checks the tree: ids unique, parents present, one root, no cycle, every position finite,
/// radii >= 0, at most one continuing child per node. Throws naming the node's line.
void checkSkeleton(const Skeleton& skeleton);

/// How reconstructPlant builds a plant on a skeleton.
struct ReconstructOptions {
    float age = 0.0f;  ///< the plant's age, days, 0 to 100000 (for its phenology)
    /// The base stem's shoot type when the root's first node names none; empty: the loaded
    /// species' (PlantArchitecture::getBaseStemShootType).
    std::string baseShootType;
    /// A branch's shoot type when its node names none; empty: the most probable child type
    /// of its parent's type (the parent's own type when that lists none).
    std::string branchShootType;
    /// Each axis resampled to internodes of about this length, m (0: every point is a node,
    /// as for a digitiser; > 0 for dense point-cloud skeletons), 0 to 10.
    float spacing = 0.0f;
    /// Metres per unit of the skeleton's coordinates and radii: 0.01 for centimetres, 0.001
    /// for millimetres; (0, 1000].
    float unit = 1.0f;
    /// Leaf scale and attach tolerance (m) of every shoot (its other fields are set per shoot).
    MeasuredShootOptions shoot;
};

/// Builds one plant per root of `skeleton` with the PlantArchitecture's shoot types (load
/// the species first): each axis becomes a shoot through its points
/// (addShootFromNodePositions), a branch grows from the node it starts at, and a tiller
/// (a branch from the root) from the base stem's first node. A node's radius is that of the
/// internode ending there (unmeasured: the type's radius_initial). Nodes tagged "bare" lose
/// their leaves, "flower" and "fruit" get a floral bud at that stage. Returns the plants'
/// IDs in the order of their roots; on an error, naming the file and the node's line,
/// nothing is added.
std::vector<unsigned> reconstructPlants(PlantArchitecture& arch, const Skeleton& skeleton,
                                        const ReconstructOptions& options = {});

/// Plants' nodes as one skeleton: for each plant its base (a root), then every node of its
/// shoots with the radius of the internode ending there (each shoot's first node names its
/// type and its link); reconstructPlants of it rebuilds the plants' axes.
Skeleton plantSkeleton(const PlantArchitecture& arch, const std::vector<unsigned>& plantIDs);
/// A skeleton as a node table (.csv): id,parent,x,y,z,radius,link,shoot_type,organs (and
/// leaf_nx,leaf_ny,leaf_nz,leaf_length when a node has a measured leaf).
std::string skeletonCSV(const Skeleton& skeleton);
/// Plants as an MTG file (FORM-A): scales P (plant), A (axis: a shoot), I (internode: a
/// phytomer), with the features docs/measured-plants.md lists.
std::string plantsMTG(const PlantArchitecture& arch, const std::vector<unsigned>& plantIDs);

}  // namespace plantarch
