// Mesh simplification by meshoptimizer (meshopt_simplify), compacted to the vertices used.

#include "core/mesh_simplify.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

namespace plantarch::meshes {

Mesh simplified(const Mesh& mesh, const SimplifyOptions& options) {
    const std::size_t target = std::max<std::size_t>(options.targetTriangles, 1);
    if (mesh.triangleCount() <= target) return mesh;
    std::vector<std::uint32_t> kept(mesh.indices.size());
    const unsigned flags = options.lockBorder ? unsigned(meshopt_SimplifyLockBorder) : 0u;
    kept.resize(meshopt_simplify(kept.data(), mesh.indices.data(), mesh.indices.size(),
                                 &mesh.positions[0].x, mesh.positions.size(), sizeof(vec3),
                                 target * 3, options.maxError, flags, nullptr));
    // Triangles that collapsed to no area (two corners at one position: seam vertices with
    // different UVs move apart from their index), which viewers drop or shade as black.
    std::size_t at = 0;
    for (std::size_t k = 0; k + 2 < kept.size(); k += 3) {
        const vec3 a = mesh.positions[kept[k]], b = mesh.positions[kept[k + 1]],
                   c = mesh.positions[kept[k + 2]];
        if (glm::cross(b - a, c - a) == vec3(0.0f)) continue;
        std::copy(kept.begin() + std::ptrdiff_t(k), kept.begin() + std::ptrdiff_t(k + 3),
                  kept.begin() + std::ptrdiff_t(at));
        at += 3;
    }
    if (at > 0) kept.resize(at);  // all collapsed: keep them, an object needs a triangle
    // Vertices renumbered in their first order, so the result does not depend on the order
    // meshoptimizer visits them.
    constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> remap(mesh.positions.size(), kUnused);
    for (std::uint32_t i : kept) remap[i] = 0;
    Mesh out;
    for (std::size_t v = 0; v < remap.size(); ++v) {
        if (remap[v] == kUnused) continue;
        remap[v] = std::uint32_t(out.positions.size());
        out.positions.push_back(mesh.positions[v]);
        if (mesh.hasUVs()) out.uvs.push_back(mesh.uvs[v]);
    }
    out.indices.reserve(kept.size());
    for (std::uint32_t i : kept) out.indices.push_back(remap[i]);
    return out;
}

}  // namespace plantarch::meshes
