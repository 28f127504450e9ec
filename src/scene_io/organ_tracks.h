#pragma once
// Organs followed through the frames of a scene, for writers that give every organ its own node
// (glTF, USD): each organ is a track, placed in each frame where it exists by a similarity
// transform (translation, rotation, uniform scale) of a shape stored once.
//
// An organ that only grows and moves keeps one shape through an animation (a leaf grows by a
// uniform scale of its blade), so the file holds its geometry once and a few numbers per frame.
// Where the geometry changes otherwise (an internode that lengthens more than it thickens), the
// frame gets a new shape. With instancing, an organ whose geometry equals another's up to a
// similarity (the flowers of one age, say) places that shape instead of storing its own.

#include <cstdint>
#include <functional>
#include <glm/gtc/quaternion.hpp>
#include <optional>
#include <string>
#include <vector>

#include "plantarch/Context.h"
#include "scene_io/export_common.h"

namespace plantarch::io {

/// Geometry stored once: the object `id` of frame `frame`, as its positions minus `centre`.
struct OrganShape {
    std::uint32_t frame = 0;
    ObjectID id = 0;
    vec3 centre{0.0f};
    /// The first shape with the same indices, UVs and material (itself when none): shapes of one
    /// topology can share their index and UV arrays.
    std::size_t topology = 0;
    /// The tracks that place this shape.
    std::vector<std::size_t> users;
};

/// A shape's placement: a vertex v of the shape is shown at
/// translation + scale * rotate(rotation, v - centre).
struct OrganPlacement {
    std::size_t shape = 0;
    vec3 translation{0.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // w, x, y, z
    float scale = 1.0f;
};

/// One organ through the frames: its labels and its placement in each frame (none where the
/// organ does not exist).
struct OrganTrack {
    ObjectLabels labels;          ///< as in the last frame where it exists
    std::uint32_t lastFrame = 0;  ///< that frame
    ObjectID lastID = 0;          ///< its object there
    std::int32_t ordinal = 0;     ///< among organs of equal labels in a frame, in ID order
    std::vector<std::optional<OrganPlacement>> frames;
};

/// The name of an organ's node or prim: "<organ>_s<shoot>_n<node>[_l<leaf>][_<k>]", the parts
/// of labels it lacks left out, `_<k>` for the k-th organ of equal labels (from 2).
std::string organName(const OrganTrack& track);

struct OrganTracks {
    std::vector<OrganShape> shapes;
    /// In the order of their organs' last frames, from the last frame back, each frame's
    /// objects in ID order (for one frame: the objects in ID order).
    std::vector<OrganTrack> tracks;
};

/// The organs of the exported objects of `frames` (one Context per frame), matched from frame
/// to frame by their labels (plant, organ, shoot, node, leaf and the ordinal among organs with
/// equal labels). A placement reproduces the frame's vertices to within 1e-5 of the organ's size
/// plus 2e-6 of their largest coordinate (a few float steps: 2 um at 1 m from the origin).
/// `uvsMatter(material)` says whether objects of a material must keep their own UVs (those with
/// a texture); objects of other materials share shapes whatever their UVs. `instancing` lets tracks
/// share shapes; without it a shape belongs to one track.
OrganTracks trackOrgans(const std::vector<const Context*>& frames, bool includeHidden,
                        bool instancing, const std::function<bool(const Material&)>& uvsMatter);

}  // namespace plantarch::io
