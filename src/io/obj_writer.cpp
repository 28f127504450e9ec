// Wavefront OBJ + MTL writer. Numbers are formatted straight into the AtomicFile's buffer
// (one reserve() per line), which is what makes several hundred MB/s possible.

#include <cstring>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <system_error>
#include <vector>

#include "core/atomic_file.h"
#include "io/export_common.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"

namespace plantarch {

namespace fs = std::filesystem;

namespace {

// Room for one OBJ line: a face with three v/vt/vn triples of 20-digit numbers, or a
// vertex with three floats.
constexpr std::size_t kLineBytes = 256;
// A split export writes many small files; a smaller buffer each is plenty.
constexpr std::size_t kSplitBufferBytes = std::size_t(256) << 10;
constexpr const char* kSplitMaterialFile = "materials.mtl";

// OBJ and MTL names end at whitespace; keep them to a portable set of characters.
std::string sanitizeName(std::string_view text) {
    std::string out(text);
    for (char& c : out) {
        const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                        (c >= '0' && c <= '9') || c == '_' || c == '-' || c == '.';
        if (!ok) c = '_';
    }
    return out;
}

std::string objectName(const Context& context, ObjectID id) {
    std::string name = "obj";  // (not "obj" + ...: GCC 12 warns falsely, -Wrestrict)
    name += std::to_string(id);
    const std::string organ = io::organOf(context, id);
    if (!organ.empty()) name.append("_").append(sanitizeName(organ));
    return name;
}

// Unique material names for the materials used by `ids` (empty string: unused).
std::vector<std::string> materialNames(const Context& context, const std::vector<ObjectID>& ids) {
    std::vector<char> used(context.materialCount(), 0);
    for (ObjectID id : ids) used[context.objectMaterial(id)] = 1;
    std::vector<std::string> names(used.size());
    std::set<std::string, std::less<>> taken;
    for (MaterialID m = 0; m < used.size(); ++m) {
        if (!used[m]) continue;
        const Material& mat = context.material(m);
        std::string name = mat.name.empty() ? std::string("material").append(std::to_string(m))
                                            : sanitizeName(mat.name);
        if (taken.count(name)) {
            const std::string base = name + "_" + std::to_string(m);
            name = base;
            for (int k = 2; taken.count(name); ++k) name = base + "_" + std::to_string(k);
        }
        taken.insert(name);
        names[m] = std::move(name);
    }
    return names;
}

// A texture path as the .mtl in `mtlDir` should name it: absolute paths unchanged,
// relative ones (meant from the working directory) made relative to mtlDir.
std::string textureReference(const std::string& texture, const fs::path& mtlDir) {
    const fs::path t(texture);
    if (t.is_absolute()) return texture;
    std::error_code ec;
    const fs::path base = fs::absolute(mtlDir.empty() ? fs::path(".") : mtlDir, ec);
    const fs::path target = fs::absolute(t, ec);
    if (ec) return texture;
    const fs::path rel = target.lexically_normal().lexically_relative(base.lexically_normal());
    return rel.empty() ? target.lexically_normal().generic_string() : rel.generic_string();
}

void writeMTL(io::AtomicFile& out, const Context& context, const std::vector<std::string>& names,
              const fs::path& mtlDir) {
    out.write("# plantarch material library\n");
    for (MaterialID m = 0; m < names.size(); ++m) {
        if (names[m].empty()) continue;
        const Material& mat = context.material(m);
        out.write("\nnewmtl " + names[m] + "\nKa 0 0 0\nKd ");
        char* p = out.reserve(kLineBytes);
        p = io::writeFloat(p, mat.color.r);
        *p++ = ' ';
        p = io::writeFloat(p, mat.color.g);
        *p++ = ' ';
        p = io::writeFloat(p, mat.color.b);
        p = io::writeText(p, "\nKs 0 0 0\nd 1\nillum 1\n");
        out.advance(p);
        if (!mat.texture.empty())
            out.write("map_Kd " + textureReference(mat.texture, mtlDir) + "\n");
    }
}

// Writes the objects' geometry, numbering vertices across the whole file.
class ObjBodyWriter {
public:
    ObjBodyWriter(const Context& context, const ObjOptions& options)
        : context_(context), options_(options) {}

    void restartNumbering() { vertexBase_ = uvBase_ = 0; }

    void writeObject(io::AtomicFile& out, ObjectID id, const std::string* materialName) {
        const ObjectView o = context_.object(id);
        const std::string name = objectName(context_, id);
        out.write("o " + name + "\ng " + name + "\n");
        if (materialName) out.write("usemtl " + *materialName + "\n");

        for (const vec3& v : o.positions) {
            char* p = out.reserve(kLineBytes);
            *p++ = 'v';
            p = vec3Text(p, v);
            out.advance(p);
        }
        const bool uvs = options_.uvs && !o.uvs.empty();
        if (uvs)
            for (const vec2& t : o.uvs) {
                char* p = out.reserve(kLineBytes);
                *p++ = 'v';
                *p++ = 't';
                *p++ = ' ';
                p = io::writeFloat(p, t.x);
                *p++ = ' ';
                p = io::writeFloat(p, t.y);
                *p++ = '\n';
                out.advance(p);
            }
        if (options_.normals) {
            io::smoothNormals(o, normals_);
            for (const vec3& n : normals_) {
                char* p = out.reserve(kLineBytes);
                *p++ = 'v';
                *p++ = 'n';
                *p++ = ' ';
                p = io::writeFixed6(p, n.x);
                *p++ = ' ';
                p = io::writeFixed6(p, n.y);
                *p++ = ' ';
                p = io::writeFixed6(p, n.z);
                *p++ = '\n';
                out.advance(p);
            }
        }
        writeFaces(out, o, uvs);
        vertexBase_ += o.positions.size();
        if (uvs) uvBase_ += o.uvs.size();
    }

private:
    // " x y z\n"
    static char* vec3Text(char* p, const vec3& v) {
        *p++ = ' ';
        p = io::writeFloat(p, v.x);
        *p++ = ' ';
        p = io::writeFloat(p, v.y);
        *p++ = ' ';
        p = io::writeFloat(p, v.z);
        *p++ = '\n';
        return p;
    }

