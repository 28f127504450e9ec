#include "scene_io/obj_labels.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <system_error>
#include <type_traits>
#include <vector>

#include "core/input_file.h"
#include "plantarch/Error.h"

namespace plantarch::io {

namespace {

// Object data read as integers, with their keys in the comment, in the order written.
constexpr const char* kIntData[5] = {"shootID", "rank", "node", "leafID", "plantID"};
constexpr const char* kIntKeys[5] = {"shoot", "rank", "node", "leaf", "plant"};

bool isPlainByte(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '-' || c == '.';
}

void appendEncoded(std::string& out, std::string_view text) {
    static constexpr char kHex[] = "0123456789ABCDEF";
    for (char c : text) {
        if (isPlainByte(c)) {
            out += c;
        } else {
            const auto byte = static_cast<unsigned char>(c);
            out += '%';
            out += kHex[byte >> 4];
            out += kHex[byte & 15];
        }
    }
}

int hexValue(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    return -1;
}

template <class T>
void appendNumber(std::string& out, T value) {
    char buffer[32];
    out.append(buffer, std::to_chars(buffer, buffer + sizeof buffer, value).ptr);
}

void appendKey(std::string& out, const char* key) {
    out += ' ';
    out += key;
    out += '=';
}

}  // namespace

ObjLabelWriter::ObjLabelWriter(const Context& context) : context_(context) {
    for (int k = 0; k < 5; ++k) hasInt_[k] = context.objectDataType(kIntData[k]) == DataType::Int;
    hasAge_ = context.objectDataType("age") == DataType::Float;
    hasOrgan_ = context.objectDataType("organ") == DataType::String;
    hasPlantName_ = context.objectDataType("plant_name") == DataType::String;
    hasName_ = context.objectDataType("name") == DataType::String;
}

void ObjLabelWriter::append(std::string& out, ObjectID id, std::string_view written) const {
    out += kObjLabelPrefix;
    appendKey(out, "object");
    appendNumber(out, id);
    if (hasInt_[4])
        if (const auto plant = context_.objectDataInt(id, "plantID")) {
            appendKey(out, "plant");
            appendNumber(out, *plant);
        }
    if (hasPlantName_)
        if (const auto name = context_.objectDataString(id, "plant_name")) {
            appendKey(out, "plant_name");
            appendEncoded(out, *name);
        }
    if (hasOrgan_)
        if (const auto organ = context_.objectDataString(id, "organ")) {
            appendKey(out, "organ");
            appendEncoded(out, *organ);
        }
    for (int k = 0; k < 4; ++k)
        if (hasInt_[k])
            if (const auto value = context_.objectDataInt(id, kIntData[k])) {
                appendKey(out, kIntKeys[k]);
                appendNumber(out, *value);
            }
    if (hasAge_)
        if (const auto age = context_.objectDataFloat(id, "age")) {
            appendKey(out, "age");
            appendNumber(out, *age);
        }
    if (hasName_)
        if (const auto name = context_.objectDataString(id, "name"); name && *name != written) {
            appendKey(out, "name");
            appendEncoded(out, *name);
        }
    out += '\n';
}

ObjLabelRecord parseObjLabelLine(std::string_view line, const std::string& path, int lineNumber) {
    ObjLabelRecord r;
    std::size_t at = kObjLabelPrefix.size();
    auto bad = [&](std::string_view key, std::string_view value, const char* range) {
        throw Error("bad value in a plantarch label comment", {.file = path,
                                                               .line = lineNumber,
                                                               .parameter = std::string(key),
                                                               .value = std::string(value),
                                                               .validRange = range});
    };
    while (at < line.size()) {
        at = line.find_first_not_of(" \t\r", at);
        if (at == std::string_view::npos) break;
        const std::size_t end = std::min(line.find_first_of(" \t\r", at), line.size());
        const std::string_view word = line.substr(at, end - at);
        at = end;
        const std::size_t eq = word.find('=');
        if (eq == std::string_view::npos) continue;  // not a key=value pair: skipped
        const std::string_view key = word.substr(0, eq), value = word.substr(eq + 1);
        auto integer = [&](auto& slot, const char* range) {
            using T = typename std::remove_reference_t<decltype(slot)>::value_type;
            T v{};
            const auto [next, ec] = std::from_chars(value.data(), value.data() + value.size(), v);
            if (ec != std::errc() || next != value.data() + value.size()) bad(key, value, range);
            slot = v;
        };
        auto text = [&](std::optional<std::string>& slot) {
            std::string decoded;
            for (std::size_t i = 0; i < value.size(); ++i) {
                if (value[i] != '%') {
                    decoded += value[i];
                    continue;
                }
                const int hi = i + 2 < value.size() ? hexValue(value[i + 1]) : -1;
                const int lo = hi >= 0 ? hexValue(value[i + 2]) : -1;
                if (lo < 0) bad(key, value, "text with bytes encoded as %XX");
                decoded += char(hi * 16 + lo);
                i += 2;
            }
            slot = std::move(decoded);
        };
        if (key == "object") {
            integer(r.object, "an object ID, 0 to 4294967295");
        } else if (key == "plant") {
            integer(r.plant, "an integer, -2147483648 to 2147483647");
        } else if (key == "shoot") {
            integer(r.shoot, "an integer, -2147483648 to 2147483647");
        } else if (key == "rank") {
            integer(r.rank, "an integer, -2147483648 to 2147483647");
        } else if (key == "node") {
            integer(r.node, "an integer, -2147483648 to 2147483647");
        } else if (key == "leaf") {
            integer(r.leaf, "an integer, -2147483648 to 2147483647");
        } else if (key == "age") {
            float v = 0.0f;
            const auto [next, ec] = std::from_chars(value.data(), value.data() + value.size(), v);
            if (ec != std::errc() || next != value.data() + value.size() || !std::isfinite(v))
                bad(key, value, "a finite number of days");
            r.age = v;
        } else if (key == "organ") {
            text(r.organ);
        } else if (key == "plant_name") {
            text(r.plantName);
        } else if (key == "name") {
            text(r.name);
        }
    }
    return r;
}

namespace {

// The name tinyobjloader gives a shape from an `o` or `g` line: the words after the keyword,
// joined by single spaces.
std::string shapeName(std::string_view rest) {
    std::string name;
    std::size_t at = 0;
    while (at < rest.size()) {
        at = rest.find_first_not_of(" \t\r", at);
        if (at == std::string_view::npos) break;
        const std::size_t end = std::min(rest.find_first_of(" \t\r", at), rest.size());
        if (!name.empty()) name += ' ';
        name.append(rest.substr(at, end - at));
        at = end;
    }
    return name;
}

}  // namespace

std::unordered_map<std::string, ObjLabelRecord> readObjLabels(const std::string& path) {
    std::unordered_map<std::string, ObjLabelRecord> labels;
    std::string current;
    // Only lines starting with 'o', 'g' or '#' are looked at closely.
    InputFile file(path, kOBJFile);
    forEachLine(file, [&](std::string_view l, int number) {
        const std::size_t first = l.find_first_not_of(" \t");
        if (first == std::string_view::npos) return;
        l.remove_prefix(first);
        if (l.size() >= 2 && (l[0] == 'o' || l[0] == 'g') && (l[1] == ' ' || l[1] == '\t')) {
            current = shapeName(l.substr(2));
        } else if (l.substr(0, kObjLabelPrefix.size()) == kObjLabelPrefix &&
                   (l.size() == kObjLabelPrefix.size() || l[kObjLabelPrefix.size()] == ' ')) {
            ObjLabelRecord record = parseObjLabelLine(l, path, number);
            labels.try_emplace(current, std::move(record));
        }
    });
    return labels;
}

void applyObjLabels(Context& context, ObjectID id, const ObjLabelRecord& r) {
    if (r.plant) context.setObjectData(id, "plantID", *r.plant);
    if (r.plantName) context.setObjectData(id, "plant_name", *r.plantName);
    if (r.organ) context.setObjectData(id, "organ", *r.organ);
    if (r.shoot) context.setObjectData(id, "shootID", *r.shoot);
    if (r.rank) context.setObjectData(id, "rank", *r.rank);
    if (r.node) context.setObjectData(id, "node", *r.node);
    if (r.leaf) context.setObjectData(id, "leafID", *r.leaf);
    if (r.age) context.setObjectData(id, "age", *r.age);
    if (r.name) context.setObjectData(id, "name", *r.name);
}

}  // namespace plantarch::io
