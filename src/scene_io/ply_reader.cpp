// PLY reader: ASCII and binary (either byte order) meshes, plantarch's own files with their
// per-face labels, and scans and meshes from other tools. Everything is parsed and checked
// before the Context is touched, so a bad file leaves the Context unchanged.

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/input_file.h"
#include "core/progress_steps.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"

namespace plantarch {

namespace {

inline constexpr io::InputKind kPLYFile{"PLY file", 4096 * io::kMiB, false};
// A polygon of more corners than this is refused (a list count read as garbage, say).
constexpr std::uint32_t kMaxPolygon = 1024;

enum class Format { Ascii, LittleEndian, BigEndian };
enum class Type { I8, U8, I16, U16, I32, U32, F32, F64 };

std::optional<Type> typeNamed(std::string_view name) {
    static const std::pair<std::string_view, Type> kNames[] = {
        {"char", Type::I8},    {"int8", Type::I8},     {"uchar", Type::U8},
        {"uint8", Type::U8},   {"short", Type::I16},   {"int16", Type::I16},
        {"ushort", Type::U16}, {"uint16", Type::U16},  {"int", Type::I32},
        {"int32", Type::I32},  {"uint", Type::U32},    {"uint32", Type::U32},
        {"float", Type::F32},  {"float32", Type::F32}, {"double", Type::F64},
        {"float64", Type::F64}};
    for (const auto& [n, t] : kNames)
        if (n == name) return t;
    return std::nullopt;
}

std::size_t sizeOf(Type t) {
    switch (t) {
        case Type::I8:
        case Type::U8:
            return 1;
        case Type::I16:
        case Type::U16:
            return 2;
        case Type::I32:
        case Type::U32:
        case Type::F32:
            return 4;
        case Type::F64:
            return 8;
    }
    return 1;
}

struct Property {
    std::string name;
    Type type = Type::F32;
    bool list = false;
    Type countType = Type::U8;
};

struct Element {
    std::string name;
    std::uint64_t count = 0;
    std::vector<Property> properties;
};

struct Header {
    Format format = Format::Ascii;
    std::vector<Element> elements;
    std::map<int, std::string> organNames;  // comment organ_label <int> <name>
    std::size_t bodyStart = 0;
};

// Splits a header line into words.
std::vector<std::string_view> words(std::string_view line) {
    std::vector<std::string_view> out;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
        const std::size_t start = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
        if (i > start) out.push_back(line.substr(start, i - start));
    }
    return out;
}

class Reader {
public:
    Reader(std::string text, std::string path) : data_(std::move(text)), path_(std::move(path)) {}