    void writeFaces(io::AtomicFile& out, const ObjectView& o, bool uvs) {
        const std::uint64_t vBase = vertexBase_ + 1, tBase = uvBase_ + 1;
        const bool normals = options_.normals;
        const bool sameUVIndex = uvs && vBase == tBase;  // then "a/a/a": format a once
        const auto& idx = o.indices;
        for (std::size_t t = 0; t + 2 < idx.size(); t += 3) {
            char* p = out.reserve(kLineBytes);
            *p++ = 'f';
            for (int k = 0; k < 3; ++k) {
                // Format the index once; copy a fixed 24 bytes (one or two stores, no call)
                // and keep `len` of them. The line's reserve() leaves room for the excess.
                char number[24];
                const std::uint64_t v = vBase + idx[t + k];
                const std::size_t len = static_cast<std::size_t>(io::writeUInt(number, v) - number);
                *p++ = ' ';
                std::memcpy(p, number, sizeof(number));
                p += len;
                if (uvs) {
                    *p++ = '/';
                    if (sameUVIndex) {
                        std::memcpy(p, number, sizeof(number));
                        p += len;
                    } else {
                        p = io::writeUInt(p, tBase + idx[t + k]);
                    }
                }
                if (normals) {
                    *p++ = '/';
                    if (!uvs) *p++ = '/';
                    std::memcpy(p, number, sizeof(number));
                    p += len;
                }
            }
            *p++ = '\n';
            out.advance(p);
        }
    }

    const Context& context_;
    const ObjOptions& options_;
    std::uint64_t vertexBase_ = 0;
    std::uint64_t uvBase_ = 0;
    std::vector<vec3> normals_;
};

void writeHeader(io::AtomicFile& out, const Context& context, const std::vector<ObjectID>& ids,
                 const std::string& mtlFile) {
    std::size_t triangles = 0;
    for (ObjectID id : ids) triangles += context.objectPrimitives(id).count;
    out.write("# plantarch OBJ: " + std::to_string(ids.size()) + " objects, " +
              std::to_string(triangles) + " triangles\n");
    if (!mtlFile.empty()) out.write("mtllib " + mtlFile + "\n");
}

void writeSplit(const Context& context, const std::string& dir, const ObjOptions& options,
                const std::vector<ObjectID>& ids) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw Error("cannot create directory: " + ec.message(), {.file = dir});
    const fs::path root(dir);
    std::vector<std::string> names;
    std::vector<io::AtomicFile> files;  // all finished first, then renamed together
    if (options.materials) {
        names = materialNames(context, ids);
        files.emplace_back((root / kSplitMaterialFile).string(), kSplitBufferBytes);
        writeMTL(files.back(), context, names, root);
        files.back().finish();
    }
    ObjBodyWriter body(context, options);
    const std::string mtlFile = options.materials ? kSplitMaterialFile : "";
    for (ObjectID id : ids) {
        files.emplace_back((root / (objectName(context, id) + ".obj")).string(), kSplitBufferBytes);
        io::AtomicFile& out = files.back();
        writeHeader(out, context, {id}, mtlFile);
        body.restartNumbering();
        body.writeObject(out, id, options.materials ? &names[context.objectMaterial(id)] : nullptr);
        out.finish();
    }
    for (io::AtomicFile& f : files) f.commit();
}

}  // namespace

void writeOBJ(const Context& context, const std::string& path, const ObjOptions& options) {
    io::requireDataType(context, "organ", DataType::String, path);
    const std::vector<ObjectID> ids = io::exportedObjects(context, options.includeHidden);
    if (options.splitPerObject) {
        writeSplit(context, path, options, ids);
        return;
    }

    io::AtomicFile obj(path);  // first, so an unwritable place is reported for the OBJ
    std::optional<io::AtomicFile> mtl;
    std::vector<std::string> names;
    fs::path mtlPath;
    if (options.materials) {
        mtlPath = fs::path(path).replace_extension(".mtl");
        if (mtlPath == fs::path(path)) mtlPath += ".mtl";
        names = materialNames(context, ids);
        mtl.emplace(mtlPath.string(), kSplitBufferBytes);
        writeMTL(*mtl, context, names, mtlPath.parent_path());
        mtl->finish();
    }
    writeHeader(obj, context, ids, options.materials ? mtlPath.filename().string() : "");
    ObjBodyWriter body(context, options);
    for (ObjectID id : ids)
        body.writeObject(obj, id, options.materials ? &names[context.objectMaterial(id)] : nullptr);
    obj.finish();
    if (mtl) mtl->commit();
    obj.commit();
}

}  // namespace plantarch
