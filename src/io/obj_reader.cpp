// Wavefront OBJ reader on tinyobjloader. Everything is parsed and checked before the Context
// is touched, so a bad file leaves the Context unchanged.

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <istream>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/input_file.h"
#include "core/progress_steps.h"
#include "io/obj_labels.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"

namespace plantarch {

namespace fs = std::filesystem;

namespace {

// Reads a file in blocks for the OBJ parser, telling how many bytes it has read so far.
class ProgressReadBuffer final : public std::streambuf {
public:
    // Blocks of `blockSize` bytes, not cleared before they are read into.
    ProgressReadBuffer(std::FILE* file, std::size_t blockSize,
                       std::function<void(std::uintmax_t)> onRead)
        : file_(file),
          onRead_(std::move(onRead)),
          block_(std::make_unique_for_overwrite<char[]>(blockSize)),
          blockSize_(blockSize) {}

    bool failed() const { return std::ferror(file_) != 0; }

protected:
    int_type underflow() override {
        if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
        const std::size_t n = std::fread(block_.get(), 1, blockSize_, file_);
        if (n == 0) return traits_type::eof();
        read_ += n;
        onRead_(read_);
        setg(block_.get(), block_.get(), block_.get() + n);
        return traits_type::to_int_type(*gptr());
    }

private:
    std::FILE* file_;
    std::function<void(std::uintmax_t)> onRead_;
    std::unique_ptr<char[]> block_;
    std::size_t blockSize_;
    std::uintmax_t read_ = 0;
};

std::string trimmed(const std::string& text) {
    const std::size_t first = text.find_first_not_of(" \t\r\n");
    if (first == std::string::npos) return {};
    const std::size_t last = text.find_last_not_of(" \t\r\n");
    return text.substr(first, last - first + 1);
}

// tinyobjloader's warnings, one per line, without blanks.
std::vector<std::string> warningLines(const std::string& text) {
    std::vector<std::string> lines;
    std::size_t start = 0;
    while (start <= text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        std::string line = trimmed(text.substr(start, end - start));
        if (!line.empty() && line != ".") lines.push_back(std::move(line));
        start = end + 1;
    }
    return lines;
}

std::string joined(const std::vector<std::string>& lines) {
    std::string out;
    for (const std::string& l : lines) out += (out.empty() ? "" : "; ") + l;
    return out;
}

// A texture named in a .mtl, as a path usable from the working directory.
std::string resolveTexture(const std::string& texture, const fs::path& baseDir) {
    if (texture.empty()) return {};
    const fs::path t(texture);
    if (t.is_absolute() || baseDir.empty()) return t.lexically_normal().generic_string();
    return (baseDir / t).lexically_normal().generic_string();
}

// One object to be: a run of faces of one shape with one material.
struct PendingObject {
    Mesh mesh;
    int material = -1;  // tinyobjloader material index, -1 for none
    const std::string* name = nullptr;
};

class ObjConverter {
public:
    ObjConverter(const tinyobj::attrib_t& attrib, const std::string& path,
                 const std::string& warnings)
        : attrib_(attrib), path_(path), warnings_(warnings) {}

    // Splits every shape into runs of faces with the same material.
    std::vector<PendingObject> convert(const std::vector<tinyobj::shape_t>& shapes) {
        std::vector<PendingObject> objects;
        for (const tinyobj::shape_t& shape : shapes) {
            const tinyobj::mesh_t& m = shape.mesh;
            std::size_t corner = 0;
            for (std::size_t face = 0; face < m.num_face_vertices.size(); ++face) {
                const int material = face < m.material_ids.size() ? m.material_ids[face] : -1;
                if (objects.empty() || face == 0 || objects.back().material != material) {
                    objects.push_back({.mesh = {}, .material = material, .name = &shape.name});
                    remap_.clear();
                }
                const std::size_t n = m.num_face_vertices[face];
                if (corner + n > m.indices.size()) malformed("face list is truncated");
                for (std::size_t k = 1; k + 1 < n; ++k) {  // fan; tinyobjloader gives n == 3
                    for (std::size_t c : {corner, corner + k, corner + k + 1})
                        objects.back().mesh.indices.push_back(
                            vertex(objects.back().mesh, m.indices[c]));
                }
                corner += n;
            }
        }
        std::erase_if(objects, [](const PendingObject& o) { return o.mesh.empty(); });
        return objects;
    }

private:
    [[noreturn]] void malformed(const std::string& what) const {
        std::string message = "malformed OBJ: " + what;
        if (!warnings_.empty()) message += " (tinyobjloader: " + warnings_ + ")";
        throw Error(message, {.file = path_});
    }

