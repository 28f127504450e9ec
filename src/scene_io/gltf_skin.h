#pragma once
// Skinned plants in glTF (GltfOptions::skeletons): a wind-ready skeleton per plant, its
// joints as nodes under the plant's node, a skin with their inverse bind matrices, JOINTS_0
// and WEIGHTS_0 on the plant's meshes, whose nodes become roots of the scene (the glTF 2.0
// spec: only the joints place a skinned mesh). docs/formats.md, "Skinned plants".

#include "scene_io/gltf_internal.h"

namespace plantarch::gltf {

/// The skeleton of a Scene node's plant, or null (not skinned, or an animation's frames).
const GltfSkeleton* skeletonOf(const Scene& s, const GltfOptions& options, std::size_t node);

/// Adds JOINTS_0 (unsigned short) and WEIGHTS_0 (float) to `attributes` of a primitive of a
/// skinned plant; nothing for the others.
void addSkinAttributes(GltfArrays& d, const Scene& s, const GltfOptions& options, Buffer& buffer,
                       const Primitive& p, json& attributes);

/// The skins of a scene's skinned plants.
struct SkinNodes {
    json skins = json::array();  ///< the document's skins
    json roots = json::array();  ///< the skinned meshes' nodes: more roots of the scene
    json animation;              ///< the "wind" animation (GltfOptions::windDegrees), or null
};

/// Checks every skeleton of options.skeletons the scene uses: parents before children, finite
/// joints, joints in range, one influence per vertex, weights >= 0 summing to 1. Throws
/// plantarch::Error naming `path`.
void checkSkins(const Scene& s, const GltfOptions& options, const std::string& path);

/// For each skinned plant (Scene node n, glTF node plantNodes[n]): its joints as nodes under
/// its node, a skin, and its mesh nodes moved from under its node to the scene's roots with
/// that skin. Throws plantarch::Error for a mesh node with a transform of its own.
SkinNodes addSkins(GltfArrays& d, const Scene& s, const GltfOptions& options, Buffer& buffer,
                   const json& plantNodes);

}  // namespace plantarch::gltf
