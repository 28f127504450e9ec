#pragma once
// The label comment of OBJ files (docs/formats.md, "Labels across formats"): one line per
// object (wrapped here), after its `o` and `g` lines,
//
//   # plantarch labels object=42 plant=3 plant_name=my%20plant organ=leaf shoot=1 rank=1 node=4
//   leaf=7 age=12.5
//
// holding the labels the other exporters write (plant, organ, shoot, rank, node, leaf, age)
// and the object's ID. Keys whose data the object lacks are left out; text values are
// percent-encoded (every byte other than letters, digits, '_', '-' and '.' as %XX), so a
// value never holds a space. Other OBJ readers skip the line as a comment; readOBJ reads it
// back into the same object data.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>

#include "plantarch/Context.h"

namespace plantarch::io {

inline constexpr std::string_view kObjLabelPrefix = "# plantarch labels";

/// The labels of one object as the comment holds them; absent keys are empty.
struct ObjLabelRecord {
    std::optional<ObjectID> object;
    std::optional<std::int32_t> plant, shoot, rank, node, leaf;
    std::optional<float> age;
    std::optional<std::string> organ, plantName, name;
};

/// Formats the label lines of objects. Reads the typed object data once per Context.
class ObjLabelWriter {
public:
    explicit ObjLabelWriter(const Context& context);
    /// Appends the object's label line, with its newline, to `out`. `written` is the name the
    /// file gives the object: its "name" label is written (name=) only when it differs.
    void append(std::string& out, ObjectID id, std::string_view written) const;

private:
    const Context& context_;
    bool hasInt_[5];
    bool hasAge_, hasOrgan_, hasPlantName_, hasName_;
};

/// The object data labels readOBJ sets from the comments, with their types.
struct ObjLabelData {
    const char* label;
    DataType type;
};
inline constexpr ObjLabelData kObjLabelData[] = {
    {"plantID", DataType::Int}, {"plant_name", DataType::String}, {"organ", DataType::String},
    {"shootID", DataType::Int}, {"rank", DataType::Int},          {"node", DataType::Int},
    {"leafID", DataType::Int},  {"age", DataType::Float}};

/// Parses one label line (starting with kObjLabelPrefix). Keys this version does not know are
/// skipped, so files of later versions still read; a known key with a bad value throws Error
/// naming `path`, the line number, the key and the value.
ObjLabelRecord parseObjLabelLine(std::string_view line, const std::string& path, int lineNumber);

/// The label lines of an OBJ file, by the name of the shape (the last `o` or `g` name before
/// the line) they belong to. A name with two different lines keeps the first.
std::unordered_map<std::string, ObjLabelRecord> readObjLabels(const std::string& path);

/// Sets the object data of a record on `id` (kObjLabelData labels; the types must match).
void applyObjLabels(Context& context, ObjectID id, const ObjLabelRecord& record);

}  // namespace plantarch::io
