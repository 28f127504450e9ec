// PLY writer (binary little-endian and ASCII) with per-face labels (plant, object, organ,
// leaf, shoot, rank, node, age) for segmentation ground truth and optional vertex colours by
// label. The binary path copies whole blocks into the output buffer: positions straight from
// the Context's arrays, faces as 45-byte records.

#include <algorithm>
#include <array>
#include <bit>
#include <climits>
#include <cmath>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "core/progress_steps.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/OutputFormats.h"
#include "scene_io/export_common.h"

namespace plantarch {

namespace {

static_assert(std::endian::native == std::endian::little,
              "the binary PLY writer copies native floats and ints as little-endian");
static_assert(sizeof(vec3) == 3 * sizeof(float), "vec3 must be three packed floats");

// count, 3 indices, 7 int labels (plant_id, object_id, organ, leaf_id, shoot_id, rank, node)
// and a float (age).
constexpr std::size_t kFaceBytes = 1 + 3 * 4 + 7 * 4 + 4;
constexpr std::size_t kFacesPerChunk = io::AtomicFile::kMaxReserve / kFaceBytes;

// One object's per-face labels and its vertices' colour.
struct FaceLabels {
    std::int32_t plant = -1, organ = 0, leaf = -1, shoot = -1, rank = -1, node = -1;
    float age = -1.0f;
    std::array<std::uint8_t, 3> rgb{};
};

struct SceneLabels {
    std::vector<std::string> organNames;  // index = organ label
    std::vector<FaceLabels> perObject;    // parallel to the exported IDs
};

std::uint8_t colorByte(float c) {
    return static_cast<std::uint8_t>(std::lround(std::clamp(c, 0.0f, 1.0f) * 255.0f));
}

// A plant's colour: hues spaced by the golden angle (neighbouring IDs far apart on the colour
// wheel), saturation 0.65, value 0.95; grey for objects of no plant.
std::array<std::uint8_t, 3> plantColor(std::int32_t plant) {
    if (plant < 0) return {128, 128, 128};
    const double hue = std::fmod(double(plant) * 0.6180339887498949, 1.0) * 6.0;
    const int sector = int(hue);
    const double f = hue - sector, v = 0.95, p = v * 0.35, q = v * (1.0 - 0.65 * f),
                 t = v * (1.0 - 0.65 * (1.0 - f));
    const double rgb[6][3] = {{v, t, p}, {q, v, p}, {p, v, t}, {p, q, v}, {t, p, v}, {v, p, q}};
    const double* c = rgb[sector % 6];
    return {colorByte(float(c[0])), colorByte(float(c[1])), colorByte(float(c[2]))};
}

std::array<std::uint8_t, 3> objectColor(const Context& context, ObjectID id, PlyColor mode,
                                        const FaceLabels& l, const std::string& organ) {
    switch (mode) {
        case PlyColor::Organ:
            return organLabelColor(organ == "trellis" ? std::string_view("obstacle") : organ);
        case PlyColor::Plant:
            return plantColor(l.plant);
        case PlyColor::Material: {
            const vec3 c = context.material(context.objectMaterial(id)).color;
            return {colorByte(c.r), colorByte(c.g), colorByte(c.b)};
        }
        case PlyColor::None:
            break;
    }
    return {0, 0, 0};
}

SceneLabels sceneLabels(const Context& context, const std::vector<ObjectID>& ids, PlyColor color) {
    SceneLabels s;
    std::vector<std::string> organs(ids.size());
    std::map<std::string, std::int32_t, std::less<>> index;
    for (std::size_t i = 0; i < kOrganLabels.size(); ++i)
        index.emplace(std::string(kOrganLabels[i]), static_cast<std::int32_t>(i));
    std::map<std::string, std::int32_t, std::less<>> extra;  // sorted unknown names
    for (std::size_t i = 0; i < ids.size(); ++i) {
        organs[i] = io::organOf(context, ids[i]);
        if (!organs[i].empty() && !index.count(organs[i])) extra.emplace(organs[i], 0);
    }
    s.organNames.assign(kOrganLabels.begin(), kOrganLabels.end());
    for (auto& [name, label] : extra) {
        label = static_cast<std::int32_t>(s.organNames.size());
        s.organNames.push_back(name);
        index.emplace(name, label);
    }
    const io::LabelReader labelsOf(context);
    s.perObject.resize(ids.size());
    for (std::size_t i = 0; i < ids.size(); ++i) {
        const io::ObjectLabels l = labelsOf(ids[i]);
        FaceLabels& f = s.perObject[i];
        f = {l.plant, organs[i].empty() ? 0 : index.find(organs[i])->second,
             l.leaf,  l.shoot,
             l.rank,  l.node,
             l.age,   {}};
        f.rgb = objectColor(context, ids[i], color, f, organs[i]);
    }
    return s;
}

// Header text is line-based: keep every name on its line.
std::string oneLine(std::string text) {
    for (char& c : text)
        if (c == '\n' || c == '\r') c = '_';
    return text;
}

void writeHeader(io::AtomicFile& out, const PlyOptions& options, const SceneLabels& labels,
                 std::size_t vertices, std::size_t faces) {
    std::string h = "ply\nformat ";
    h += options.format == PlyFormat::Ascii ? "ascii 1.0\n" : "binary_little_endian 1.0\n";
    h += "comment plantarch export: per-face plant_id, object_id, organ label, leaf_id, "
         "shoot_id, rank, node (-1: none), age (days, -1: unknown)\n";
    if (options.color != PlyColor::None)
        h += std::string("comment vertex colour: ") + plyColorName(options.color) + "\n";
    for (std::size_t i = 0; i < labels.organNames.size(); ++i)
        h +=
            "comment organ_label " + std::to_string(i) + " " + oneLine(labels.organNames[i]) + "\n";
    h += "element vertex " + std::to_string(vertices) + "\n";
    h += "property float x\nproperty float y\nproperty float z\n";
    if (options.normals) h += "property float nx\nproperty float ny\nproperty float nz\n";
    if (options.color != PlyColor::None)
        h += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
    h += "element face " + std::to_string(faces) + "\n";
    h += "property list uchar int vertex_indices\n";
    h += "property int plant_id\nproperty int object_id\nproperty int organ\n";
    h += "property int leaf_id\nproperty int shoot_id\nproperty int rank\nproperty int node\n";
    h += "property float age\n";
    h += "end_header\n";
    out.write(h);
}

void writeBinaryVertices(io::AtomicFile& out, const ObjectView& o, const PlyOptions& options,
                         const FaceLabels& labels, std::vector<vec3>& normals) {
    const bool color = options.color != PlyColor::None;
    if (!options.normals && !color) {
        out.write(o.positions.data(), o.positions.size_bytes());
        return;
    }
    if (options.normals) io::smoothNormals(o, normals);
    const std::size_t vertexBytes = (options.normals ? 2 : 1) * sizeof(vec3) + (color ? 3 : 0);
    const std::size_t chunk = io::AtomicFile::kMaxReserve / vertexBytes;
    for (std::size_t first = 0; first < o.positions.size(); first += chunk) {
        const std::size_t n = std::min(chunk, o.positions.size() - first);
        char* p = out.reserve(n * vertexBytes);
        for (std::size_t i = first; i < first + n; ++i) {
            std::memcpy(p, &o.positions[i], sizeof(vec3));
            p += sizeof(vec3);
            if (options.normals) {
                std::memcpy(p, &normals[i], sizeof(vec3));
                p += sizeof(vec3);
            }
            if (color) {
                std::memcpy(p, labels.rgb.data(), 3);
                p += 3;
            }
        }
        out.advance(p);
    }
}

void writeBinaryFaces(io::AtomicFile& out, const ObjectView& o, std::int32_t base,
                      const FaceLabels& labels) {
    // One record: uchar 3, int a, b, c, then the labels (the same for the whole object).
    // Stored field by field: staging a record on the stack and copying it stalls store
    // forwarding.
    std::int32_t tail[8] = {labels.plant, static_cast<std::int32_t>(o.id),
                            labels.organ, labels.leaf,
                            labels.shoot, labels.rank,
                            labels.node,  0};
    std::memcpy(&tail[7], &labels.age, 4);
    const auto& idx = o.indices;
    const std::size_t triangles = idx.size() / 3;
    for (std::size_t first = 0; first < triangles; first += kFacesPerChunk) {
        const std::size_t n = std::min(kFacesPerChunk, triangles - first);
        char* p = out.reserve(n * kFaceBytes);
        for (std::size_t t = first; t < first + n; ++t) {
            const std::int32_t a = base + static_cast<std::int32_t>(idx[3 * t]);
            const std::int32_t b = base + static_cast<std::int32_t>(idx[3 * t + 1]);
            const std::int32_t c = base + static_cast<std::int32_t>(idx[3 * t + 2]);
            p[0] = 3;
            std::memcpy(p + 1, &a, 4);
            std::memcpy(p + 5, &b, 4);
            std::memcpy(p + 9, &c, 4);
            std::memcpy(p + 13, tail, sizeof(tail));
            p += kFaceBytes;
        }
        out.advance(p);
    }
}

void writeAsciiVertices(io::AtomicFile& out, const ObjectView& o, const PlyOptions& options,
                        const FaceLabels& labels, std::vector<vec3>& normals) {
    if (options.normals) io::smoothNormals(o, normals);
    for (std::size_t i = 0; i < o.positions.size(); ++i) {
        char* p = out.reserve(io::kLineBytes);
        const vec3& v = o.positions[i];
        p = io::writeFloat(p, v.x);
        *p++ = ' ';
        p = io::writeFloat(p, v.y);
        *p++ = ' ';
        p = io::writeFloat(p, v.z);
        if (options.normals) {
            const vec3& n = normals[i];
            *p++ = ' ';
            p = io::writeFixed6(p, n.x);
            *p++ = ' ';
            p = io::writeFixed6(p, n.y);
            *p++ = ' ';
            p = io::writeFixed6(p, n.z);
        }
        if (options.color != PlyColor::None)
            for (std::uint8_t c : labels.rgb) {
                *p++ = ' ';
                p = io::writeUInt(p, c);
            }
        *p++ = '\n';
        out.advance(p);
    }
}

void writeAsciiFaces(io::AtomicFile& out, const ObjectView& o, std::int32_t base,
                     const FaceLabels& labels) {
    // The labels end every line of this object: format them once.
    char tail[7 * 12 + io::kMaxFloatChars + 2];
    char* q = tail;
    for (const std::int64_t v :
         {std::int64_t(labels.plant), std::int64_t(o.id), std::int64_t(labels.organ),
          std::int64_t(labels.leaf), std::int64_t(labels.shoot), std::int64_t(labels.rank),
          std::int64_t(labels.node)}) {
        *q++ = ' ';
        q = io::writeInt(q, v);
    }
    *q++ = ' ';
    q = io::writeFloat(q, labels.age);
    *q++ = '\n';
    const std::size_t tailLength = static_cast<std::size_t>(q - tail);
    const auto& idx = o.indices;
    for (std::size_t t = 0; t + 2 < idx.size(); t += 3) {
        char* p = out.reserve(io::kLineBytes);
        *p++ = '3';
        for (int k = 0; k < 3; ++k) {
            *p++ = ' ';
            p = io::writeInt(p, base + static_cast<std::int64_t>(idx[t + k]));
        }
        std::memcpy(p, tail, tailLength);
        out.advance(p + tailLength);
    }
}

}  // namespace

const char* plyColorName(PlyColor color) {
    switch (color) {
        case PlyColor::Organ:
            return "organ";
        case PlyColor::Plant:
            return "plant";
        case PlyColor::Material:
            return "material";
        case PlyColor::None:
            break;
    }
    return "none";
}

std::optional<PlyColor> plyColorFromName(std::string_view name) {
    for (PlyColor c : {PlyColor::None, PlyColor::Organ, PlyColor::Plant, PlyColor::Material})
        if (name == plyColorName(c)) return c;
    return std::nullopt;
}

std::vector<std::string> organLabelTable(const Context& context, bool includeHidden) {
    return sceneLabels(context, io::exportedObjects(context, includeHidden), PlyColor::None)
        .organNames;
}

void writePLY(const Context& context, const std::string& path, const PlyOptions& options) {
    requireOutputFormat(path, {".ply"}, "writePLY writes a PLY mesh");
    io::requireDataType(context, "organ", DataType::String, path);
    io::requireDataType(context, "plantID", DataType::Int, path);
    const std::vector<ObjectID> ids = io::exportedObjects(context, options.includeHidden);
    const SceneLabels labels = sceneLabels(context, ids, options.color);
    std::size_t vertices = 0, faces = 0;
    for (ObjectID id : ids) {
        const ObjectView o = context.object(id);
        vertices += o.positions.size();
        faces += o.triangleCount();
    }
    if (vertices > static_cast<std::size_t>(INT_MAX))
        throw Error("too many vertices for PLY int indices",
                    {.file = path,
                     .value = std::to_string(vertices),
                     .validRange = "at most " + std::to_string(INT_MAX)});

    io::AtomicFile out(path);
    writeHeader(out, options, labels, vertices, faces);
    const bool binary = options.format == PlyFormat::BinaryLittleEndian;
    std::vector<vec3> normals;
    ProgressSteps steps(options.progress, "writing PLY", double(vertices + faces));
    double done = 0.0;
    for (std::size_t i = 0; i < ids.size(); ++i) {
        const ObjectView o = context.object(ids[i]);
        if (binary)
            writeBinaryVertices(out, o, options, labels.perObject[i], normals);
        else
            writeAsciiVertices(out, o, options, labels.perObject[i], normals);
        steps.at(done += double(o.positions.size()));
    }
    std::int32_t base = 0;
    for (std::size_t i = 0; i < ids.size(); ++i) {
        const ObjectView o = context.object(ids[i]);
        if (binary)
            writeBinaryFaces(out, o, base, labels.perObject[i]);
        else
            writeAsciiFaces(out, o, base, labels.perObject[i]);
        base += static_cast<std::int32_t>(o.positions.size());
        steps.at(done += double(o.triangleCount()));
    }
    out.commit();
    steps.finish();
}

}  // namespace plantarch
