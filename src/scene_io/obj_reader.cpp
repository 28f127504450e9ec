// Wavefront OBJ reader on tinyobjloader. Everything is parsed and checked before the Context
// is touched, so a bad file leaves the Context unchanged.

#include <tiny_obj_loader.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <functional>
#include <istream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/input_file.h"
#include "core/progress_steps.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/OutputFormats.h"
#include "scene_io/obj_labels.h"

namespace plantarch {

namespace fs = std::filesystem;

namespace {

// Reads a file in blocks for the OBJ parser, telling how many bytes it has read so far. The
// first block is checked to be text (not UTF-16, not binary), and every block to hold no NUL
// byte: the parser would stop at one silently.
class ProgressReadBuffer final : public std::streambuf {
public:
    // Blocks of `blockSize` bytes, not cleared before they are read into.
    ProgressReadBuffer(io::InputFile& file, std::size_t blockSize,
                       std::function<void(std::uintmax_t)> onRead)
        : file_(file),
          onRead_(std::move(onRead)),
          block_(std::make_unique_for_overwrite<char[]>(blockSize)),
          blockSize_(blockSize) {}

    // Ends the stream at the next block: the parser sees the end of the file.
    void stop() { stopped_ = true; }
    // An error while reading ends the stream (the parser sees its end); thrown here after.
    void rethrow() const {
        if (error_) std::rethrow_exception(error_);
    }

protected:
    int_type underflow() override {
        if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
        if (stopped_) return traits_type::eof();
        try {
            return next();
        } catch (...) {
            error_ = std::current_exception();
            return traits_type::eof();
        }
    }

private:
    int_type next() {
        const std::size_t n = file_.read(block_.get(), blockSize_);
        if (n == 0) return traits_type::eof();
        const std::string_view data(block_.get(), n);
        if (read_ == 0) io::checkText(data.substr(0, 4096), file_.path(), io::kOBJFile);
        if (const std::size_t nul = data.find('\0'); nul != std::string_view::npos)
            throw Error("binary data (a NUL byte), not an OBJ file",
                        {.file = file_.path(), .line = lineAt(read_ + nul)});
        read_ += n;
        onRead_(read_);
        setg(block_.get(), block_.get(), block_.get() + n);
        return traits_type::to_int_type(*gptr());
    }

    // The line of byte `offset` of the file, read again (only to name a bad byte's line).
    int lineAt(std::uintmax_t offset) const {
        io::InputFile again(file_.path(), io::kOBJFile);
        int line = 1;
        std::uintmax_t at = 0;
        io::forEachLine(again, [&](std::string_view l, int number) {
            if (at <= offset) line = number;
            at += l.size() + 1;
        });
        return line;
    }

