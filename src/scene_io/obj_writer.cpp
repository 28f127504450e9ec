// Wavefront OBJ + MTL writer. The body is cut into chunks of consecutive objects (by line
// count, so the cut never depends on the thread count); each thread formats whole chunks
// into its own buffer (one reserve() per line, numbers by std::to_chars) and writes them to
// the file in order, so the bytes are the same on one thread or many.

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstring>
#include <exception>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include "core/atomic_file.h"
#include "core/progress_steps.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/OutputFormats.h"
#include "scene_io/export_common.h"
#include "scene_io/obj_labels.h"
#include "scene_io/obj_materials.h"

namespace plantarch {

namespace fs = std::filesystem;

namespace {

// Lines of OBJ text formatted together by one thread (a few MB).
constexpr std::uint64_t kChunkLines = std::uint64_t(1) << 16;
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

// obj<ID>[_plant<P>][_<organ>]: unique per object, and it tells plants and organs apart in
// tools that show only names. `plantIDs`: the Context's "plantID" data are ints.
std::string objectName(const Context& context, ObjectID id, bool plantIDs) {
    std::string name = "obj";  // (not "obj" + ...: GCC 12 warns falsely, -Wrestrict)
    name += std::to_string(id);
    if (plantIDs)
        if (const auto plant = context.objectDataInt(id, "plantID"))
            name.append("_plant").append(std::to_string(*plant));
    const std::string organ = io::organOf(context, id);
    if (!organ.empty()) name.append("_").append(sanitizeName(organ));
    return name;
}

bool hasPlantIDs(const Context& context) {
    return context.objectDataType("plantID") == DataType::Int;
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
              const fs::path& mtlDir, const io::ObjTextures& textures) {
    out.write("# plantarch material library\n");
    for (MaterialID m = 0; m < names.size(); ++m) {
        if (names[m].empty()) continue;
        const Material& mat = context.material(m);
        out.write("\nnewmtl " + names[m] + "\nKa 0 0 0\nKd ");
        char* p = out.reserve(io::kLineBytes);
        p = io::writeFloat(p, mat.color.r);
        *p++ = ' ';
        p = io::writeFloat(p, mat.color.g);
        *p++ = ' ';
        p = io::writeFloat(p, mat.color.b);
        p = io::writeText(p, "\nKs 0 0 0\nd 1\nillum 1\n");
        out.advance(p);
        if (!mat.texture.empty())
            out.write("map_Kd " + textureReference(mat.texture, mtlDir) + "\n");
        out.write(textures.lines(mat));  // textured materials (obj_materials.cpp)
    }
}

// A growing in-memory text buffer with AtomicFile's reserve/advance/write interface: one
// chunk of the OBJ body is formatted into it by one thread, then written out in order.
class TextChunk {
public:
    char* reserve(std::size_t size) {
        if (capacity_ - used_ < size) grow(size);
        return buffer_.get() + used_;
    }
    void advance(const char* end) { used_ = static_cast<std::size_t>(end - buffer_.get()); }
    void write(std::string_view text) {
        std::memcpy(reserve(text.size()), text.data(), text.size());
        used_ += text.size();
    }
    void clear() { used_ = 0; }
    const char* data() const { return buffer_.get(); }
    std::size_t size() const { return used_; }

private:
    void grow(std::size_t size) {
        const std::size_t capacity =
            std::max(2 * capacity_, used_ + size + (std::size_t(64) << 10));
        auto bigger = std::make_unique_for_overwrite<char[]>(capacity);
        if (used_) std::memcpy(bigger.get(), buffer_.get(), used_);
        buffer_ = std::move(bigger);
        capacity_ = capacity;
    }

    std::unique_ptr<char[]> buffer_;
    std::size_t capacity_ = 0;
    std::size_t used_ = 0;
};

// Writes objects' geometry; `vertexBase` and `uvBase` count the vertices and UVs written
// before the object in the same file.
class ObjBodyWriter {
public:
    ObjBodyWriter(const Context& context, const ObjOptions& options)
        : context_(context), options_(options), plantIDs_(hasPlantIDs(context)), labels_(context) {}

