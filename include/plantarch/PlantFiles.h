#pragma once
// Plants and scenes written to the files a user names, each in the format its extension says
// (plantarch/OutputFormats.h lists them): a plant structure file (.xml; .helios.xml in the
// reference system's layout), plant strings (.txt), cylinders (.csv, writeQSM), or the scene's
// geometry (.obj, .ply, .npz, .glb, .gltf, .usda) or a picture of it (.png). The command line
// and the project builder write their outputs through these, so a file comes out the same
// whichever wrote it. Each file appears whole or not at all (plantarch/OutputFiles.h).

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "plantarch/Export.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/Progress.h"
#include "plantarch/Render.h"

namespace plantarch {

/// How plant and scene files are written.
struct PlantFileOptions {
    /// .xml files carry each organ's object IDs, and each mesh file gets an object table
    /// beside it (field.obj -> field.objects.json).
    bool objectIDs = false;
    int stringDigits = 4;     ///< significant digits of plant strings (.txt)
    std::size_t points = 0;   ///< .ply and .npz as labelled point clouds of this many points
    std::uint64_t seed = 42;  ///< seed of the point sampling and of the picture's jitter
    PlyColor plyColor = PlyColor::None;
    PlyFormat plyFormat = PlyFormat::BinaryLittleEndian;
    int imageWidth = 1024;  ///< size of .png pictures
    int imageHeight = 768;
    /// The camera of .png pictures; a fixed camera (autoFrame false) without `cameraTarget`
    /// looks at the centre of the scene's box.
    Camera camera;
    bool cameraTarget = false;
    RenderMode mode = RenderMode::Shaded;  ///< shaded picture or a label mask
    bool cameraJson = false;  ///< NAME.camera.json (the camera's matrices) beside each .png
    /// Skinning: .glb, .gltf and .usda files of plants carry a wind-ready skeleton per plant
    /// (exportSkeletons, GltfOptions::skeletons); other files are written as without it.
    bool skin = false;
    /// With `skin`: .glb and .gltf files get a "wind" animation (GltfOptions::windDegrees).
    float wind = 0.0f;
    // Levels of detail and compression of .glb and .gltf files (GltfOptions): levels given
    // with another mesh format are an error.
    std::vector<GltfLevel> levels;
    bool meshoptCompression = false;
    /// Materials of .obj, .glb, .gltf, .usda, .usdz and .png outputs: flat colours or
    /// procedural textures (MaterialOptions).
    MaterialOptions appearance;
    /// Nodes of .glb, .gltf, .usda and .usdz files (GltfOptions::nodes, ::instancing); a level
    /// other than NodeLevel::Kind with another mesh format is an error.
    NodeLevel nodes = NodeLevel::Kind;
    Instancing instancing = Instancing::Shared;
    /// Each writer's progress; for separate files, one report over the plants.
    ProgressCallback progress;
    /// Called with the path of every file written (an object table and a camera file too).
    std::function<void(const std::string& path)> onWritten;
};

/// Whether a file of this path holds object IDs (.obj, .ply, .glb, .gltf, .usda, .npz), and
/// so gets an object table beside it when options.objectIDs.
bool holdsObjectIDs(const std::string& path);
/// The object table beside a mesh file: field.obj -> field.objects.json.
std::string objectTablePath(const std::string& path);

/// Writes a Context to `path` in the scene format its extension names; `plants` names and
/// places the plants in glTF and USD files, `skeletons` skins them there (exportSkeletons).
/// Throws plantarch::Error for an extension that is not a scene format (or an .npz without
/// points).
void writeSceneFile(const Context& context, const std::string& path,
                    const PlantFileOptions& options, const std::vector<GltfPlant>& plants = {},
                    const std::vector<GltfSkeleton>& skeletons = {});

/// Writes `plants` of `arch` to `path`: a plant structure file, plant strings, cylinders or
/// the whole scene (writeSceneFile, with an object table when options.objectIDs).
void writePlantFile(const PlantArchitecture& arch, const std::vector<unsigned>& plants,
                    const std::string& path, const PlantFileOptions& options);

/// `path` with a plant's ID before the extension: field.glb -> field_0007.glb
/// (field.helios.xml -> field_0007.helios.xml).
std::string separatePlantFileName(const std::string& path, unsigned plant);
/// The index of separate files: <stem of `path`>_index.json beside it.
std::string separatePlantIndexName(const std::string& path);
/// One file per plant for each of `paths` (separatePlantFileName), each in scene coordinates
/// or, with `ownOrigin`, moved so that the plant's base is at the origin; and one index,
/// separatePlantIndexName(paths.front()), of the plants' IDs, files, positions, species, ages
/// and seed.
void writeSeparatePlantFiles(const PlantArchitecture& arch, const std::vector<unsigned>& plants,
                             const std::vector<std::string>& paths, bool ownOrigin,
                             const PlantFileOptions& options);

}  // namespace plantarch
