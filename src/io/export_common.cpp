#include "io/export_common.h"

#include <cmath>

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

std::string organOf(const Context& context, ObjectID id) {
    return context.objectDataString(id, "organ").value_or(std::string());
}

}  // namespace plantarch::io

namespace plantarch {

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