    io::InputFile& file_;
    std::function<void(std::uintmax_t)> onRead_;
    std::unique_ptr<char[]> block_;
    std::size_t blockSize_;
    std::uintmax_t read_ = 0;
    std::exception_ptr error_;
    bool stopped_ = false;
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
        // The material reader says which file was not found and what follows.
        const bool repeated = line.rfind("Failed to load material file(s)", 0) == 0;
        if (!line.empty() && line != "." && !repeated) lines.push_back(std::move(line));
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

std::optional<Error> badIndex(const std::string& path);

// One object to be: a run of faces of one shape with one material.
struct PendingObject {
    Mesh mesh;
    int material = -1;  // tinyobjloader material index, -1 for none
    const std::string* name = nullptr;
};

class ObjConverter {
public:
    ObjConverter(const tinyobj::attrib_t& attrib, const std::string& path)
        : attrib_(attrib), path_(path) {}

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
    // A bad index is named at its line; anything else as found here.
    [[noreturn]] void malformed(const std::string& what) const {
        if (std::optional<Error> bad = badIndex(path_)) throw *bad;
        throw Error("malformed OBJ: " + what, {.file = path_});
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
    io::InputFile file(path, io::kOBJFile);
    io::forEachLine(file, [&](std::string_view line, int number) {
        if (line.size() < 2 || line[0] != 'v' || (line[1] != ' ' && line[1] != '\t')) return;
        std::size_t at = 1;
        for (int k = 0; k < 3; ++k) {
            at = line.find_first_not_of(" \t\r", at);
            if (at == std::string_view::npos) break;  // too few numbers: the parser's own error
            const std::size_t end = std::min(line.find_first_of(" \t\r", at), line.size());
            const std::string_view word = line.substr(at, end - at);
            float v = 0.0f;
            const auto [next, ec] = std::from_chars(word.data(), word.data() + word.size(), v);
            if (ec != std::errc() || next != word.data() + word.size() || !std::isfinite(v))
                throw Error("vertex coordinate is not a finite number",
                            {.file = path,
                             .line = number,
                             .parameter = "v",
                             .value = std::string(word),
                             .validRange = "finite numbers"});
            at = end;
        }
    });
}

namespace {

// The first index of a face (f), line (l) or point (p) line that tinyobjloader refuses or
// that names a vertex or texture coordinate the file does not have, as an Error naming the
// line; none when every index is good. Read only after the parser or the conversion found
// a bad index, to say where it is.
std::optional<Error> badIndex(const std::string& path) {
    struct Counts {
        long v = 0, vt = 0, vn = 0;
    };
    auto countLine = [](std::string_view l, Counts& c) {
        if (l.size() < 2 || l[0] != 'v') return;
        if (l[1] == ' ' || l[1] == '\t') ++c.v;
        if (l.size() >= 3 && (l[2] == ' ' || l[2] == '\t')) {
            if (l[1] == 't') ++c.vt;
            if (l[1] == 'n') ++c.vn;
        }
    };
    Counts total;
    {
        io::InputFile file(path, io::kOBJFile);
        io::forEachLine(file, [&](std::string_view l, int) {
            countLine(l.substr(std::min(l.find_first_not_of(" \t"), l.size())), total);
        });
    }
    static const char* const kWhat[3] = {"vertex", "texture coordinate", "normal"};
    std::optional<Error> found;
    Counts now;
    io::InputFile file(path, io::kOBJFile);
    io::forEachLine(file, [&](std::string_view l, int number) {
        if (found) return;
        l.remove_prefix(std::min(l.find_first_not_of(" \t"), l.size()));
        countLine(l, now);
        if (l.size() < 2 || (l[0] != 'f' && l[0] != 'l' && l[0] != 'p') ||
            (l[1] != ' ' && l[1] != '\t'))
            return;
        const std::string keyword(1, l[0]);
        std::size_t at = 1;
        while (!found && (at = l.find_first_not_of(" \t\r", at)) != std::string_view::npos) {
            const std::size_t end = std::min(l.find_first_of(" \t\r", at), l.size());
            const std::string_view word = l.substr(at, end - at);
            at = end;
            std::size_t part = 0, start = 0;
            for (; part < 3 && start <= word.size(); ++part) {
                const std::size_t slash = std::min(word.find('/', start), word.size());
                const std::string_view text = word.substr(start, slash - start);
                start = slash + 1;
                if (text.empty() && part > 0) continue;  // "1//2": no texture coordinate
                const long count = part == 0 ? total.v : part == 1 ? total.vt : total.vn;
                const long before = part == 0 ? now.v : part == 1 ? now.vt : now.vn;
                long index = 0;
                const auto [next, ec] =
                    std::from_chars(text.data(), text.data() + text.size(), index);
                std::string message, valid;
                if (ec != std::errc() || next != text.data() + text.size())
                    message = std::string("not a ") + kWhat[part] + " index";
                else if (index == 0)
                    message = std::string(kWhat[part]) + " index 0: OBJ indices start at 1";
                else if (part < 2 && index > count)
                    message = std::string(kWhat[part]) + " index out of range";
                else if (index < 0 && -index > before)
                    message = std::string(kWhat[part]) + " index out of range (counted back from " +
                              "this line)";
                if (message.empty()) continue;
                if (count == 0)
                    valid = std::string("none: the file has no ") + kWhat[part] + "s above";
                else
                    valid = "1 to " + std::to_string(count) +
                            (before > 0 ? ", or -" + std::to_string(before) + " to -1" : "");
                found = Error(message, {.file = path,
                                        .line = number,
                                        .parameter = keyword,
                                        .value = std::string(word),
                                        .validRange = valid});
                break;
            }
        }
    });
    return found;
}

// The .mtl files an OBJ names (mtllib), resolved from `dir` and read as input files. One that
// does not exist is a warning (its objects get the default material); one that is no regular
// file or is too large is kept as the error, and reading stops.
class MaterialFiles final : public tinyobj::MaterialReader {
public:
    MaterialFiles(fs::path dir, std::function<void()> stop)
        : dir_(std::move(dir)), stop_(std::move(stop)) {}

    bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* matMap, std::string* warn,
                    std::string* err) override {
        if (error_) return false;
        const fs::path given(name);
        const std::string path =
            (given.is_absolute() ? given : dir_ / given).lexically_normal().string();
        std::error_code ec;
        if (!fs::exists(fs::symlink_status(path, ec))) {
            if (warn) *warn += "material file " + path + " not found: default material used\n";
            return false;
        }
        try {
            const std::string text = io::readWholeFile(path, io::kMTLFile);
            std::istringstream in(text);
            tinyobj::LoadMtl(matMap, materials, &in, warn, err);
            return true;
        } catch (const Error& e) {
            error_ = e;
            name_ = name;
            stop_();
            return false;
        }
    }