    template <class Out>
    void writeObject(Out& out, ObjectID id, const std::string* materialName,
                     std::uint64_t vertexBase, std::uint64_t uvBase) {
        const ObjectView o = context_.object(id);
        // The object's name, its label comment (io/obj_labels.h) and its material.
        const std::string name = objectName(context_, id, plantIDs_);
        head_.assign("o ").append(name).append("\ng ").append(name).append("\n");
        labels_.append(head_, id, name);
        if (materialName) head_.append("usemtl ").append(*materialName).append("\n");
        out.write(head_);

        for (const vec3& v : o.positions) {
            char* p = out.reserve(io::kLineBytes);
            *p++ = 'v';
            p = vec3Text(p, v);
            out.advance(p);
        }
        const bool uvs = options_.uvs && !o.uvs.empty();
        if (uvs) out.write(uvText(o.uvs));
        if (options_.normals) {
            io::smoothNormals(o, normals_);
            for (const vec3& n : normals_) {
                char* p = out.reserve(io::kLineBytes);
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
        writeFaces(out, o, uvs, vertexBase + 1, uvBase + 1);
    }

    /// The vertices and UVs an object adds to the file's numbering.
    std::pair<std::uint64_t, std::uint64_t> counts(const ObjectView& o) const {
        return {o.positions.size(), options_.uvs ? o.uvs.size() : 0};
    }

private:
    // The "vt" lines of `uvs`. Leaves made from one prototype share their UVs, so the text
    // of the last UVs formatted is kept and reused when the next object's are the same.
    std::string_view uvText(std::span<const vec2> uvs) {
        if (uvs.size() == lastUVs_.size() &&
            std::memcmp(uvs.data(), lastUVs_.data(), uvs.size_bytes()) == 0)
            return {uvText_.data(), uvTextSize_};
        lastUVs_.assign(uvs.begin(), uvs.end());
        const std::size_t lineBytes = 2 * io::kMaxFloatChars + 5;  // "vt x y\n"
        if (uvText_.size() < uvs.size() * lineBytes) uvText_.resize(uvs.size() * lineBytes);
        char* p = uvText_.data();
        for (const vec2& t : uvs) {
            *p++ = 'v';
            *p++ = 't';
            *p++ = ' ';
            p = io::writeFloat(p, t.x);
            *p++ = ' ';
            p = io::writeFloat(p, t.y);
            *p++ = '\n';
        }
        uvTextSize_ = static_cast<std::size_t>(p - uvText_.data());
        return {uvText_.data(), uvTextSize_};
    }

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

    template <class Out>
    void writeFaces(Out& out, const ObjectView& o, bool uvs, std::uint64_t vBase,
                    std::uint64_t tBase) {
        const bool normals = options_.normals;
        const bool sameUVIndex = uvs && vBase == tBase;  // then "a/a/a": format a once
        const auto& idx = o.indices;
        for (std::size_t t = 0; t + 2 < idx.size(); t += 3) {
            char* p = out.reserve(io::kLineBytes);
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
    bool plantIDs_;
    io::ObjLabelWriter labels_;
    std::string head_;
    std::vector<vec3> normals_;
    std::vector<vec2> lastUVs_;
    std::vector<char> uvText_;
    std::size_t uvTextSize_ = 0;
};

// A run of consecutive objects formatted together, with the numbering they start at.
struct Chunk {
    std::size_t first = 0, last = 0;  // into the exported IDs, last exclusive
    std::uint64_t vertexBase = 0, uvBase = 0;
};

// Splits `ids` into chunks of about kChunkLines lines each. Depends only on the geometry, so
// the file's bytes do not depend on the thread count.
std::vector<Chunk> chunksOf(const Context& context, const std::vector<ObjectID>& ids,
                            const ObjBodyWriter& body, bool normals) {
    std::vector<Chunk> chunks;
    Chunk chunk;
    std::uint64_t vertices = 0, uvs = 0, lines = 0;
    for (std::size_t i = 0; i < ids.size(); ++i) {
        const ObjectView o = context.object(ids[i]);
        const auto [v, t] = body.counts(o);
        vertices += v;
        uvs += t;
        lines += v * (normals ? 2 : 1) + t + o.triangleCount() + 4;
        if (lines >= kChunkLines || i + 1 == ids.size()) {
            chunk.last = i + 1;
            chunks.push_back(chunk);
            chunk = {i + 1, i + 1, vertices, uvs};
            lines = 0;
        }
    }
    return chunks;
}

// Waits for `done()`: yields at first, then sleeps in short naps (a writer bound by a slow
// disk leaves the formatting threads idle for long).
template <class Done>
void waitFor(Done&& done) {
    for (int spins = 0; !done(); ++spins) {
        if (spins < 256)
            std::this_thread::yield();
        else
            std::this_thread::sleep_for(std::chrono::microseconds(50));
    }
}

// The objects' geometry into `out`. Chunks are claimed in order by whichever thread is free
// and formatted into a ring of buffers (chunk c into slot c % slots, once chunk c - slots is
// written); the calling thread writes them in chunk order, formatting chunks itself while
// the next one is not ready, and reports progress. So a thread held up (a busy machine)
// never stalls the others, and the bytes do not depend on the thread count.
void writeBody(io::AtomicFile& out, const Context& context, const ObjOptions& options,
               const std::vector<ObjectID>& ids, const std::vector<std::string>& names) {
    const std::vector<Chunk> chunks =
        chunksOf(context, ids, ObjBodyWriter(context, options), options.normals);
    const std::ptrdiff_t n = std::ptrdiff_t(chunks.size());
    const int threads =
        int(std::clamp<std::ptrdiff_t>(omp_get_max_threads(), 1, std::max<std::ptrdiff_t>(n, 1)));
    const std::ptrdiff_t slots = 2 * threads;
    std::vector<TextChunk> buffers(static_cast<std::size_t>(slots));
    std::vector<std::atomic<std::ptrdiff_t>> ready(static_cast<std::size_t>(slots));  // chunk + 1
    for (auto& r : ready) r.store(0, std::memory_order_relaxed);
    std::atomic<std::ptrdiff_t> claimed{0}, written{0};
    std::atomic<bool> failed{false};
    std::exception_ptr failure;
    auto fail = [&] {
#pragma omp critical(plantarch_obj_failure)
        if (!failure) failure = std::current_exception();
        failed.store(true, std::memory_order_release);
    };
    auto slotFree = [&](std::ptrdiff_t c) {
        return written.load(std::memory_order_acquire) > c - slots ||
               failed.load(std::memory_order_acquire);
    };
    // Formats chunk c into its slot (free) and marks it ready.
    auto format = [&](ObjBodyWriter& body, std::ptrdiff_t c) {
        const Chunk& chunk = chunks[std::size_t(c)];
        TextChunk& text = buffers[std::size_t(c % slots)];
        try {
            text.clear();
            std::uint64_t vertexBase = chunk.vertexBase, uvBase = chunk.uvBase;
            for (std::size_t i = chunk.first; i < chunk.last; ++i) {
                const ObjectID id = ids[i];
                body.writeObject(text, id,
                                 options.materials ? &names[context.objectMaterial(id)] : nullptr,
                                 vertexBase, uvBase);
                const auto [v, t] = body.counts(context.object(id));
                vertexBase += v;
                uvBase += t;
            }
        } catch (...) {
            fail();
        }
        ready[std::size_t(c % slots)].store(c + 1, std::memory_order_release);
    };
    ProgressSteps steps(options.progress, "writing OBJ", double(n));
#pragma omp parallel num_threads(threads)
    {
        ObjBodyWriter body(context, options);
        if (omp_get_thread_num() != 0) {
            for (;;) {
                const std::ptrdiff_t c = claimed.fetch_add(1, std::memory_order_relaxed);
                if (c >= n) break;
                waitFor([&] { return slotFree(c); });
                if (failed.load(std::memory_order_acquire)) break;
                format(body, c);
            }
        } else {
            std::ptrdiff_t mine = -1;  // a chunk this thread claimed whose slot is not yet free
            for (std::ptrdiff_t w = 0; w < n && !failed.load(std::memory_order_acquire); ++w) {
                std::atomic<std::ptrdiff_t>& next = ready[std::size_t(w % slots)];
                for (int spins = 0; next.load(std::memory_order_acquire) != w + 1;) {
                    if (failed.load(std::memory_order_acquire)) break;
                    if (mine < 0 && claimed.load(std::memory_order_relaxed) < n) {
                        const std::ptrdiff_t c = claimed.fetch_add(1, std::memory_order_relaxed);
                        if (c < n) mine = c;
                    }
                    if (mine >= 0 && slotFree(mine)) {
                        format(body, mine);
                        mine = -1;
                    } else if (++spins < 256) {
                        std::this_thread::yield();
                    } else {
                        std::this_thread::sleep_for(std::chrono::microseconds(50));
                    }
                }
                if (failed.load(std::memory_order_acquire)) break;
                try {
                    const TextChunk& text = buffers[std::size_t(w % slots)];
                    out.write(text.data(), text.size());
                    written.store(w + 1, std::memory_order_release);
                    steps.at(double(w + 1));
                } catch (...) {
                    fail();
                }
            }
        }
    }
    if (failure) std::rethrow_exception(failure);
}

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
        const io::ObjTextures textures(context, options, root, "", files);
        files.emplace_back((root / kSplitMaterialFile).string(), kSplitBufferBytes);
        writeMTL(files.back(), context, names, root, textures);
        files.back().finish();
    }
    ObjBodyWriter body(context, options);
    const bool plantIDs = hasPlantIDs(context);
    const std::string mtlFile = options.materials ? kSplitMaterialFile : "";
    ProgressSteps steps(options.progress, "writing OBJ", double(ids.size()));
    for (std::size_t i = 0; i < ids.size(); ++i) {
        const ObjectID id = ids[i];
        files.emplace_back((root / (objectName(context, id, plantIDs) + ".obj")).string(),
                           kSplitBufferBytes);
        io::AtomicFile& out = files.back();
        writeHeader(out, context, {id}, mtlFile);
        body.writeObject(out, id, options.materials ? &names[context.objectMaterial(id)] : nullptr,
                         0, 0);
        out.finish();
        steps.at(double(i + 1));
    }
    for (io::AtomicFile& f : files) f.commit();
    steps.finish();
}

}  // namespace

void writeOBJ(const Context& context, const std::string& path, const ObjOptions& options) {
    if (!options.splitPerObject)
        requireOutputFormat(path, {".obj"}, "writeOBJ writes a Wavefront OBJ mesh");
    io::requireDataType(context, "organ", DataType::String, path);
    const std::vector<ObjectID> ids = io::exportedObjects(context, options.includeHidden);
    if (options.splitPerObject) {
        writeSplit(context, path, options, ids);
        return;
    }

    // A buffer for about the whole file when it is small (a small file needs no 4 MB); first,
    // so an unwritable place is reported for the OBJ.
    const std::size_t estimate = std::size_t(120) * context.triangleCount() + 512 * ids.size();
    io::AtomicFile obj(
        path, std::clamp(estimate, kSplitBufferBytes / 4, io::AtomicFile::kDefaultBufferBytes));
    std::optional<io::AtomicFile> mtl;
    std::vector<io::AtomicFile> textureFiles;  // textured materials' maps beside the .mtl
    std::vector<std::string> names;
    fs::path mtlPath;
    if (options.materials) {
        mtlPath = fs::path(path).replace_extension(".mtl");
        if (mtlPath == fs::path(path)) mtlPath += ".mtl";
        names = materialNames(context, ids);
        const io::ObjTextures textures(context, options, mtlPath.parent_path(),
                                       mtlPath.stem().string() + "_", textureFiles);
        mtl.emplace(mtlPath.string(), kSplitBufferBytes);
        writeMTL(*mtl, context, names, mtlPath.parent_path(), textures);
        mtl->finish();
    }
    writeHeader(obj, context, ids, options.materials ? mtlPath.filename().string() : "");
    writeBody(obj, context, options, ids, names);
    obj.finish();
    for (io::AtomicFile& f : textureFiles) f.commit();
    if (mtl) mtl->commit();
    obj.commit();
    if (options.progress) options.progress("writing OBJ", 1.0);
}

}  // namespace plantarch
