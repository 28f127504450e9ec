#pragma once
// Writing a Context to mesh files (Wavefront OBJ + MTL, PLY) and reading OBJ files back.
//
// Every writer writes into a temporary file next to the target (`<path>.tmp-<pid>-<n>`)
// and renames it over the target only once everything was written, so an export that
// fails or is interrupted never leaves a partial file and never damages an existing one.
// Failures throw plantarch::Error naming the file, e.g.
//   out/plant.obj: cannot open for writing: No such file or directory
//
// Output is deterministic: the same Context and options give the same bytes. Objects are
// written in increasing object ID order. Positions, UVs and colours use the shortest text
// that reads back to the same float (std::to_chars), so they round-trip exactly; normals
// in text formats are written with 6 decimals (ample for unit vectors, and much faster).
//
// Object data read by the writers (the labels; -1 or absent where an object has none):
//   "organ"      (string) organ kind: OBJ group names and label comments, PLY per-face organ
//   "plantID"    (int)    plant: OBJ names and comments, PLY per-face plant_id
//   "shootID", "rank", "node", "leafID" (int), "age" (float, days), "plant_name" (string):
//                         OBJ label comments, PLY per-face properties (not plant_name),
//                         glTF and USD labels

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "plantarch/Context.h"
#include "plantarch/Error.h"
#include "plantarch/PlantState.h"
#include "plantarch/Progress.h"