    // The error of an mtllib file, placed at the OBJ's mtllib line naming it.
    void rethrow(const std::string& objPath) const {
        if (!error_) return;
        int line = 0;
        io::InputFile file(objPath, io::kOBJFile);
        io::forEachLine(file, [&](std::string_view l, int number) {
            l.remove_prefix(std::min(l.find_first_not_of(" \t"), l.size()));
            if (line == 0 && l.substr(0, 6) == "mtllib" && l.find(name_) != std::string_view::npos)
                line = number;
        });
        throw Error(error_->message(), {.file = objPath,
                                        .line = line,
                                        .parameter = "mtllib",
                                        .value = error_->file(),
                                        .validRange = error_->validRange()});
    }

private:
    fs::path dir_;
    std::function<void()> stop_;
    std::optional<Error> error_;
    std::string name_;
};

}  // namespace

std::vector<ObjectID> readOBJ(Context& context, const std::string& path,
                              const ObjReadOptions& options) {
    if (options.storeShapeNames) {
        const auto type = context.objectDataType("name");
        if (type && *type != DataType::String)
            throw Error(std::string("object data has type ") + dataTypeName(*type) +
                            ", readOBJ stores shape names as string",
                        {.file = path, .parameter = "name"});
    }
    // Progress as fractions of the whole read: the parse is about half of it, reported as
    // the share of the file's bytes read.
    ProgressSteps steps(options.progress, "reading OBJ", 1.0);
    io::InputFile file(path, io::kOBJFile);
    const std::uintmax_t size = std::max<std::uintmax_t>(file.size(), 1);
    // Blocks of 1 MB, or of the whole file when it is smaller.
    const std::size_t blockSize =
        std::size_t(std::clamp<std::uintmax_t>(size + 1, 4096, std::uintmax_t(1) << 20));
    ProgressReadBuffer buffer(file, blockSize, [&](std::uintmax_t read) {
        steps.at(0.5 * double(std::min(read, size)) / double(size));
    });
    std::istream in(&buffer);
    const fs::path baseDir = options.mtlSearchPath.empty() ? fs::path(path).parent_path()
                                                           : fs::path(options.mtlSearchPath);
    MaterialFiles materialReader(baseDir, [&] { buffer.stop(); });
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> tinyMaterials;
    std::string warning, error;
    const bool ok = tinyobj::LoadObj(&attrib, &shapes, &tinyMaterials, &warning, &error, &in,
                                     &materialReader, /*triangulate=*/true,
                                     /*default_vcols_fallback=*/false);
    buffer.rethrow();
    materialReader.rethrow(path);
    if (!ok) {
        if (std::optional<Error> bad = badIndex(path)) throw *bad;
        const std::string why = trimmed(error);
        throw Error("cannot read OBJ: " + (why.empty() ? std::string("unknown error") : why),
                    {.file = path});
    }
    const std::vector<std::string> warnings = warningLines(warning);
    steps.at(0.5);
    checkVertexNumbers(path);
    steps.at(0.7);

    const std::string warningText = joined(warnings);
    ObjConverter converter(attrib, path);
    std::vector<PendingObject> objects = converter.convert(shapes);
    steps.at(0.8);
    if (objects.empty()) {
        std::string message = "OBJ file has no faces";
        if (!warningText.empty()) message += " (tinyobjloader: " + warningText + ")";
        throw Error(message, {.file = path});
    }
    if (options.onWarning)
        for (const std::string& w : warnings) options.onWarning(w);

    std::unordered_map<std::string, io::ObjLabelRecord> records;
    const std::vector<const io::ObjLabelRecord*> labels =
        labelsOf(context, path, options, objects, records);
    const bool sameIDs = recordedIDsFree(context, labels, options.maxSkippedObjectIDs);

    // Materials as the Context will hold them; added only now that the file is known good.
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

std::vector<ObjectID> readObstacleMesh(Context& context, const std::string& path) {
    const std::string ext = lowerExtension(path);
    if (ext != ".obj" && ext != ".ply")
        throw Error("an obstacle is read from an OBJ or PLY mesh",
                    {.file = path,
                     .value = ext.empty() ? "no extension" : ext,
                     .validRange = ".obj, .ply"});
    const std::vector<ObjectID> ids = ext == ".obj" ? readOBJ(context, path, {.labels = false})
                                                    : readPLY(context, path, {.labels = false});
    const DataColumn organ = context.dataColumn("organ", DataType::String);
    for (ObjectID id : ids) context.setObjectData(id, organ, std::string("obstacle"));
    return ids;
}

}  // namespace plantarch
