// Skinned plants in USD (usd_skin.h): UsdSkel prims from the skeletons the API layer computes
// (exportSkeletons). Joint paths run from the root joint ("root/s0_n0/s0_n1/..."), so a joint's
// path names its ancestors, as UsdSkel asks; bind transforms are the joints' matrices in the
// plant prim's frame at bind pose (the plant as built), rest transforms the same relative to
// each parent. Matrices are written row by row with the translation in the last row, as USD
// keeps them.

#include "scene_io/usd_skin.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/quaternion.hpp>

#include "plantarch/Error.h"
#include "scene_io/export_common.h"

namespace plantarch::io {

namespace {

glm::dmat4 jointMatrix(const GltfJoint& j, glm::dvec3 origin) {
    const glm::dquat q(j.rotation[3], j.rotation[0], j.rotation[1], j.rotation[2]);
    glm::dmat4 m = glm::dmat4(glm::mat3_cast(glm::normalize(q)));
    m[3] = glm::dvec4(glm::dvec3(j.position) - origin, 1.0);
    return m;
}

void number(std::string& out, double v) {
    char p[kMaxFloatChars];
    out.append(p, std::size_t(writeFloat(p, float(v)) - p));
}

void integer(std::string& out, std::int64_t v) {
    char p[24];
    out.append(p, std::size_t(writeInt(p, v) - p));
}

void matrix(std::string& out, const glm::dmat4& m) {
    out += "(";
    for (int r = 0; r < 4; ++r) {
        out += r ? ", (" : "(";
        for (int c = 0; c < 4; ++c) {
            if (c) out += ", ";
            // Exact zeros and ones stay so (no -0 or 0.99999994 from the float round trip).
            number(out, std::abs(m[r][c]) < 1e-12 ? 0.0 : m[r][c]);
        }
        out += ")";
    }
    out += ")";
}

std::string jointToken(const GltfJoint& j) {
    return j.parent < 0 ? "root" : "s" + std::to_string(j.shoot) + "_n" + std::to_string(j.node);
}

const GltfSkinnedObject* bindingOf(const GltfSkeleton& sk, ObjectID id) {
    const auto it =
        std::lower_bound(sk.objects.begin(), sk.objects.end(), id,
                         [](const GltfSkinnedObject& so, ObjectID o) { return so.object < o; });
    return it != sk.objects.end() && it->object == id ? &*it : nullptr;
}

}  // namespace

const GltfSkeleton* usdSkeletonOf(const UsdOptions& options, std::int32_t plant) {
    if (plant < 0) return nullptr;
    for (const GltfSkeleton& sk : options.skeletons)
        if (sk.plant == plant) return &sk;
    return nullptr;
}

void checkUsdSkins(const UsdOptions& options, const Context& context, const std::string& file) {
    for (const GltfSkeleton& sk : options.skeletons) {
        for (std::size_t j = 0; j < sk.joints.size(); ++j) {
            const GltfJoint& jt = sk.joints[j];
            const bool finite = std::isfinite(jt.position.x) && std::isfinite(jt.position.y) &&
                                std::isfinite(jt.position.z);
            if (j == 0 ? jt.parent != -1 : jt.parent < 0 || std::size_t(jt.parent) >= j || !finite)
                throw Error("skeleton of plant " + std::to_string(sk.plant) + ": joint " +
                                std::to_string(j) + " has a bad parent or position",
                            {.file = file,
                             .parameter = "skeletons",
                             .value = jt.name,
                             .validRange = "a finite position, the parent an earlier joint"});
        }
        if (sk.joints.empty())
            throw Error(
                "skeleton of plant " + std::to_string(sk.plant) + " has no joints",
                {.file = file, .parameter = "skeletons", .validRange = "1 to 65535 joints"});
        for (const GltfSkinnedObject& b : sk.objects) {
            if (!context.doesObjectExist(b.object)) continue;
            const ObjectID id = b.object;
            const std::size_t count = context.object(id).positions.size();
            bool fits =
                b.joint < sk.joints.size() && (b.vertices.empty() || b.vertices.size() == count);
            for (std::size_t k = 0; fits && k < b.vertices.size(); ++k)
                for (int i = 0; i < 4; ++i)
                    fits = fits && b.vertices[k].joints[i] < sk.joints.size() &&
                           b.vertices[k].weights[i] >= 0.0f;
            if (!fits)
                throw Error("skeleton of plant " + std::to_string(sk.plant) + ": object " +
                                std::to_string(id) + " is bound to joints it lacks",
                            {.file = file,
                             .parameter = "skeletons",
                             .value = std::to_string(id),
                             .validRange = "joints 0 to " + std::to_string(sk.joints.size() - 1) +
                                           ", one influence per vertex, weights >= 0"});
        }
    }
}

std::string usdSkeleton(const GltfSkeleton& sk, vec3 base) {
    std::vector<std::string> paths;
    for (const GltfJoint& j : sk.joints)
        paths.push_back(j.parent < 0 ? jointToken(j)
                                     : paths[std::size_t(j.parent)] + "/" + jointToken(j));
    std::string out =
        "\n        def Skeleton \"skeleton\"\n        {\n            uniform token[] joints = [";
    for (std::size_t j = 0; j < paths.size(); ++j) out += (j ? ", \"" : "\"") + paths[j] + "\"";
    const glm::dvec3 origin(base);
    out += "]\n            uniform matrix4d[] bindTransforms = [";
    for (std::size_t j = 0; j < sk.joints.size(); ++j) {
        if (j) out += ", ";
        matrix(out, jointMatrix(sk.joints[j], origin));
    }
    out += "]\n            uniform matrix4d[] restTransforms = [";
    for (std::size_t j = 0; j < sk.joints.size(); ++j) {
        const GltfJoint& jt = sk.joints[j];
        glm::dmat4 local = jointMatrix(jt, origin);
        if (jt.parent >= 0)
            local = glm::inverse(jointMatrix(sk.joints[std::size_t(jt.parent)], origin)) * local;
        if (j) out += ", ";
        matrix(out, local);
    }
    out += "]\n        }\n";
    return out;
}

std::string usdSkinBinding(const GltfSkeleton& sk, const Context& context,
                           const std::vector<ObjectID>& objects, const std::string& skeletonPath) {
    std::string indices, weights;
    bool comma = false;
    for (ObjectID id : objects) {
        const GltfSkinnedObject* so = bindingOf(sk, id);
        const std::size_t count = context.object(id).positions.size();
        for (std::size_t k = 0; k < count; ++k) {
            GltfInfluence g;
            if (so && !so->vertices.empty()) {
                g = so->vertices[k];
            } else {
                g.joints[0] = so ? so->joint : 0;
                g.weights[0] = 1.0f;
            }
            for (int i = 0; i < 4; ++i) {
                if (comma) {
                    indices += ", ";
                    weights += ", ";
                }
                comma = true;
                integer(indices, g.joints[i]);
                number(weights, g.weights[i]);
            }
        }
    }
    return "            rel skel:skeleton = <" + skeletonPath +
           ">\n            int[] primvars:skel:jointIndices = [" + indices +
           "] (\n                elementSize = 4\n                interpolation = \"vertex\"\n"
           "            )\n            float[] primvars:skel:jointWeights = [" +
           weights +
           "] (\n                elementSize = 4\n                interpolation = \"vertex\"\n"
           "            )\n";
}

}  // namespace plantarch::io
