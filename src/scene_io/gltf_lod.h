#pragma once
// Levels of detail (MSFT_lod) and EXT_meshopt_compression of glTF files: the parts of the
// document that gltf_writer.cpp adds through two hooks (docs/formats.md, "Levels of detail").

#include <deque>
#include <functional>

#include "scene_io/gltf_internal.h"

namespace plantarch::gltf {

/// What the levels' buffer blocks read while the file is written: kept until then.
struct Levels {
    std::deque<Context> contexts;
    std::deque<Scene> scenes;
    std::deque<Buffer> buffers;
};

/// A level's scene from its Context, and its document (collect, normals and document of
/// gltf_writer.cpp, with the options given).
using CollectLevel = std::function<Scene(const Context& context, const GltfOptions& options)>;
using LevelDocument = std::function<json(Scene& scene, const GltfOptions& options, Buffer& buffer)>;

/// Adds options.levels to `doc`: each level's meshes, its plant nodes (outside the scene,
/// named as the full level's with a "_lod<N>" suffix) and, on each node of the full level's
/// plants, MSFT_lod with their IDs and extras MSFT_screencoverage. Each level's buffer
/// becomes one block of `buffer`. Nothing without levels; throws plantarch::Error for levels
/// with a growth animation or skins.
void addLevels(json& doc, Buffer& buffer, const Scene& full, const GltfOptions& options,
               Levels& keep, const CollectLevel& collect, const LevelDocument& document);

/// `buffer` with its views compressed by EXT_meshopt_compression (vertex attributes and
/// property columns as ATTRIBUTES, triangle indices as TRIANGLES; images and views that would
/// not shrink stored as they are), the uncompressed layout kept as a fallback buffer without
/// data, and the extension in extensionsUsed and extensionsRequired of `doc`.
Buffer compressMeshopt(json& doc, const Buffer& buffer);

/// For the reader: decodes each buffer view of `doc` that has EXT_meshopt_compression (any mode
/// and filter) from its compressed buffer into a buffer of its own, appended to `buffers`, and
/// points the view at it. Throws plantarch::Error naming `path` for data that does not decode,
/// or that would decode to more than 256 times its size.
void decodeMeshopt(json& doc, std::vector<std::string>& buffers, const std::string& path);

}  // namespace plantarch::gltf