    // The object-local vertex for one face corner, created on first use.
    std::uint32_t vertex(Mesh& mesh, const tinyobj::index_t& index) {
        const std::size_t vertexCount = attrib_.vertices.size() / 3;
        const std::size_t uvCount = attrib_.texcoords.size() / 2;
        if (index.vertex_index < 0 || std::size_t(index.vertex_index) >= vertexCount)
            malformed("vertex index " + std::to_string(index.vertex_index + 1) +
                      " out of range (1 to " + std::to_string(vertexCount) + ")");
        if (index.texcoord_index >= 0 && std::size_t(index.texcoord_index) >= uvCount)
            malformed("texture coordinate index " + std::to_string(index.texcoord_index + 1) +
                      " out of range (1 to " + std::to_string(uvCount) + ")");
        const std::uint64_t key = (std::uint64_t(std::uint32_t(index.vertex_index)) << 32) |
                                  std::uint32_t(index.texcoord_index + 1);
        const auto [it, added] = remap_.try_emplace(key, std::uint32_t(mesh.positions.size()));
        if (!added) return it->second;

        const float* p = &attrib_.vertices[3 * std::size_t(index.vertex_index)];
        if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
            malformed("vertex " + std::to_string(index.vertex_index + 1) + " is not finite");
        mesh.positions.push_back({p[0], p[1], p[2]});
        vec2 uv(0.0f);
        const bool hasUV = index.texcoord_index >= 0;
        if (hasUV) {
            const float* t = &attrib_.texcoords[2 * std::size_t(index.texcoord_index)];
            uv = {t[0], t[1]};
        }
        // A mesh has UVs for all vertices or none: start them at the first corner with one.
        if (hasUV && mesh.uvs.empty()) mesh.uvs.assign(mesh.positions.size() - 1, vec2(0.0f));
        if (!mesh.uvs.empty()) mesh.uvs.push_back(uv);
        return it->second;
    }

    const tinyobj::attrib_t& attrib_;
    const std::string& path_;
    const std::string& warnings_;
    std::unordered_map<std::uint64_t, std::uint32_t> remap_;
};

// The label record of each object (null: none), read from the file's plantarch label
// comments (io/obj_labels.h) unless options.labels is off. Checks that the Context's data
// of those labels have the types the labels need, so nothing is added before an error.
std::vector<const io::ObjLabelRecord*> labelsOf(
    const Context& context, const std::string& path, const ObjReadOptions& options,
    const std::vector<PendingObject>& objects,
    std::unordered_map<std::string, io::ObjLabelRecord>& records) {
    std::vector<const io::ObjLabelRecord*> labels(objects.size(), nullptr);
    if (!options.labels) return labels;
    records = io::readObjLabels(path);
    if (records.empty()) return labels;
    for (const io::ObjLabelData& d : io::kObjLabelData) {
        const auto type = context.objectDataType(d.label);
        if (type && *type != d.type)
            throw Error(std::string("object data has type ") + dataTypeName(*type) +
                            ", readOBJ stores labels of this name as " + dataTypeName(d.type),
                        {.file = path, .parameter = d.label});
    }
    for (std::size_t i = 0; i < objects.size(); ++i) {
        const auto it = records.find(*objects[i].name);
        if (it != records.end()) labels[i] = &it->second;
    }
    return labels;
}

// Whether the objects can have the IDs their labels record: every object has one, they
// increase in file order (so each names one object), all are free in `context` (at or above
// every ID it has issued) and leave at most `maxUnused` unused IDs below them.
bool recordedIDsFree(const Context& context, const std::vector<const io::ObjLabelRecord*>& labels,
                     ObjectID maxUnused) {
    ObjectID next = context.objectIDLimit();
    std::uint64_t unused = 0;
    for (const io::ObjLabelRecord* r : labels) {
        if (!r || !r->object || *r->object < next) return false;
        unused += *r->object - next;
        if (unused > maxUnused) return false;
        next = *r->object + 1;
    }
    return !labels.empty();
}

}  // namespace

// Every vertex line ("v x y z") holds finite numbers: the OBJ parser reads a word such as
// "nan" as 0, so the text itself is checked, naming the line and the word.
void checkVertexNumbers(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        if (line.size() < 2 || line[0] != 'v' || (line[1] != ' ' && line[1] != '\t')) continue;
        std::size_t at = 1;
        for (int k = 0; k < 3; ++k) {
            at = line.find_first_not_of(" \t\r", at);
            if (at == std::string::npos) break;  // too few numbers: the parser's own error
            const std::size_t end = std::min(line.find_first_of(" \t\r", at), line.size());
            const std::string word = line.substr(at, end - at);
            float v = 0.0f;
            const auto [next, ec] = std::from_chars(word.data(), word.data() + word.size(), v);
            if (ec != std::errc() || next != word.data() + word.size() || !std::isfinite(v))
                throw Error("vertex coordinate is not a finite number",
                            {.file = path,
                             .line = number,
                             .parameter = "v",
                             .value = word,
                             .validRange = "finite numbers"});
            at = end;
        }
    }
}