namespace plantarch {

// ---- materials and procedural textures -----------------------------------------------

/// How the writers and the renderer draw surfaces.
enum class MaterialStyle {
    Flat,      ///< one colour per material, as plantarch always wrote them
    Textured,  ///< procedural textures and PBR factors per organ (docs/formats.md, "Materials")
};
/// "flat", "textured".
const char* materialStyleName(MaterialStyle style);
/// The MaterialStyle of a name of materialStyleName; nullopt for another text.
std::optional<MaterialStyle> materialStyleFromName(std::string_view name);

/// The smallest and largest texture size (texels a side); sizes are powers of two.
inline constexpr int kMinTextureSize = 16, kMaxTextureSize = 4096;

/// Materials of an export: flat colours (the default), or procedural textures drawn from the
/// materials' colours and the leaves' outlines: leaves get base colour (venation from the
/// outline, colour and gloss variation, alpha outside the outline), normal and
/// occlusion-roughness-metallic maps; internodes bark (fine striations on green stems);
/// petioles and peduncles a green stem's skin; fruit and flowers PBR factors only.
struct MaterialOptions {
    MaterialStyle style = MaterialStyle::Flat;
    /// Texels a side of each texture: a power of two from kMinTextureSize to kMaxTextureSize.
    int textureSize = 512;
    /// Pack the maps of leaves (all whose texture coordinates stay in 0..1) into one atlas
    /// image per map kind, each material reading its part through a texture transform
    /// (KHR_texture_transform, UsdTransform2d, MTL -o/-s); off: an image per material
    /// (--no-texture-atlas). An atlas that would pass 8192 texels a side is not made: the
    /// maps stay separate images.
    bool atlas = true;
};

/// Throws plantarch::Error (parameter "texture_size", its value and the valid sizes) unless
/// options.textureSize is a power of two from kMinTextureSize to kMaxTextureSize.
void checkMaterialOptions(const MaterialOptions& options);

// ---- OBJ ---------------------------------------------------------------------------

/// Options of writeOBJ. Defaults give one OBJ with normals, UVs and a material library.
struct ObjOptions {
    /// Also write hidden objects (skipped by default).
    bool includeHidden = false;
    /// Write smooth per-vertex normals (`vn`): per object, the area-weighted average of
    /// the normals of the triangles around each vertex, 6 decimals. Off: smaller files and
    /// faster export, faces `v/vt`.
    bool normals = true;
    /// Write texture coordinates (`vt`) of objects that have UVs.
    bool uvs = true;
    /// Write the .mtl material library, `mtllib` and one `usemtl` per object.
    bool materials = true;
    /// One OBJ file per object instead of one for the scene. `path` then names a directory
    /// (created when missing, with its parents) that receives `obj<ID>[_plant<P>][_<organ>].obj`
    /// for each object and one shared `materials.mtl`. Every file is written to a temporary first
    /// and all are renamed into place together at the end; files already in the directory are left
    /// alone.
    bool splitPerObject = false;
    /// Materials and textures: with MaterialStyle::Textured the .mtl gets map_Kd, map_d,
    /// norm/map_Bump and map_Pr (PNG files named `<stem>_<texture>_<map>.png` next to it,
    /// written atomically with the OBJ) and PBR factors (Pr, Pm).
    MaterialOptions appearance;
    /// Receives ("writing OBJ", fraction) while the file is written; may be empty.
    ProgressCallback progress;
};

/// Writes the visible objects of `context` as a Wavefront OBJ file and, next to it, a
/// material library with the same stem (`scene.obj` -> `scene.mtl`).
///
/// Layout: per object an `o` and a `g` line named `obj<ID>[_plant<P>][_<organ>]` (P from the
/// object's "plantID" int data, the organ from its "organ" string data with characters other
/// than letters, digits, `-`, `_` and `.` replaced by `_`), a label comment
///   # plantarch labels object=<ID> plant=<P> plant_name=<name> organ=<organ> shoot=<S>
///     rank=<R> node=<N> leaf=<L> age=<days>
/// (one line; keys of data the object lacks left out, text percent-encoded; docs/formats.md,
/// "OBJ labels"), a `usemtl` line, its `v` (and `vt`, `vn`, one per vertex) lines and
/// its faces `f v/vt/vn`. Materials are named after Material::name or `material<ID>`;
/// the .mtl holds `Kd` (the colour) and `map_Kd` (the texture; a relative texture path
/// is rewritten relative to the .mtl's directory so viewers find it).
///
/// Throws Error (naming the file) when a file cannot be written, or when the object data
/// "organ" exists with a type other than string.
void writeOBJ(const Context& context, const std::string& path, const ObjOptions& options = {});

/// Options of readOBJ.
struct ObjReadOptions {
    /// Directory searched for the .mtl files named by `mtllib`; empty: the OBJ's directory.
    /// Texture paths in the .mtl are resolved against this directory too.
    std::string mtlSearchPath;
    /// Store each shape's name (from `o` / `g`) as object string data "name".
    bool storeShapeNames = true;
    /// Read the plantarch label comments (`# plantarch labels ...`, see writeOBJ) into object
    /// data: "plantID", "plant_name", "organ", "shootID", "rank", "node", "leafID" and "age",
    /// as the writers read them. When every object has a recorded `object=` ID, the IDs
    /// increase through the file and all are free in the Context (at or above every ID it
    /// has issued, as in a fresh Context, with fewer than `maxSkippedObjectIDs` unused IDs
    /// below them), the objects get exactly those IDs; otherwise new IDs in file order.
    bool labels = true;
    /// The most object IDs that keeping the recorded ones may leave unused (each costs the
    /// Context a few dozen bytes); above it the objects are numbered afresh.
    unsigned maxSkippedObjectIDs = 1u << 20;
    /// Receives tinyobjloader's warnings (for example a .mtl that was not found, which is
    /// not an error: the objects get the default material). Ignored when empty.
    std::function<void(const std::string& message)> onWarning;
    /// Receives ("reading OBJ", fraction) while the file is read; may be empty. The parse
    /// itself is one step, so the fraction moves in a few large steps.
    ProgressCallback progress;
};

/// Reads a Wavefront OBJ file (with its .mtl materials) into `context` and returns the IDs
/// of the objects added, in file order.
///
/// One object per run of faces of one shape (`o` / `g`) with the same material, labelled from
/// the plantarch label comments (ObjReadOptions::labels). Polygons
/// are triangulated (fan); UVs are kept when present; normals in the file are ignored.
/// Each object's material takes the colour (`Kd`), texture path (`map_Kd`, resolved so it
/// can be opened from the working directory) and name of its .mtl material; faces without
/// a material get Material{}.
///
/// Throws Error naming the file when it cannot be read, is malformed (tinyobjloader's
/// message included; also an index out of range or a coordinate that is not finite), or
/// holds no faces. On error `context` is left unchanged.
std::vector<ObjectID> readOBJ(Context& context, const std::string& path,
                              const ObjReadOptions& options = {});

// ---- PLY ---------------------------------------------------------------------------

enum class PlyFormat {
    BinaryLittleEndian,  ///< `format binary_little_endian 1.0`: compact and fast
    Ascii,               ///< `format ascii 1.0`: human-readable
};

/// Vertex colours of a PLY mesh (`uchar red green blue`), one colour per object.
enum class PlyColor {
    None,      ///< no colour properties
    Organ,     ///< the organ's label colour (organLabelColors(); trellis as obstacle)
    Plant,     ///< a colour per plant ID: hues spaced by the golden angle; grey for no plant
    Material,  ///< the object's material colour (Material::color, 0..1 as 0..255)
};
/// "none", "organ", "plant", "material".
const char* plyColorName(PlyColor color);
/// The PlyColor of a name of plyColorName; nullopt for another text.
std::optional<PlyColor> plyColorFromName(std::string_view name);

/// Options of writePLY.
struct PlyOptions {
    PlyFormat format = PlyFormat::BinaryLittleEndian;
    /// Also write hidden objects (skipped by default).
    bool includeHidden = false;
    /// Add per-vertex smooth normals (`nx ny nz`, computed as for OBJ).
    bool normals = false;
    /// Add per-vertex colours (`red green blue`, after the normals) coding a label.
    PlyColor color = PlyColor::None;
    /// Receives ("writing PLY", fraction) while the file is written; may be empty.
    ProgressCallback progress;
};

/// Integer organ labels written by writePLY, index = label: "unlabelled", the organ kinds'
/// names in OrganKind order (plantarch/PlantState.h: "internode" ... "fruit"), "ground",
/// "obstacle". Objects without "organ" data (or with an empty string) get 0. Organ strings
/// not in this list get the next integers (10, 11, ...) in sorted order of the strings present
/// among the exported objects.
inline constexpr std::array<std::string_view, kOrganKinds + 3> kOrganLabels = [] {
    std::array<std::string_view, kOrganKinds + 3> labels{};
    labels[0] = "unlabelled";
    for (std::size_t k = 0; k < kOrganKinds; ++k) labels[k + 1] = kStateNames<OrganKind>[k].name;
    labels[kOrganKinds + 1] = "ground";
    labels[kOrganKinds + 2] = "obstacle";
    return labels;
}();

/// An organ's colour in label images (plantarch/Render.h) and colour-coded PLY files.
struct OrganLabelColor {
    std::string_view organ;
    std::array<std::uint8_t, 3> rgb;
};
/// The organ label colour table (listed in plantarch/Render.h), in table order.
const std::vector<OrganLabelColor>& organLabelColors();
/// Colour of an organ name; unknown names give the "other" colour (white).
std::array<std::uint8_t, 3> organLabelColor(std::string_view organ);

/// The organ label table writePLY would use for `context`: kOrganLabels followed by the
/// other organ strings of the exported objects in sorted order. Entry i names label i.
std::vector<std::string> organLabelTable(const Context& context, bool includeHidden = false);

/// Writes the visible objects of `context` as a PLY mesh, ready to use as segmentation
/// ground truth:
///
///   element vertex N: float x, y, z (and nx, ny, nz with PlyOptions::normals; uchar red,
///                     green, blue with PlyOptions::color)
///   element face M:   list uchar int vertex_indices, int plant_id, int object_id,
///                     int organ, int leaf_id, int shoot_id, int rank, int node, float age
///
/// plant_id is the object's "plantID" int data, object_id its object ID, organ its label (see
/// kOrganLabels), leaf_id, shoot_id, rank and node its "leafID", "shootID", "rank" and "node"
/// int data (-1 when absent), age its "age" float data (days, -1 when absent); ASCII and
/// binary files hold the same properties. The header lists the label names as lines
/// `comment organ_label <int> <name>`. Vertices of each object are written in order, so
/// objects never share vertices.
///
/// Throws Error (naming the file) when the file cannot be written, when "organ" or
/// "plantID" data have the wrong type, or when the scene has more vertices than an int
/// index can address.
void writePLY(const Context& context, const std::string& path, const PlyOptions& options = {});

/// Options of readPLY.
struct PlyReadOptions {
    /// Read the per-face labels writePLY writes: one object per `object_id`, with "plantID",
    /// "organ" (named by the file's `comment organ_label` lines), "leafID", "shootID",
    /// "rank", "node" and "age" data where the face has them (-1: absent). Off, or in files
    /// without `object_id`, the whole mesh is one object.
    bool labels = true;
    /// Receives ("reading PLY", fraction) while the file is parsed; may be empty.
    ProgressCallback progress;
};

/// Reads a PLY mesh (`format ascii`, `binary_little_endian` or `binary_big_endian` 1.0; at
/// most 4 GiB) into `context` and returns the IDs of the objects added, in file order: the
/// `vertex` element's x, y, z (any number type; other properties, such as normals and
/// colours, are skipped) and the `face` element's `vertex_indices` (or `vertex_index`) lists,
/// polygons of 3 to 1024 corners triangulated as fans; other elements are skipped. An object
/// whose vertices carry uchar `red green blue` (writePLY's PlyColor::Material) gets a material
/// of its first vertex's colour, others the default material. Throws Error naming the file for a
/// malformed header, data that ends early, a number that is not one, a vertex that is not finite, a
/// corner index out of range, or no faces; on error `context` is left unchanged.
std::vector<ObjectID> readPLY(Context& context, const std::string& path,
                              const PlyReadOptions& options = {});

/// The points of a PLY file (a point cloud, or a mesh's vertices): its `vertex` element's x,
/// y, z in file order, whatever else the file holds. Throws Error naming the file as readPLY
/// does, and for a file without vertices.
std::vector<vec3> readPLYPoints(const std::string& path);

/// Reads the triangle meshes of a glTF 2.0 scene (.glb, or .gltf with its buffers embedded
/// as data URIs; at most 4 GiB) into `context` and returns the IDs of the objects added: the
/// default scene's nodes with their transforms, glTF's y up turned into plantarch's z up. A
/// file plantarch wrote reads back as its objects, one per `_OBJECT_ID` in ascending order,
/// with "plantID" and "organ" data from `_PLANT_ID` and `_ORGAN`; in other files each
/// primitive is one object, in file order.
/// Materials and textures are not read. Throws Error naming the file for malformed JSON or
/// binary chunks, references or accessors out of range, node cycles, external buffer files,
/// or no triangles; on error `context` is left unchanged.
std::vector<ObjectID> readGLTF(Context& context, const std::string& path);

/// Reads an obstacle mesh, OBJ (readOBJ) or PLY (readPLY) by its extension: its geometry only
/// (without labels, whatever its file carries: an obstacle is no plant), each object with
/// organ "obstacle". Throws Error naming the file for another extension.
std::vector<ObjectID> readObstacleMesh(Context& context, const std::string& path);

/// A plant as a glTF file names it: its node is called "<species>_<id>", placed at its base,
/// with the species, age and seed in the node's extras.
struct GltfPlant {
    std::int32_t id = 0;
    std::string species;
    vec3 base{0.0f};
    double age = 0.0;
    std::uint64_t seed = 0;
};

// ---- a wind-ready skeleton (skinned glTF, UsdSkel) --------------------------------------

/// A joint of a plant's skeleton (GltfSkeleton), at its bind pose, in plantarch's world axes
/// (z up), m: the plant's root joint at its base, or one joint per internode at the internode's
/// base (its node below), turning what the internode carries.
struct GltfJoint {
    std::string name;          ///< "plant<P>_root" or "plant<P>_shoot<S>_node<N>"
    std::int32_t parent = -1;  ///< index in GltfSkeleton::joints (smaller than its own); -1: root
    vec3 position{0.0f};       ///< the joint's origin, world
    /// Its orientation, world: a unit quaternion (x, y, z, w) taking the joint's local axes to
    /// world axes; local +y runs along its internode, local +x toward the internode's roll
    /// reference (where petioles of azimuth 0 stand).
    std::array<float, 4> rotation{0.0f, 0.0f, 0.0f, 1.0f};
    std::int32_t shoot = -1, node = -1;  ///< the internode's shoot ID and node (-1: the root)
};

/// Up to four joints moving one vertex, with weights (non-negative, summing to 1; unused slots
/// joint 0 and weight 0).
struct GltfInfluence {
    std::array<std::uint16_t, 4> joints{};
    std::array<float, 4> weights{};
};

/// How an object of a plant is bound to its skeleton.
struct GltfSkinnedObject {
    ObjectID object = kNoObject;
    std::uint16_t joint = 0;  ///< the joint moving every vertex, when `vertices` is empty
    /// Per vertex of the object (its positions, in order), or empty (rigid on `joint`).
    std::vector<GltfInfluence> vertices;
};

/// A plant's skeleton and the binding of its objects, made by exportSkeletons
/// (plantarch/ExportPlants.h). The bind pose is the geometry as it stands in the Context.
struct GltfSkeleton {
    std::int32_t plant = 0;
    std::vector<GltfJoint> joints;  ///< joints[0] is the root; parents before children
    /// In ascending object ID; an object of the plant not listed is rigid on the root.
    std::vector<GltfSkinnedObject> objects;
};

/// One lower level of detail of a glTF file (GltfOptions::levels). Every level keeps every
/// object with its ID, material and labels; only its mesh is coarser.
struct GltfLevel {
    enum class Kind {
        Reduced,  ///< each object simplified by meshoptimizer to `share` of its triangles
        Cards,    ///< each object a card: one quad for a flat organ, two crossed ones otherwise
    };
    Kind kind = Kind::Reduced;
    /// Reduced: the share of each object's triangles kept, above 0 and below 1.
    float share = 0.25f;
    /// MSFT_screencoverage: the level is shown while the plant covers less than this share of
    /// the screen's height (and more than the next level's), above 0 and below 1; 0 (the
    /// default) for 0.4 / 3^i, level i counted from 0 (gltfLevelCoverage).
    float coverage = 0.0f;
};
/// "reduced", "cards".
const char* gltfLevelName(GltfLevel::Kind kind);
/// Throws plantarch::Error (parameter "levels", the value, the valid range) unless each level's
/// share is above 0 and below 1 and the coverages fall from one level to the next within 0 to 1.
void checkGltfLevels(const std::vector<GltfLevel>& levels);
/// The screen coverage of levels[i]: its own, or 0.4 / 3^i when it has none (0).
float gltfLevelCoverage(const std::vector<GltfLevel>& levels, std::size_t i);
/// Levels from text (the command line's --lod): comma-separated `reduced` (a quarter of the
/// triangles), `reduced:SHARE` (0 < SHARE < 1) or `cards`, each optionally `@COVERAGE` (without,
/// gltfLevelCoverage's default). "none" or "" gives no levels. Throws plantarch::Error
/// (parameter `option`, the text, the valid form) for anything else.
std::vector<GltfLevel> parseGltfLevels(std::string_view text, const std::string& option = "lod");

// ---- organ granularity and instancing (glTF and USD) ------------------------------------

/// How a glTF or USD file groups each plant's geometry into nodes (USD: prims).
enum class NodeLevel {
    Plant,  ///< one mesh per plant, a primitive (USD: a mesh) per material
    Kind,   ///< under each plant, one mesh per organ kind (the default)
    /// Under each plant, a node per shoot and under it a node per organ (each leaf, internode,
    /// petiole, flower, fruit ...), named "<organ>_s<shoot>_n<node>[_l<leaf>][_<k>]" and
    /// labelled in its extras (USD: customData); organs of one shape share a mesh (instancing).
    Organ,
};
/// "plant", "kind", "organ".
const char* nodeLevelName(NodeLevel level);
/// The NodeLevel of a name of nodeLevelName; nullopt for another text.
std::optional<NodeLevel> nodeLevelFromName(std::string_view name);

/// How organs of one shape (equal up to a translation, rotation and uniform scale) are stored
/// with a node per organ (docs/formats.md, "Nodes and instancing").
enum class Instancing {
    None,    ///< every organ its own mesh
    Shared,  ///< organ nodes (USD prims) that point at one mesh (the default)
    /// Each shape that two or more organs of a plant use is one node with EXT_mesh_gpu_instancing
    /// (USD: a UsdGeomPointInstancer per plant), the organs its instances, labelled per
    /// instance; organs of a shape of their own keep their nodes. Needs NodeLevel::Organ and
    /// cannot be animated.
    Gpu,
};
/// "none", "shared", "gpu".
const char* instancingName(Instancing instancing);
/// The Instancing of a name of instancingName; nullopt for another text.
std::optional<Instancing> instancingFromName(std::string_view name);

struct GltfOptions {
    bool includeHidden = false;
    bool normals = true;   ///< smooth per-vertex normals (NORMAL)
    bool uvs = true;       ///< TEXCOORD_0 for primitives whose objects all have UVs
    bool textures = true;  ///< embed the image of every material that has one
    /// Labels: _PLANT_ID, _OBJECT_ID, _ORGAN and _FEATURE_ID_0 vertex attributes (floats),
    /// EXT_mesh_features feature IDs and an EXT_structural_metadata property table with the
    /// plant, object, organ, leaf, shoot, rank, node and age of every object (docs/formats.md).
    bool labels = true;
    /// Plants to name and place (from the PlantArchitecture: getPlantBasePosition, ...); a
    /// plant not listed gets a node named "plant_<id>" at the origin.
    std::vector<GltfPlant> plants;
    /// Skinning (a wind-ready skeleton): the skeletons of plants whose meshes get a glTF skin
    /// (JOINTS_0, WEIGHTS_0, joint nodes, inverse bind matrices); empty: no skins. Ignored
    /// by growth animations.
    std::vector<GltfSkeleton> skeletons;
    /// With skeletons: a looping two-second animation "wind" swaying every skinned plant toward
    /// +x (world), each joint turning about the horizontal axis across the wind, more toward the
    /// tips and a little later the higher it is, the deepest tip by about this many degrees in
    /// all (0 to 90; 0: no animation).
    float windDegrees = 0.0f;
    /// Materials and textures: with MaterialStyle::Textured, PBR materials with
    /// baseColorTexture (alphaMode MASK where a leaf's outline needs it), normalTexture,
    /// occlusionTexture and metallicRoughnessTexture, the PNG images embedded.
    MaterialOptions appearance;
    // Levels of detail and compression (docs/formats.md, "Levels of detail").
    /// Lower levels of detail after the full one, from finer to coarser, written as MSFT_lod
    /// alternatives of each plant's node (and of the node of the objects of no plant); empty:
    /// the full geometry only. Not with growth animations.
    std::vector<GltfLevel> levels;
    /// Compress the buffer views with EXT_meshopt_compression (lossless: the same vertices,
    /// triangles and labels), listed in extensionsRequired. Readers need meshoptimizer's
    /// decoder (three.js with MeshoptDecoder, Babylon.js, gltfpack); Blender 3.4 cannot read it.
    bool meshoptCompression = false;
    // Organ granularity and instancing (docs/formats.md, "Nodes and instancing").
    /// How the geometry is grouped into nodes. Growth animations always have a node per organ.
    NodeLevel nodes = NodeLevel::Kind;
    /// With a node per organ: organs whose geometry equals another organ's up to a translation,
    /// rotation and uniform scale place that organ's mesh instead of storing their own (the
    /// shared mesh then carries the plant and organ labels per vertex, the object's in the
    /// node's extras); Instancing::Gpu makes them instances of one node.
    Instancing instancing = Instancing::Shared;
    /// Receives ("writing glTF", fraction) while the file is written; may be empty.
    ProgressCallback progress;
};

/// Writes the Context as glTF 2.0: a .glb file (binary) or a .gltf file (JSON with the buffer
/// embedded as base64), atomically. One node per plant (and one for the objects of no plant),
/// one mesh per organ kind under it, one primitive per material; z up in plantarch becomes y
/// up in glTF by a rotation of the root node. Throws plantarch::Error naming the file.
void writeGLTF(const Context& context, const std::string& path, const GltfOptions& options = {});

struct UsdOptions {
    bool includeHidden = false;
    bool normals = true;  ///< primvars:normals (vertex interpolation)
    bool uvs = true;      ///< primvars:st for meshes whose objects all have UVs
    /// Plants to name and place, as for glTF.
    std::vector<GltfPlant> plants;
    /// Skinning (a wind-ready skeleton): as GltfOptions::skeletons, written as UsdSkel (a
    /// SkelRoot per plant, a Skeleton, joint indices and weights on its meshes).
    std::vector<GltfSkeleton> skeletons;
    /// Materials and textures: with MaterialStyle::Textured, a UsdPreviewSurface per material
    /// (UsdUVTexture shaders reading primvars:st) bound to the meshes, the PNG files named
    /// `<stem>_<texture>_<map>.png` next to the .usda (written atomically with it), or inside
    /// the package for a .usdz.
    MaterialOptions appearance;
    // Organ granularity and instancing, as for glTF.
    NodeLevel nodes = NodeLevel::Kind;
    Instancing instancing = Instancing::Shared;
    /// Receives ("writing USD", fraction) while the file is written; may be empty.
    ProgressCallback progress;
};

/// Writes the Context as a USD text file (.usda), atomically: upAxis Z, metersPerUnit 1, an
/// Xform per plant (translated to its base; plantID, species, age, seed in customData) and a
/// Mesh per organ kind under it, with primvars normals and st, per-face (uniform) primvars
/// displayColor, organ, plantID, objectID, leafID, shootID, rank, node and age, and the organ kind
/// as a semantic class label
/// (SemanticsLabelsAPI). Throws plantarch::Error naming the file.
void writeUSDA(const Context& context, const std::string& path, const UsdOptions& options = {});

/// One frame of an animation: the geometry of the scene at one time, and its plants.
struct AnimationFrame {
    const Context* context = nullptr;  ///< must outlive the write
    double day = 0.0;                  ///< the frame's time, days (increasing from frame to frame)
    std::vector<GltfPlant> plants;     ///< as GltfOptions::plants, at this frame
};

/// How an animation plays: `framesPerSecond` frames a second, one frame shown at a time.
struct AnimationOptions {
    double framesPerSecond = 24.0;  ///< 0.001 to 1000
    /// writeGrowthAnimation's progress (may be empty): ("growing", fraction) over the frames,
    /// then each file's writing ("writing glTF", "writing USD"). The animated writeGLTF and
    /// writeUSDA report through their GltfOptions and UsdOptions instead.
    ProgressCallback progress;
    /// writeGrowthAnimation's materials (MaterialOptions), given to each file's writer; the
    /// animated writeGLTF and writeUSDA take theirs from their GltfOptions and UsdOptions.
    MaterialOptions appearance;
};

/// Writes frames as one animated glTF (.glb or .gltf): a node per organ, laid out as
/// NodeLevel::Organ lays out a still file, its organs followed from frame to frame by their
/// labels. An animation "growth" (extras {"days": [...]}) keys, with STEP samplers at
/// i / framesPerSecond seconds for frame i, each organ node's translation, rotation and scale
/// (scale 0 before the organ exists) and, for an organ whose shape changed in another way, the
/// weights selecting its morph targets. The property table holds a row per organ. Throws
/// plantarch::Error naming the file for no frames, times not increasing or a bad rate.
void writeGLTF(const std::vector<AnimationFrame>& frames, const std::string& path,
               const GltfOptions& options = {}, const AnimationOptions& animation = {});

/// Writes frames as one animated USD file (.usda, or .usdz): a prim per organ as
/// NodeLevel::Organ lays out a still file, its translate, orient and scale time-sampled at
/// time code i for frame i (startTimeCode 0, endTimeCode the last frame's index,
/// timeCodesPerSecond = framesPerSecond) and its visibility keyed invisible before it appears;
/// an organ whose shape changed holds a mesh per shape, each visible on its frames. Throws
/// plantarch::Error as the glTF form does.
void writeUSDA(const std::vector<AnimationFrame>& frames, const std::string& path,
               const UsdOptions& options = {}, const AnimationOptions& animation = {});

/// How samplePoints draws a point cloud.
struct PointSampleOptions {
    std::size_t points = 100000;  ///< points to draw, 1 to 2^31
    std::uint64_t seed = 0;       ///< same seed, same points
    bool includeHidden = false;
    /// Receives ("sampling points", fraction) while the points are drawn; may be empty.
    ProgressCallback progress;
};

/// A labelled point cloud: parallel arrays, one entry per point.
struct PointCloud {
    std::vector<vec3> positions;        ///< m
    std::vector<vec3> normals;          ///< unit normal of the triangle the point lies on
    std::vector<std::int32_t> plantID;  ///< -1 for objects of no plant
    std::vector<ObjectID> objectID;
    std::vector<std::uint8_t> organ;    ///< index into kOrganLabels
    std::vector<std::int32_t> leafID;   ///< leaf within its plant (-1: not a leaf)
    std::vector<std::int32_t> shootID;  ///< shoot within its plant (-1: none)
    std::vector<std::int32_t> rank;     ///< shoot rank, 0 for the base stem (-1: none)
    std::vector<float> age;             ///< organ age, days (-1: unknown)
    /// Scans only (empty for surface samples): distance from the scanner to the point (m,
    /// with the scan's range noise) and the index of the scanner that saw it.
    std::vector<float> range;
    std::vector<std::uint16_t> scanner;
};

/// Memory one sampled point takes while it is drawn and written (its arrays and its share of
/// the writer's buffer), for the estimate of maxSamplePoints.
inline constexpr std::size_t kBytesPerSamplePoint = 112;
/// The most points samplePoints draws on this machine: half its physical memory at
/// kBytesPerSamplePoint a point (2^31 at most; 2^31 when the memory is unknown).
std::size_t maxSamplePoints();

/// Points drawn uniformly by area over the (visible) triangles of the Context, each with its
/// face normal and its object's labels. Deterministic for a seed. Throws plantarch::Error for
/// a point count out of range (above maxSamplePoints too, before any work) or a scene with no
/// surface.
PointCloud samplePoints(const Context& context, const PointSampleOptions& options = {});

/// Writes a point cloud as a binary PLY of vertices (x y z nx ny nz plant_id object_id organ
/// leaf_id shoot_id rank age, and range scanner for a scan; the organ table in the header's
/// comments), atomically.
/// Throws plantarch::Error naming the file when the arrays differ in length.
/// `progress` (may be empty) receives ("writing PLY", fraction).
void writePointCloudPLY(const PointCloud& cloud, const std::string& path,
                        const ProgressCallback& progress = {});

/// Writes a point cloud as a NumPy .npz archive (numpy.load), atomically: arrays positions
/// (N x 3 float32), normals (N x 3 float32), plant_id (int32), object_id (uint32), organ
/// (uint8), leaf_id, shoot_id, rank (int32), age (float32), organ_labels (the names of
/// kOrganLabels), and for a scan range (float32) and
/// scanner (uint16). Throws plantarch::Error as writePointCloudPLY does. `progress` (may be
/// empty) receives ("writing NPZ", fraction).
void writePointCloudNPZ(const PointCloud& cloud, const std::string& path,
                        const ProgressCallback& progress = {});

/// Smooth per-vertex normals of one object (as the OBJ and PLY writers write them): the
/// area-weighted sum of the normals of the triangles around each vertex, normalized; (0, 0, 1)
/// where that sum vanishes. `normals` is resized to the object's vertex count.
void smoothNormals(const ObjectView& object, std::vector<vec3>& normals);

}  // namespace plantarch