    Header header() {
        Header h;
        if (data_.compare(0, 4, "ply\n") != 0 && data_.compare(0, 5, "ply\r\n") != 0)
            fail("not a PLY file: it does not start with \"ply\"");
        std::size_t pos = data_.find('\n') + 1;
        int line = 1;
        bool formatSeen = false;
        for (;;) {
            const std::size_t end = data_.find('\n', pos);
            if (end == std::string::npos) fail("the header has no end_header line");
            const std::string_view text(data_.data() + pos, end - pos);
            pos = end + 1;
            ++line;
            const std::vector<std::string_view> w = words(text);
            if (w.empty()) continue;
            if (w[0] == "end_header") break;
            if (w[0] == "comment" || w[0] == "obj_info") {
                int label = 0;
                if (w.size() == 4 && w[1] == "organ_label" &&
                    std::from_chars(w[2].data(), w[2].data() + w[2].size(), label).ec ==
                        std::errc())
                    h.organNames[label] = std::string(w[3]);
                continue;
            }
            if (w[0] == "format") {
                if (w.size() != 3 || w[2] != "1.0") headerError(line, "a format version of 1.0");
                if (w[1] == "ascii")
                    h.format = Format::Ascii;
                else if (w[1] == "binary_little_endian")
                    h.format = Format::LittleEndian;
                else if (w[1] == "binary_big_endian")
                    h.format = Format::BigEndian;
                else
                    headerError(line, "ascii, binary_little_endian or binary_big_endian");
                formatSeen = true;
            } else if (w[0] == "element") {
                std::uint64_t count = 0;
                if (w.size() != 3 ||
                    std::from_chars(w[2].data(), w[2].data() + w[2].size(), count).ec !=
                        std::errc())
                    headerError(line, "element <name> <count>");
                // Each item takes a byte at least: a count past the file's size is a lie.
                if (count > data_.size()) headerError(line, "a count the file can hold");
                h.elements.push_back({std::string(w[1]), count, {}});
            } else if (w[0] == "property") {
                if (h.elements.empty()) headerError(line, "a property after its element");
                Property p;
                if (w.size() == 5 && w[1] == "list") {
                    const auto count = typeNamed(w[2]), item = typeNamed(w[3]);
                    if (!count || !item || *count == Type::F32 || *count == Type::F64)
                        headerError(line, "property list <integer type> <type> <name>");
                    p = {std::string(w[4]), *item, true, *count};
                } else if (w.size() == 3 && typeNamed(w[1])) {
                    p = {std::string(w[2]), *typeNamed(w[1]), false, Type::U8};
                } else {
                    headerError(line, "property <type> <name> or property list ...");
                }
                h.elements.back().properties.push_back(p);
            } else {
                headerError(line, "format, element, property, comment or end_header");
            }
        }
        if (!formatSeen) fail("the header has no format line");
        h.bodyStart = pos;
        pos_ = pos;
        format_ = h.format;
        return h;
    }

    // The next value of type `t` as a double.
    double value(Type t) {
        if (format_ == Format::Ascii) return asciiValue();
        const std::size_t n = sizeOf(t);
        if (data_.size() - pos_ < n) fail("the file ends before its data does");
        unsigned char b[8];
        std::memcpy(b, data_.data() + pos_, n);
        pos_ += n;
        const bool swap =
            (format_ == Format::BigEndian) != (std::endian::native == std::endian::big);
        if (swap)
            for (std::size_t i = 0; i < n / 2; ++i) std::swap(b[i], b[n - 1 - i]);
        switch (t) {
            case Type::I8:
                return double(std::int8_t(b[0]));
            case Type::U8:
                return double(b[0]);
            case Type::I16:
                return double(load<std::int16_t>(b));
            case Type::U16:
                return double(load<std::uint16_t>(b));
            case Type::I32:
                return double(load<std::int32_t>(b));
            case Type::U32:
                return double(load<std::uint32_t>(b));
            case Type::F32:
                return double(load<float>(b));
            case Type::F64:
                return load<double>(b);
        }
        return 0.0;
    }

    // Skips one item of an element nobody reads (ASCII: its line).
    void skipItem(const Element& e) {
        if (format_ == Format::Ascii) {
            skipSpace();
            const std::size_t end = data_.find('\n', pos_);
            pos_ = end == std::string::npos ? data_.size() : end + 1;
            return;
        }
        for (const Property& p : e.properties) {
            if (!p.list) {
                value(p.type);
                continue;
            }
            skipList(p);
        }
    }

    // Skips one list value of property `p` (binary or ASCII).
    void skipList(const Property& p) {
        const double n = value(p.countType);
        if (!(n >= 0.0) || n > double(data_.size())) fail("a list count past the file's end");
        for (std::uint64_t i = 0; i < std::uint64_t(n); ++i) value(p.type);
    }

    // Refuses an element that claims more items than the rest of the file can hold: each takes
    // at least its scalars' bytes (binary) or two characters a property (ASCII).
    void checkCount(const Element& e) const {
        std::uint64_t least = 0;
        for (const Property& p : e.properties)
            least += format_ == Format::Ascii ? 2 : sizeOf(p.list ? p.countType : p.type);
        if (least > 0 && e.count > (data_.size() - pos_) / least)
            fail("element " + e.name + " claims " + std::to_string(e.count) +
                 " items, more than the rest of the file holds");
    }

