#pragma once
// glTF with Instancing::Gpu (gltf_instancing.cpp): each shape two or more organs of a plant
// place is one node with EXT_mesh_gpu_instancing, the organs its instances.

#include <functional>
#include <vector>

#include "scene_io/gltf_internal.h"

namespace plantarch::gltf {

/// The instancing nodes of the organs `tracks` (of one plant, its base at `base`), appended to
/// `children`: a node per shape that two or more of them place, its mesh from `mesh(shape)`,
/// per instance TRANSLATION, ROTATION, SCALE and (with options.labels) the organ's labels as
/// _OBJECT_ID, _FEATURE_ID_0 (EXT_instance_features), _SHOOT, _RANK, _NODE, _LEAF and _AGE;
/// the instances' names and object IDs in order in the node's extras.
void addInstanceNodes(GltfArrays& d, const Scene& s, const GltfOptions& options, Buffer& buffer,
                      const std::vector<std::size_t>& tracks, vec3 base,
                      const std::function<std::size_t(std::size_t)>& mesh, json& children);

/// Lists EXT_mesh_gpu_instancing (and EXT_instance_features) in extensionsUsed, and
/// EXT_mesh_gpu_instancing in extensionsRequired, when a node of `nodes` uses it.
void declareInstancing(json& doc, const json& nodes);

}  // namespace plantarch::gltf
