#pragma once
// Instancing::Gpu (docs/formats.md, "Nodes and instancing"): which organs are drawn as
// instances, and the check that the writers are asked for something they can write.

#include <string>

#include "plantarch/Export.h"
#include "scene_io/organ_tracks.h"

namespace plantarch::io {

/// Throws plantarch::Error (the file, parameter "instancing", what is valid) for
/// Instancing::Gpu without a node per organ or in an animation; before anything is written.
void checkInstancing(const std::string& path, NodeLevel nodes, Instancing instancing,
                     bool animated);

/// With Instancing::Gpu, a shape is drawn by instancing when two or more organs place it (one
/// frame: every track has one placement, so each user is one instance).
inline bool gpuInstanced(const OrganShape& shape, Instancing instancing) {
    return instancing == Instancing::Gpu && shape.users.size() >= 2;
}

/// The track's placement in a single-frame scene.
inline const OrganPlacement& onlyPlacement(const OrganTrack& track) {
    return *track.frames[track.lastFrame];
}

}  // namespace plantarch::io