    double fraction() const {
        return double(pos_) / double(std::max<std::size_t>(1, data_.size()));
    }

    [[noreturn]] void fail(const std::string& what) const { throw Error(what, {.file = path_}); }

private:
    template <class T>
    static T load(const unsigned char* b) {
        T v;
        std::memcpy(&v, b, sizeof v);
        return v;
    }

    void skipSpace() {
        while (pos_ < data_.size() && (data_[pos_] == ' ' || data_[pos_] == '\t' ||
                                       data_[pos_] == '\r' || data_[pos_] == '\n'))
            ++pos_;
    }

    double asciiValue() {
        skipSpace();
        if (pos_ >= data_.size()) fail("the file ends before its data does");
        double v = 0.0;
        const char* begin = data_.data() + pos_;
        const auto [end, ec] = std::from_chars(begin, data_.data() + data_.size(), v);
        if (ec != std::errc() || end == begin)
            fail("not a number in the data: \"" +
                 std::string(begin, std::min<std::size_t>(20, data_.size() - pos_)) + "\"");
        pos_ = std::size_t(end - data_.data());
        return v;
    }

    [[noreturn]] void headerError(int line, const std::string& valid) const {
        throw Error("bad PLY header line " + std::to_string(line),
                    {.file = path_, .validRange = valid});
    }

