#pragma once
// Fewer triangles for the same shape, by meshoptimizer's edge collapses: the coarse organ
// meshes of a low mesh detail (PlantArchitecture::setMeshDetail) and the reduced level of
// detail of exported scenes.

#include <cstddef>

#include "plantarch/Mesh.h"

namespace plantarch::meshes {

struct SimplifyOptions {
    /// Stop at or below this many triangles (sooner when `maxError` is reached).
    std::size_t targetTriangles = 0;
    /// The largest distance a collapse may move the surface, relative to the mesh's extent
    /// (meshoptimizer's target_error): 1 lets it go as far as the target asks.
    float maxError = 1.0f;
    /// Keep every vertex of the open border where it is (a mesh whose border meets another).
    bool lockBorder = false;
};

/// `mesh` with at most about options.targetTriangles triangles. The vertices kept are a
/// subset of mesh's, in their order, with their UVs; a vertex no triangle uses is dropped.
/// Vertices at one position with different UVs (a seam) move together. A mesh already at or
/// below the target comes back unchanged. The same mesh gives the same bytes.
Mesh simplified(const Mesh& mesh, const SimplifyOptions& options);

}  // namespace plantarch::meshes
