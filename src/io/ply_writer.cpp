// PLY writer (binary little-endian and ASCII) with per-face plant, object and organ labels
// for segmentation ground truth. The binary path copies whole blocks into the output
// buffer: positions straight from the Context's arrays, faces as 25-byte records.

#include <bit>
#include <climits>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "core/progress_steps.h"
#include "io/export_common.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"

namespace plantarch {

namespace {

static_assert(std::endian::native == std::endian::little,
              "the binary PLY writer copies native floats and ints as little-endian");
static_assert(sizeof(vec3) == 3 * sizeof(float), "vec3 must be three packed floats");

constexpr std::size_t kFaceBytes = 1 + 3 * 4 + 3 * 4;  // count, 3 indices, 3 labels
constexpr std::size_t kFacesPerChunk = io::AtomicFile::kMaxReserve / kFaceBytes;
constexpr std::size_t kLineBytes = 256;

struct ObjectLabels {
    std::int32_t plant = -1;
    std::int32_t organ = 0;
};

struct SceneLabels {
    std::vector<std::string> organNames;  // index = organ label
    std::vector<ObjectLabels> perObject;  // parallel to the exported IDs
};

SceneLabels sceneLabels(const Context& context, const std::vector<ObjectID>& ids) {
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
    s.perObject.resize(ids.size());
    for (std::size_t i = 0; i < ids.size(); ++i) {
        s.perObject[i].plant = context.objectDataInt(ids[i], "plantID").value_or(-1);
        s.perObject[i].organ = organs[i].empty() ? 0 : index.find(organs[i])->second;
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
    h += "comment plantarch export: per-face plant_id (-1: none), object_id, organ label\n";
    for (std::size_t i = 0; i < labels.organNames.size(); ++i)
        h +=
            "comment organ_label " + std::to_string(i) + " " + oneLine(labels.organNames[i]) + "\n";
    h += "element vertex " + std::to_string(vertices) + "\n";
    h += "property float x\nproperty float y\nproperty float z\n";
    if (options.normals) h += "property float nx\nproperty float ny\nproperty float nz\n";
    h += "element face " + std::to_string(faces) + "\n";
    h += "property list uchar int vertex_indices\n";
    h += "property int plant_id\nproperty int object_id\nproperty int organ\n";
    h += "end_header\n";
    out.write(h);
}

void writeBinaryVertices(io::AtomicFile& out, const ObjectView& o, const PlyOptions& options,
                         std::vector<vec3>& normals) {
    if (!options.normals) {
        out.write(o.positions.data(), o.positions.size_bytes());
        return;
    }
    io::smoothNormals(o, normals);
    constexpr std::size_t kVertexBytes = 2 * sizeof(vec3);
    constexpr std::size_t kChunk = io::AtomicFile::kMaxReserve / kVertexBytes;
    for (std::size_t first = 0; first < o.positions.size(); first += kChunk) {
        const std::size_t n = std::min(kChunk, o.positions.size() - first);
        char* p = out.reserve(n * kVertexBytes);
        for (std::size_t i = first; i < first + n; ++i) {
            std::memcpy(p, &o.positions[i], sizeof(vec3));
            std::memcpy(p + sizeof(vec3), &normals[i], sizeof(vec3));
            p += kVertexBytes;
        }
        out.advance(p);
    }
}

void writeBinaryFaces(io::AtomicFile& out, const ObjectView& o, std::int32_t base,
                      const ObjectLabels& labels) {
    // One record: uchar 3, int a, b, c, int plant_id, object_id, organ. Stored field by
    // field: staging a record on the stack and copying it stalls store forwarding.
    const std::int32_t tail[3] = {labels.plant, static_cast<std::int32_t>(o.id), labels.organ};
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
                        std::vector<vec3>& normals) {
    if (options.normals) io::smoothNormals(o, normals);
    for (std::size_t i = 0; i < o.positions.size(); ++i) {
        char* p = out.reserve(kLineBytes);
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
        *p++ = '\n';
        out.advance(p);
    }
}

void writeAsciiFaces(io::AtomicFile& out, const ObjectView& o, std::int32_t base,
                     const ObjectLabels& labels) {
    // The labels end every line of this object: format them once.
    char tail[3 * 12 + 2];
    char* q = tail;
    *q++ = ' ';
    q = io::writeInt(q, labels.plant);
    *q++ = ' ';
    q = io::writeUInt(q, o.id);
    *q++ = ' ';
    q = io::writeInt(q, labels.organ);
    *q++ = '\n';
    const std::size_t tailLength = static_cast<std::size_t>(q - tail);
    const auto& idx = o.indices;
    for (std::size_t t = 0; t + 2 < idx.size(); t += 3) {
        char* p = out.reserve(kLineBytes);
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

std::vector<std::string> organLabelTable(const Context& context, bool includeHidden) {
    return sceneLabels(context, io::exportedObjects(context, includeHidden)).organNames;
}

void writePLY(const Context& context, const std::string& path, const PlyOptions& options) {
    io::requireDataType(context, "organ", DataType::String, path);
    io::requireDataType(context, "plantID", DataType::Int, path);
    const std::vector<ObjectID> ids = io::exportedObjects(context, options.includeHidden);
    const SceneLabels labels = sceneLabels(context, ids);
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
    for (ObjectID id : ids) {
        const ObjectView o = context.object(id);
        if (binary)
            writeBinaryVertices(out, o, options, normals);
        else
            writeAsciiVertices(out, o, options, normals);
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