    std::string data_;
    std::string path_;
    std::size_t pos_ = 0;
    Format format_ = Format::Ascii;
};

// A face's labels, as writePLY writes them (-1: absent).
struct FaceValues {
    int plant = -1, object = -1, organ = -1, leaf = -1, shoot = -1, rank = -1, node = -1;
    double age = -1.0;
};

int whole(double v) {
    return std::isfinite(v) && v >= -2147483648.0 && v <= 2147483647.0 ? int(v) : -1;
}

// A face: its corners (vertex indices) and its labels.
struct PlyFace {
    std::vector<std::uint32_t> corners;
    FaceValues labels;
};

// The vertex element: positions, and colours when it has red, green and blue bytes.
void readVertices(Reader& r, const Element& e, std::vector<vec3>& vertices,
                  std::vector<vec3>& colours) {
    int ix = -1, iy = -1, iz = -1, ic[3] = {-1, -1, -1};
    for (std::size_t k = 0; k < e.properties.size(); ++k) {
        const Property& p = e.properties[k];
        if (p.list) continue;
        if (p.name == "x") ix = int(k);
        if (p.name == "y") iy = int(k);
        if (p.name == "z") iz = int(k);
        if (p.type == Type::U8 && (p.name == "red" || p.name == "green" || p.name == "blue"))
            ic[p.name == "red" ? 0 : p.name == "green" ? 1 : 2] = int(k);
    }
    const bool coloured = ic[0] >= 0 && ic[1] >= 0 && ic[2] >= 0;
    if (ix < 0 || iy < 0 || iz < 0) r.fail("the vertex element has no x, y and z");
    vertices.reserve(std::size_t(e.count));
    for (std::uint64_t i = 0; i < e.count; ++i) {
        double xyz[3] = {0, 0, 0};
        vec3 rgb(0.0f);
        for (std::size_t k = 0; k < e.properties.size(); ++k) {
            const Property& p = e.properties[k];
            if (p.list) {
                r.skipList(p);
                continue;
            }
            const double v = r.value(p.type);
            if (int(k) == ix) xyz[0] = v;
            if (int(k) == iy) xyz[1] = v;
            if (int(k) == iz) xyz[2] = v;
            for (int c = 0; c < 3; ++c)
                if (int(k) == ic[c]) rgb[c] = float(v) / 255.0f;
        }
        if (coloured) colours.push_back(rgb);
        for (double c : xyz)
            if (!(std::abs(c) <= double(std::numeric_limits<float>::max())))
                r.fail("vertex " + std::to_string(i) + " is not a finite float");
        vertices.push_back(vec3{float(xyz[0]), float(xyz[1]), float(xyz[2])});
    }
}

// The face element: corners checked against the `vertexCount` vertices read before it.
std::vector<PlyFace> readFaces(Reader& r, const Element& e, std::size_t vertexCount) {
    int corners = -1;
    for (std::size_t k = 0; k < e.properties.size(); ++k)
        if (e.properties[k].list &&
            (e.properties[k].name == "vertex_indices" || e.properties[k].name == "vertex_index"))
            corners = int(k);
    if (corners < 0) r.fail("the face element has no vertex_indices list");
    std::vector<PlyFace> faces;
    faces.reserve(std::size_t(std::min<std::uint64_t>(e.count, 1u << 26)));
    for (std::uint64_t i = 0; i < e.count; ++i) {
        PlyFace f;
        for (std::size_t k = 0; k < e.properties.size(); ++k) {
            const Property& p = e.properties[k];
            if (p.list) {
                const double n = r.value(p.countType);
                if (!(n >= 0.0) || (int(k) == corners && (n < 3 || n > kMaxPolygon)))
                    r.fail("face " + std::to_string(i) + " has " + std::to_string(whole(n)) +
                           " corners (valid: 3 to " + std::to_string(kMaxPolygon) + ")");
                for (std::uint64_t j = 0; j < std::uint64_t(n); ++j) {
                    const double v = r.value(p.type);
                    if (int(k) != corners) continue;
                    if (!(v >= 0.0 && v < double(vertexCount) && v == std::floor(v)))
                        r.fail("face " + std::to_string(i) + " names vertex " +
                               std::to_string(whole(v)) +
                               (vertexCount == 0
                                    ? std::string(" (no vertices come before the faces)")
                                    : " (valid: 0 to " + std::to_string(vertexCount - 1) + ")"));
                    f.corners.push_back(std::uint32_t(v));
                }
                continue;
            }
            const double v = r.value(p.type);
            FaceValues& l = f.labels;
            if (p.name == "plant_id") l.plant = whole(v);
            if (p.name == "object_id") l.object = whole(v);
            if (p.name == "organ") l.organ = whole(v);
            if (p.name == "leaf_id") l.leaf = whole(v);
            if (p.name == "shoot_id") l.shoot = whole(v);
            if (p.name == "rank") l.rank = whole(v);
            if (p.name == "node") l.node = whole(v);
            if (p.name == "age") l.age = std::isfinite(v) ? v : -1.0;
        }
        faces.push_back(std::move(f));
    }
    return faces;
}

// One object's mesh, labels and colour (of its first vertex).
struct PlyObject {
    Mesh mesh;
    FaceValues labels;
    std::map<std::uint32_t, std::uint32_t> local;
    std::optional<vec3> colour;
};

// The faces as objects: one per object_id (in first-appearance order) when `perObject`, else
// one, each with vertices of its own; polygons as fans.
std::vector<PlyObject> partsOf(const std::vector<PlyFace>& faces, const std::vector<vec3>& vertices,
                               const std::vector<vec3>& colours, bool perObject) {
    std::vector<PlyObject> parts;
    std::map<int, std::size_t> partOf;
    for (const PlyFace& f : faces) {
        const int key = perObject ? f.labels.object : -1;
        auto [it, added] = partOf.emplace(key, parts.size());
        if (added)
            parts.push_back(
                {{},
                 f.labels,
                 {},
                 colours.empty() ? std::nullopt : std::optional<vec3>(colours[f.corners[0]])});
        PlyObject& part = parts[it->second];
        std::vector<std::uint32_t> ids;
        for (std::uint32_t c : f.corners) {
            auto [at, fresh] = part.local.emplace(c, std::uint32_t(part.mesh.positions.size()));
            if (fresh) part.mesh.positions.push_back(vertices[c]);
            ids.push_back(at->second);
        }
        for (std::size_t j = 1; j + 1 < ids.size(); ++j)
            part.mesh.indices.insert(part.mesh.indices.end(), {ids[0], ids[j], ids[j + 1]});
    }
    return parts;
}

// The parts added to `context` with their labels as object data (when `perObject`); on
// failure the objects added so far are deleted again.
std::vector<ObjectID> addParts(Context& context, const std::vector<PlyObject>& parts,
                               const Header& h, bool perObject) {
    std::vector<ObjectID> made;
    try {
        for (const PlyObject& part : parts) {
            const ObjectID id = part.colour ? context.addObject(part.mesh, Material{*part.colour})
                                            : context.addObject(part.mesh);
            made.push_back(id);
            if (!perObject) continue;
            const FaceValues& l = part.labels;
            if (l.plant >= 0) context.setObjectData(id, "plantID", std::int32_t(l.plant));
            // A label named "unlabelled" (writePLY's name for no organ data, whatever its
            // number in the file) gives none, so that the object writes back as it read.
            if (const auto n = h.organNames.find(l.organ);
                n != h.organNames.end() && l.organ > 0 && n->second != kOrganLabels[0])
                context.setObjectData(id, "organ", n->second);
            if (l.leaf >= 0) context.setObjectData(id, "leafID", std::int32_t(l.leaf));
            if (l.shoot >= 0) context.setObjectData(id, "shootID", std::int32_t(l.shoot));
            if (l.rank >= 0) context.setObjectData(id, "rank", std::int32_t(l.rank));
            if (l.node >= 0) context.setObjectData(id, "node", std::int32_t(l.node));
            if (l.age >= 0.0) context.setObjectData(id, "age", float(l.age));
        }
    } catch (...) {
        context.deleteObjects(made);
        throw;
    }
    return made;
}

}  // namespace

