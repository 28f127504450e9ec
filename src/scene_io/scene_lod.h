#pragma once
// Levels of detail of an exported scene. Each level is a copy of the Context whose objects
// keep their IDs, materials, hidden flags and data (so every label of a full-detail file holds
// on every level): only their meshes change, one object at a time, so that no triangle ever
// mixes two organs.

#include "plantarch/Context.h"
#include "plantarch/Export.h"

namespace plantarch::io {

/// `ctx` with each object's mesh simplified by meshoptimizer to about `share` (0 to 1) of its
/// triangles, never fewer than one, nor so far that the surface moves by more than a tenth of
/// the object's size.
Context reducedLevel(const Context& ctx, float share);

/// `ctx` with each object replaced by a card: a leaf (object data "organ") or another flat
/// object (the ground) by one quad in its plane: over its extent along its two main directions
/// when its material has a texture image (a leaf card shows the leaf's image), else a rhombus
/// no larger than its area, widest at its centre of area; any other object (a stem, a fruit)
/// by two crossed quads along its main direction. Cards of objects with UVs get UVs fitted
/// to the object's.
Context cardLevel(const Context& ctx);

/// The level `level` of `ctx`.
Context lodLevel(const Context& ctx, const GltfLevel& level);

}  // namespace plantarch::io
