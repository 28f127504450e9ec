#pragma once
// Pieces of the USD text writers (usd_writer.cpp, usd_organs.cpp): prim names, quoted strings and
// the text sink that writes numbers as their shortest exact text.

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/atomic_file.h"
#include "core/progress_steps.h"
#include "plantarch/Export.h"
#include "scene_io/export_common.h"

namespace plantarch::io {

// Prim names are identifiers: letters, digits and '_', not starting with a digit.
inline std::string primName(const std::string& text) {
    std::string out;
    for (char c : text) out += (std::isalnum(static_cast<unsigned char>(c)) ? c : '_');
    if (out.empty() || std::isdigit(static_cast<unsigned char>(out[0]))) out = "_" + out;
    return out;
}

inline std::string usdQuoted(const std::string& text) {
    std::string out = "\"";
    for (char c : text) {
        if (c == '"' || c == '\\') out += '\\';
        out += (c == '\n' ? ' ' : c);
    }
    return out + "\"";
}

// Numbers into the file's buffer (or a string, for a .usdz package), shortest exact text.
class Text {
public:
    explicit Text(io::AtomicFile& file) : file_(&file) {}
    explicit Text(std::string& text) : text_(&text) {}
    /// Text written at the start of each line from now on (the nesting of a frame's prims);
    /// called at the start of a line.
    void indent(std::string_view prefix) {
        indent_ = prefix;
        lineStart_ = true;
    }
    Text& operator<<(std::string_view s) {
        if (indent_.empty()) {
            put(s);
            return *this;
        }
        for (std::size_t at = 0; at < s.size();) {
            const std::size_t end = std::min(s.find('\n', at), s.size() - 1);
            lineStart();
            put(s.substr(at, end + 1 - at));
            lineStart_ = s[end] == '\n';
            at = end + 1;
        }
        return *this;
    }
    Text& number(float v) {
        lineStart();
        char p[io::kMaxFloatChars];
        put(std::string_view(p, std::size_t(io::writeFloat(p, v) - p)));
        return *this;
    }
    Text& integer(std::int64_t v) {
        lineStart();
        char p[24];
        put(std::string_view(p, std::size_t(io::writeInt(p, v) - p)));
        return *this;
    }
    Text& tuple(const float* v, int n) {
        put("(");
        for (int i = 0; i < n; ++i) {
            if (i) put(", ");
            number(v[i]);
        }
        put(")");
        return *this;
    }

private:
    void put(std::string_view s) {
        if (file_)
            file_->write(s);
        else
            text_->append(s);
    }
    void lineStart() {
        if (lineStart_ && !indent_.empty()) put(indent_);
        lineStart_ = false;
    }

    io::AtomicFile* file_ = nullptr;
    std::string* text_ = nullptr;
    std::string indent_;
    bool lineStart_ = false;
};

/// Which attributes writeMeshData writes.
struct UsdMeshParts {
    bool topology = true;      ///< face counts and indices, UVs, display colour and labels
    bool geometry = true;      ///< points and normals
    bool objectLabels = true;  ///< per-face object, leaf, shoot, rank, node and age (else only
                               ///< organ and plant: a mesh several organs share)
};

/// The attributes of one Mesh prim holding `objects` (points relative to `origin`), at 12
/// spaces: faces, points, normals (with options.normals), UVs (with `uvs`), and per face the
/// display colour and the labels (organ code, plant, object, leaf, shoot, rank, node, age).
/// `plant` is the plant of every object.
void writeMeshData(Text& out, const Context& context, std::span<const ObjectID> objects,
                   vec3 origin, std::int32_t plant, bool uvs, const UsdOptions& options,
                   const LabelReader& labelsOf, UsdMeshParts parts = {});

class UsdLooks;

/// The plants of `frames` with a prim per shoot and per organ (NodeLevel::Organ, and every
/// animation), each organ placed by its translation, orientation and scale (time samples in an
/// animation, one per frame; visibility where it does not exist), its shape written once and
/// referenced by the organs that share it (usd_organs.cpp). Reports ("writing USD", fraction)
/// to options.progress by the triangles of the shapes written.
void writeOrganPrims(Text& out, const std::vector<const Context*>& frames,
                     const std::vector<std::vector<GltfPlant>>& plants, const UsdOptions& options,
                     const UsdLooks& looks, bool animated);

}  // namespace plantarch::io
