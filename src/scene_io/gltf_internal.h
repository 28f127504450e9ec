#pragma once
// The glTF writer's pieces, shared by the files that write parts of a document (materials,
// levels of detail, skins, ...): the scene being written, and the binary buffer.
//
// A part adds its arrays to GltfArrays and reserves its buffer views with Buffer::add, giving
// each view the function that later writes its bytes. The writer lays out the JSON first, then
// streams the views in the order they were added, so a part never has to know what other parts
// wrote before or after it.

#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "core/progress_steps.h"
#include "plantarch/Context.h"
#include "plantarch/Export.h"
#include "scene_io/organ_tracks.h"

namespace plantarch::gltf {

using json = nlohmann::json;

static_assert(std::endian::native == std::endian::little, "glTF buffers are little-endian");

constexpr int kFloat = 5126, kUInt = 5125;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

// The property table's optional columns: float object data a physiology season leaves (on
// leaves, or on every object of a shoot with a carbohydrate budget). A column is written when
// any exported object carries its data (as a float); the others' rows hold kNoData, declared
// as the property's noData. A scene with none of them is written as before.
struct OptionalColumn {
    const char* name;  // the object data's label, and the column's name
    const char* description;
};
constexpr OptionalColumn kOptionalColumns[] = {
    {"absorbed_par",
     "PAR absorbed, umol m-2 s-1, mean over the last simulated day's daylight hours"},
    {"sunlit_fraction", "sunlit share of the leaf, 0 to 1, mean over the same hours"},
    {"net_photosynthesis", "net CO2 assimilation, umol m-2 s-1, mean over the same hours"},
    {"carbohydrate_concentration",
     "the shoot's sugar and starch per structural carbon of its wood, mol C / mol C"},
};
constexpr std::size_t kOptionalCount = std::size(kOptionalColumns);
constexpr float kNoData = -9999.0f;

// What one exported object contributes, and where.
struct ObjectRecord {
    ObjectID id;
    std::int32_t plant;
    std::uint8_t organ;
    std::int32_t leaf, shoot, rank, node;
    float age;
    std::size_t material;  // index into Scene::materials
    std::uint32_t frame;
    bool uvs;
    std::array<float, kOptionalCount> optional;  // kNoData where the object has no such data
};

// One primitive: the objects of one (node, organ kind, material).
struct Primitive {
    std::size_t node;
    std::uint8_t organ;
    std::size_t material;
    std::vector<std::size_t> objects;  // indices into the records
    std::size_t vertices = 0, triangles = 0;
    bool uvs = true;
};

struct Node {
    std::size_t frame;
    std::int32_t plant;  // -1: the objects of no plant
    vec3 base{0.0f};
    std::optional<GltfPlant> info;  // species, age and seed, when given
};

inline float linear(float srgb) {
    const float c = std::clamp(srgb, 0.0f, 1.0f);
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

inline std::size_t align8(std::size_t n) {
    return (n + 7) & ~std::size_t(7);
}

// A texture image as embedded: the bytes of a file that decoded as a PNG or JPEG image.
struct EmbeddedImage {
    std::string bytes;
    const char* mimeType;
};

// Writes bytes to a .glb file or collects them for a .gltf's base64. Blocks are filled in
// place (reserve, then commit), so each byte is copied once on its way to the file.
class Sink {
public:
    static constexpr std::size_t kBlock = io::AtomicFile::kMaxReserve;

    Sink(io::AtomicFile* file, std::string* bytes, ProgressSteps& steps)
        : file_(file), bytes_(bytes), steps_(steps) {}
    void write(const void* data, std::size_t n) {
        if (file_)
            file_->write(data, n);
        else
            bytes_->append(static_cast<const char*>(data), n);
        written_ += n;
        steps_.at(double(written_));
    }
    /// Room for n <= kBlock bytes, to be filled and then handed back with commit(n).
    char* reserve(std::size_t n) {
        if (file_) return file_->reserve(n);
        bytes_->resize(written_ + n);
        return bytes_->data() + written_;
    }
    void commit(std::size_t n) {
        if (file_) file_->advance(file_->reserve(n) + n);
        written_ += n;
        steps_.at(double(written_));
    }
    std::size_t written() const { return written_; }
    void pad() {
        static const char zeros[8] = {};
        write(zeros, align8(written_) - written_);
    }

    /// Writes `count` elements of `size` bytes, made by fill(destination, first, n) in
    /// blocks of n elements.
    template <class Fill>
    void elements(std::size_t count, std::size_t size, Fill&& fill) {
        const std::size_t perBlock = kBlock / size;
        for (std::size_t first = 0; first < count; first += perBlock) {
            const std::size_t n = std::min(perBlock, count - first);
            fill(reserve(n * size), first, n);
            commit(n * size);
        }
    }

private:
    io::AtomicFile* file_;
    std::string* bytes_;
    ProgressSteps& steps_;  // by bytes of the buffer
    std::size_t written_ = 0;
};

// The byte blocks of the binary buffer, in order, each with the function that writes it.
class Buffer {
public:
    /// Writes exactly the bytes reserved for its view.
    using Fill = std::function<void(Sink& out)>;

    /// Reserves a block of `bytes` (written later by `fill`) and returns its view index; a
    /// `target` of 0 leaves the view's target out.
    int add(json& views, std::size_t bytes, int target, Fill fill);
    std::size_t size() const { return size_; }
    std::size_t viewSize(int view) const { return blocks_[std::size_t(view)].bytes; }
    /// Writes every block in order, each padded to 8 bytes. Throws std::logic_error when a
    /// block writes another number of bytes than it reserved.
    void write(Sink& out) const;

private:
    struct Block {
        std::size_t bytes;
        Fill fill;
    };
    std::size_t size_ = 0;
    std::vector<Block> blocks_;
};

struct Scene {
    std::vector<const Context*> frames;
    std::vector<double> days;  // the frames' times
    bool animated = false;
    double framesPerSecond = 24.0;
    std::vector<ObjectRecord> records;
    std::vector<Node> nodes;
    std::vector<Primitive> primitives;
    std::vector<Material> materials;               // in glTF material order
    std::vector<std::string> images;               // texture files, in glTF image order
    std::vector<EmbeddedImage> imageData;          // each decoded and checked, as embedded
    std::array<bool, kOptionalCount> hasColumn{};  // the optional columns written
    // Smooth normals of record i: normals[normalAt[i]] on, one per vertex (when written).
    std::vector<vec3> normals;
    std::vector<std::size_t> normalAt;
    // A node per organ (NodeLevel::Organ, and every animation): the organs through the frames,
    // and each shape's material index; records then hold one row per organ track.
    bool organNodes = false;
    io::OrganTracks organs;
    std::vector<std::size_t> shapeMaterials;

    ObjectView object(const ObjectRecord& r) const { return frames[r.frame]->object(r.id); }
    ObjectView object(std::size_t record) const { return object(records[record]); }
};

/// Writes `count` values of T, value(i) for i in [0, count), as one block.
template <class T, class Value>
void writeValues(Sink& out, std::size_t count, Value value) {
    out.elements(count, sizeof(T), [&](char* dst, std::size_t first, std::size_t n) {
        for (std::size_t k = 0; k < n; ++k) {
            const T v = T(value(first + k));
            std::memcpy(dst + k * sizeof(T), &v, sizeof(T));
        }
    });
}

/// An accessor of `count` elements of a view.
json accessor(int view, int componentType, std::size_t count, const char* type);

/// A plant's node ("<species>_<id>" at its base, species, age and seed in its extras; "scene"
/// for the objects of no plant) over `children` (node indices).
json plantNode(const Node& node, const json& children);

/// The bytes of a decoded PNG or JPEG texture file, as embedded.
EmbeddedImage embeddedImage(const std::string& path);

// The arrays of the JSON document, filled in the order their buffer views are laid out.
struct GltfArrays {
    json views = json::array(), accessors = json::array(), meshes = json::array();
    json nodes = json::array(), materials = json::array();
    json textures = json::array(), images = json::array();
};

// ---- textured materials (gltf_materials.cpp) ----
/// The images, textures and materials of MaterialStyle::Textured (options.appearance).
void addTexturedMaterials(GltfArrays& d, const Scene& s, const GltfOptions& options,
                          Buffer& buffer);
/// TANGENT of a primitive whose material has a normal map (smooth normals written).
void addTangents(GltfArrays& d, const Scene& s, const GltfOptions& options, Buffer& buffer,
                 const Primitive& p, json& attributes);
/// Per-vertex tangents of one object (xyz along increasing u, w the bitangent's sign), made
/// perpendicular to its vertex `normals`.
void objectTangents(const ObjectView& o, const vec3* normals, std::vector<glm::vec4>& out);

// ---- a node per organ (gltf_organs.cpp) ----
/// Follows the organs of the scene's frames (io::trackOrgans) and makes the records one row per
/// organ, from its last frame.
void collectOrgans(Scene& s, const GltfOptions& options);
/// The plant, shoot and organ nodes of an organ-level scene; the plant nodes go to `roots`.
/// Returns the growth animation of an animated scene (empty otherwise).
json addOrganNodes(GltfArrays& d, const Scene& s, const GltfOptions& options, Buffer& buffer,
                   json& roots);

}  // namespace plantarch::gltf
