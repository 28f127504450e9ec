#pragma once
// The corners of an object's triangles, in order: what mesh readers are checked against.

#include <vector>

#include "plantarch/Context.h"

namespace plantarch::testing {

inline std::vector<vec3> objectCorners(const Context& ctx, ObjectID id) {
    std::vector<vec3> out;
    const ObjectView v = ctx.object(id);
    for (std::uint32_t i : v.indices) out.push_back(v.positions[i]);
    return out;
}

}  // namespace plantarch::testing
