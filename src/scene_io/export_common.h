#pragma once
// Pieces shared by the OBJ and PLY writers: number formatting into a raw buffer, the
// choice of objects to export, smooth normals and the typed object data they read.

#include <charconv>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "plantarch/Context.h"
#include "plantarch/Export.h"

namespace plantarch::io {

/// Longest text writeFloat produces ("-1.17549435e-38").
inline constexpr std::size_t kMaxFloatChars = 16;
/// Room for one line of a text format: a face of three index triples of 20-digit numbers, or
/// a vertex of a few floats.
inline constexpr std::size_t kLineBytes = 256;

/// Shortest text that reads back as the same float; -0 is written as 0.
inline char* writeFloat(char* out, float value) {
    return std::to_chars(out, out + kMaxFloatChars, value + 0.0f).ptr;
}

/// Fixed-point text with up to 6 decimals, trailing zeros dropped ("0.707107", "-1", "0").
/// For unit normals, where 1e-6 is far below any use and shortest round-trip text (nine
/// digits, through the general algorithm) would cost most of the export time.
/// Requires |value| < 9e12.
inline char* writeFixed6(char* out, float value) {
    std::int64_t scaled = std::llround(double(value) * 1e6);
    if (scaled < 0) {
        *out++ = '-';
        scaled = -scaled;
    }
    const std::uint64_t whole = std::uint64_t(scaled) / 1000000u;
    std::uint32_t fraction = std::uint32_t(std::uint64_t(scaled) % 1000000u);
    out = std::to_chars(out, out + 20, whole).ptr;
    if (fraction != 0) {
        int digits = 6;
        while (fraction % 10 == 0) {
            fraction /= 10;
            --digits;
        }
        *out++ = '.';
        for (int i = digits - 1; i >= 0; --i) {
            out[i] = char('0' + fraction % 10);
            fraction /= 10;
        }
        out += digits;
    }
    return out;
}

inline char* writeUInt(char* out, std::uint64_t value) {
    return std::to_chars(out, out + 20, value).ptr;
}

inline char* writeInt(char* out, std::int64_t value) {
    return std::to_chars(out, out + 21, value).ptr;
}

inline char* writeText(char* out, std::string_view text) {
    for (char c : text) *out++ = c;
    return out;
}

/// The objects a writer exports, in increasing ID order.
std::vector<ObjectID> exportedObjects(const Context& context, bool includeHidden);

/// Smooth per-vertex normals (declared in plantarch/Export.h).
using plantarch::smoothNormals;

/// Throws Error (naming `file`) when object data `label` exists with a type other than
/// `expected`, so writers can then use the typed getters without surprises.
void requireDataType(const Context& context, std::string_view label, DataType expected,
                     const std::string& file);

/// Throws Error (naming `file`) unless the frame rate is 0.001 to 1000.
void checkFrameRate(const AnimationOptions& animation, const std::string& file);
/// Throws Error (naming `file`) unless there is at least one frame, every frame has a
/// Context, days are finite and increasing, and the frame rate is 0.001 to 1000.
void checkAnimation(const std::vector<AnimationFrame>& frames, const AnimationOptions& animation,
                    const std::string& file);

/// The index in kOrganLabels of an organ name (trellis parts are obstacles); 0 for others.
std::uint8_t organCode(std::string_view organ);

/// An object's labels as exporters write them: -1 (age: -1) where the data is absent.
struct ObjectLabels {
    std::int32_t plant = -1, leaf = -1, shoot = -1, rank = -1, node = -1;
    float age = -1.0f;
    std::uint8_t organ = 0;
};

/// Reads objects' labels from their data (plantID, leafID, shootID, rank, node, age, organ);
/// data of another type than plantarch writes counts as absent.
class LabelReader {
public:
    explicit LabelReader(const Context& context);
    ObjectLabels operator()(ObjectID id) const;

private:
    const Context& context_;
    bool hasInt_[5];
    bool hasAge_, hasOrgan_;
};

/// Appends one point's object and labels to the label arrays of a point cloud.
inline void appendLabels(PointCloud& cloud, ObjectID id, const ObjectLabels& l) {
    cloud.plantID.push_back(l.plant);
    cloud.objectID.push_back(id);
    cloud.organ.push_back(l.organ);
    cloud.leafID.push_back(l.leaf);
    cloud.shootID.push_back(l.shoot);
    cloud.rank.push_back(l.rank);
    cloud.age.push_back(l.age);
}

/// "organ" data of an object, empty when absent.
std::string organOf(const Context& context, ObjectID id);

}  // namespace plantarch::io
