#include "scene_io/export_common.h"

#include <cctype>
#include <cmath>

#include "core/value_text.h"
#include "plantarch/Error.h"

namespace plantarch::io {

std::vector<ObjectID> exportedObjects(const Context& context, bool includeHidden) {
    std::vector<ObjectID> ids = context.objectIDs();
    if (!includeHidden) std::erase_if(ids, [&](ObjectID id) { return context.isObjectHidden(id); });
    return ids;
}

void requireDataType(const Context& context, std::string_view label, DataType expected,
                     const std::string& file) {
    const std::optional<DataType> type = context.objectDataType(label);
    if (type && *type != expected)
        throw Error(std::string("object data has type ") + dataTypeName(*type) +
                        ", exporters need " + dataTypeName(expected),
                    {.file = file, .parameter = std::string(label)});
}

void checkFrameRate(const AnimationOptions& animation, const std::string& file) {
    const double rate = animation.framesPerSecond;
    if (!(rate >= 0.001 && rate <= 1000.0))
        throw Error("frame rate out of range", {.file = file,
                                                .parameter = "framesPerSecond",
                                                .value = text::formatDouble(rate),
                                                .validRange = "0.001 to 1000"});
}

void checkAnimation(const std::vector<AnimationFrame>& frames, const AnimationOptions& animation,
                    const std::string& file) {
    if (frames.empty()) throw Error("an animation needs at least one frame", {.file = file});
    checkFrameRate(animation, file);
    for (std::size_t i = 0; i < frames.size(); ++i) {
        if (!frames[i].context)
            throw Error("animation frame " + std::to_string(i) + " has no Context", {.file = file});
        const double day = frames[i].day;
        if (!std::isfinite(day) || (i > 0 && !(day > frames[i - 1].day)))
            throw Error("animation frame days must be finite and increasing",
                        {.file = file,
                         .parameter = "frame " + std::to_string(i) + " day",
                         .value = text::formatDouble(day),
                         .validRange = i > 0 ? "more than " + text::formatDouble(frames[i - 1].day)
                                             : "a finite number"});
    }
}

std::uint8_t organCode(std::string_view organ) {
    for (std::size_t i = 0; i < kOrganLabels.size(); ++i)
        if (organ == kOrganLabels[i]) return std::uint8_t(i);
    return organ == "trellis" ? std::uint8_t(9) : std::uint8_t(0);
}

namespace {
constexpr const char* kIntLabels[5] = {"plantID", "leafID", "shootID", "rank", "node"};
}

LabelReader::LabelReader(const Context& context) : context_(context) {
    for (int k = 0; k < 5; ++k) hasInt_[k] = context.objectDataType(kIntLabels[k]) == DataType::Int;
    hasAge_ = context.objectDataType("age") == DataType::Float;
    hasOrgan_ = context.objectDataType("organ") == DataType::String;
}

ObjectLabels LabelReader::operator()(ObjectID id) const {
    ObjectLabels l;
    std::int32_t* ints[5] = {&l.plant, &l.leaf, &l.shoot, &l.rank, &l.node};
    for (int k = 0; k < 5; ++k)
        if (hasInt_[k]) *ints[k] = context_.objectDataInt(id, kIntLabels[k]).value_or(-1);
    if (hasAge_) l.age = context_.objectDataFloat(id, "age").value_or(-1.0f);
    if (hasOrgan_) l.organ = organCode(context_.objectDataString(id, "organ").value_or(""));
    return l;
}

std::string organOf(const Context& context, ObjectID id) {
    return context.objectDataString(id, "organ").value_or(std::string());
}

}  // namespace plantarch::io

namespace plantarch {

const std::vector<OrganLabelColor>& organLabelColors() {
    static const std::vector<OrganLabelColor> table = {
        {"internode", {230, 25, 75}},      {"petiole", {245, 130, 48}},
        {"leaf", {60, 180, 75}},           {"peduncle", {255, 225, 25}},
        {"flower_closed", {240, 50, 230}}, {"flower_open", {145, 30, 180}},
        {"fruit", {0, 130, 200}},          {"ground", {128, 128, 128}},
        {"obstacle", {70, 240, 240}},
    };
    return table;
}

std::array<std::uint8_t, 3> organLabelColor(std::string_view organ) {
    for (const auto& entry : organLabelColors())
        if (entry.organ == organ) return entry.rgb;
    return {255, 255, 255};
}

void smoothNormals(const ObjectView& object, std::vector<vec3>& normals) {
    const auto& p = object.positions;
    normals.assign(p.size(), vec3(0.0f));
    const auto& idx = object.indices;
    for (std::size_t t = 0; t + 2 < idx.size(); t += 3) {
        const std::uint32_t a = idx[t], b = idx[t + 1], c = idx[t + 2];
        // |cross| is twice the triangle's area, so the sum is area-weighted.
        const vec3 n = glm::cross(p[b] - p[a], p[c] - p[a]);
        normals[a] += n;
        normals[b] += n;
        normals[c] += n;
    }
    for (vec3& n : normals) {
        const float length = glm::length(n);
        n = (length > 0.0f && std::isfinite(length)) ? n / length : vec3(0.0f, 0.0f, 1.0f);
    }
}

}  // namespace plantarch
