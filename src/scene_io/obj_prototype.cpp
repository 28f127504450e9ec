#include <cmath>

#include "core/value_text.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/OrganPrototypes.h"

namespace plantarch {

bool isOBJPrototypeName(const std::string& name) {
    return name.size() > 4 && name.compare(name.size() - 4, 4, ".obj") == 0;
}

OrganPrototype loadOBJPrototype(const std::string& path, bool normalize) {
    Context ctx;
    // Only the geometry and materials make the prototype: no labels, no recorded IDs.
    const std::vector<ObjectID> ids = readOBJ(ctx, path, {.labels = false});
    AABB box;
    for (ObjectID id : ids) box.add(ctx.objectBoundingBox(id));
    const float length = box.extent().x;
    if (!(length > 0.0f))
        throw Error(
            "OBJ prototype has no extent along +x (the organ axis)",
            {.file = path, .value = "length " + text::formatFloat(length), .validRange = "> 0"});
    mat4 xf(1.0f);
    if (normalize) {
        // Base (smallest x) to the origin, centred on the axis there, unit length.
        vec3 base(box.min.x, 0.0f, 0.0f);
        AABB atBase;
        for (ObjectID id : ids)
            for (const vec3& p : ctx.object(id).positions)
                if (p.x <= box.min.x + 0.02f * length) atBase.add(p);
        base.y = atBase.center().y;
        base.z = atBase.center().z;
        const float s = 1.0f / length;
        xf = mat4(s, 0, 0, 0, 0, s, 0, 0, 0, 0, s, 0, -base.x * s, -base.y * s, -base.z * s, 1);
    } else if (std::abs(box.min.x) > 0.01f || std::abs(box.max.x - 1.0f) > 0.01f) {
        throw Error(
            "OBJ prototype does not follow the convention (length 1 along +x from the "
            "origin); set normalize_OBJ_model to fit it",
            {.file = path,
             .value =
                 "x from " + text::formatFloat(box.min.x) + " to " + text::formatFloat(box.max.x),
             .validRange = "x from 0 to 1 (within 0.01)"});
    }
    OrganPrototype proto;
    for (ObjectID id : ids) {
        PrototypePart part{ctx.objectMesh(id), ctx.material(ctx.objectMaterial(id))};
        part.mesh.transform(xf);
        proto.push_back(std::move(part));
    }
    return proto;
}

}  // namespace plantarch