std::vector<ObjectID> readOBJ(Context& context, const std::string& path,
                              const ObjReadOptions& options) {
    io::rejectDirectory(path, "OBJ file");
    if (options.storeShapeNames) {
        const auto type = context.objectDataType("name");
        if (type && *type != DataType::String)
            throw Error(std::string("object data has type ") + dataTypeName(*type) +
                            ", readOBJ stores shape names as string",
                        {.file = path, .parameter = "name"});
    }
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw Error("is a directory, not an OBJ file", {.file = path});
    // Progress as fractions of the whole read: the parse is about half of it, reported as
    // the share of the file's bytes read.
    ProgressSteps steps(options.progress, "reading OBJ", 1.0);
    std::FILE* file = std::fopen(path.c_str(), "rb");
    if (!file)
        throw Error(std::string("cannot open OBJ file: ") + std::strerror(errno), {.file = path});
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> closer(file, &std::fclose);
    const std::uintmax_t size = std::max<std::uintmax_t>(fs::file_size(path, ec), 1);
    // Blocks of 1 MB, or of the whole file when it is smaller.
    const std::size_t blockSize =
        std::size_t(std::clamp<std::uintmax_t>(size + 1, 4096, std::uintmax_t(1) << 20));
    ProgressReadBuffer buffer(file, blockSize, [&](std::uintmax_t read) {
        steps.at(0.5 * double(std::min(read, size)) / double(size));
    });
    std::istream in(&buffer);
    std::string mtlDir = options.mtlSearchPath.empty() ? fs::path(path).parent_path().string()
                                                       : options.mtlSearchPath;
    if (!mtlDir.empty() && mtlDir.back() != '/') mtlDir += '/';
    tinyobj::MaterialFileReader materialReader(mtlDir);
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> tinyMaterials;
    std::string warning, error;
    const bool ok = tinyobj::LoadObj(&attrib, &shapes, &tinyMaterials, &warning, &error, &in,
                                     &materialReader, /*triangulate=*/true,
                                     /*default_vcols_fallback=*/false);
    if (buffer.failed()) throw Error("cannot read OBJ file", {.file = path});
    const std::vector<std::string> warnings = warningLines(warning);
    if (!ok) {
        const std::string why = trimmed(error);
        throw Error("cannot read OBJ: " + (why.empty() ? std::string("unknown error") : why),
                    {.file = path});
    }
    steps.at(0.5);
    checkVertexNumbers(path);
    steps.at(0.7);
    if (options.onWarning)
        for (const std::string& w : warnings) options.onWarning(w);

    const std::string warningText = joined(warnings);
    ObjConverter converter(attrib, path, warningText);
    std::vector<PendingObject> objects = converter.convert(shapes);
    steps.at(0.8);
    if (objects.empty()) {
        std::string message = "OBJ file has no faces";
        if (!warningText.empty()) message += " (tinyobjloader: " + warningText + ")";
        throw Error(message, {.file = path});
    }

    std::unordered_map<std::string, io::ObjLabelRecord> records;
    const std::vector<const io::ObjLabelRecord*> labels =
        labelsOf(context, path, options, objects, records);
    const bool sameIDs = recordedIDsFree(context, labels, options.maxSkippedObjectIDs);

    // Materials as the Context will hold them; added only now that the file is known good.
    const fs::path baseDir = options.mtlSearchPath.empty() ? fs::path(path).parent_path()
                                                           : fs::path(options.mtlSearchPath);
    std::vector<MaterialID> materialIDs(tinyMaterials.size());
    for (std::size_t i = 0; i < tinyMaterials.size(); ++i) {
        const tinyobj::material_t& m = tinyMaterials[i];
        materialIDs[i] = context.addMaterial({.color = {m.diffuse[0], m.diffuse[1], m.diffuse[2]},
                                              .texture = resolveTexture(m.diffuse_texname, baseDir),
                                              .name = m.name});
    }
    const MaterialID plain = context.addMaterial(Material{});

    std::vector<ObjectID> ids;
    ids.reserve(objects.size());
    for (std::size_t i = 0; i < objects.size(); ++i) {
        const PendingObject& o = objects[i];
        const bool known = o.material >= 0 && std::size_t(o.material) < materialIDs.size();
        if (sameIDs) context.skipObjectIDs(*labels[i]->object);
        const ObjectID id = context.addObject(o.mesh, known ? materialIDs[o.material] : plain);
        if (options.storeShapeNames && !o.name->empty()) context.setObjectData(id, "name", *o.name);
        if (labels[i]) io::applyObjLabels(context, id, *labels[i]);
        ids.push_back(id);
        steps.at(0.8 + 0.2 * double(ids.size()) / double(objects.size()));
    }
    steps.finish();
    return ids;
}

std::vector<ObjectID> readObstacleOBJ(Context& context, const std::string& path) {
    const std::vector<ObjectID> ids = readOBJ(context, path, {.labels = false});
    const DataColumn organ = context.dataColumn("organ", DataType::String);
    for (ObjectID id : ids) context.setObjectData(id, organ, std::string("obstacle"));
    return ids;
}

}  // namespace plantarch