std::vector<ObjectID> readPLY(Context& context, const std::string& path,
                              const PlyReadOptions& options) {
    io::InputFile file(path, kPLYFile);
    Reader r(file.readAll(), path);
    const Header h = r.header();
    ProgressSteps steps(options.progress, "reading PLY", 1.0);

    std::vector<vec3> vertices;
    std::vector<vec3> colours;  // the vertices' red, green, blue (0 to 1), when they have them
    std::vector<PlyFace> faces;
    bool vertexSeen = false, faceSeen = false;
    for (const Element& e : h.elements) {
        r.checkCount(e);
        if (e.name == "vertex" && !vertexSeen) {
            vertexSeen = true;
            readVertices(r, e, vertices, colours);
        } else if (e.name == "face" && !faceSeen) {
            faceSeen = true;
            faces = readFaces(r, e, vertices.size());
        } else {
            for (std::uint64_t i = 0; i < e.count; ++i) r.skipItem(e);
        }
        steps.at(r.fraction());
    }
    if (!vertexSeen || !faceSeen || faces.empty())
        r.fail("no faces: render and obstacles need a mesh (a vertex and a face element)");
    std::vector<PlyObject> parts = partsOf(faces, vertices, colours, options.labels);
    vertices.clear();
    faces.clear();
    const std::vector<ObjectID> made = addParts(context, parts, h, options.labels);
    steps.finish();
    return made;
}

std::vector<vec3> readPLYPoints(const std::string& path) {
    io::InputFile file(path, kPLYFile);
    Reader r(file.readAll(), path);
    const Header h = r.header();
    std::vector<vec3> vertices, colours;
    for (const Element& e : h.elements) {
        r.checkCount(e);
        if (e.name == "vertex") {
            readVertices(r, e, vertices, colours);
            break;  // the elements after the vertices (faces) are not needed
        }
        for (std::uint64_t i = 0; i < e.count; ++i) r.skipItem(e);
    }
    if (vertices.empty()) r.fail("no points: a point cloud needs a vertex element of x, y, z");
    return vertices;
}

}  // namespace plantarch
