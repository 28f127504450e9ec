// Preparing a Context for ray casting: one Embree BVH over every visible triangle, plus the
// tables that map a hit back to its object, material, texture and organ kind.

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "core/embree_api.h"
#include "core/embree_scene.h"
#include "core/parallel.h"
#include "plantarch/Error.h"
#include "render/render_internal.h"
#include "scene_io/material_textures.h"

namespace plantarch::render_detail {

namespace {

std::uint8_t organIndex(const std::optional<std::string>& organ) {
    if (!organ) return kOrganOther;
    const auto& table = organLabelColors();
    for (std::size_t i = 0; i < table.size(); ++i)
        if (table[i].organ == *organ) return std::uint8_t(i);
    return kOrganOther;
}

/// Discards hits on texels whose alpha is below one half (cut-out leaves).
void alphaMaskFilter(const RTCFilterFunctionNArguments* args) {
    const auto* g = static_cast<const GeometryData*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const unsigned prim = RTCHitN_primID(args->hit, args->N, i);
        const ObjectInfo& obj = g->scene->objects[g->triangleObject[prim]];
        if (obj.texture < 0 || g->uvs.empty()) continue;
        const float u = RTCHitN_u(args->hit, args->N, i);
        const float v = RTCHitN_v(args->hit, args->N, i);
        const std::uint32_t* tri = g->indices + 3 * std::size_t(prim);
        const vec2 uv = (1.0f - u - v) * g->uvs[tri[0]] + u * g->uvs[tri[1]] + v * g->uvs[tri[2]];
        if (g->scene->textures[std::size_t(obj.texture)].alpha(uv) < 0.5f) args->valid[i] = 0;
    }
}

/// Per-object placement in one of the two geometries.
struct Placement {
    ObjectID id;
    std::uint32_t slot;     ///< index into SceneData::objects
    std::uint8_t geometry;  ///< 0 opaque, 1 alpha-masked
    std::size_t firstVertex;
    std::size_t firstTriangle;
};

}  // namespace

SceneData::~SceneData() {
    for (auto& g : geometries)
        if (g.geometry) core::embree().rtcReleaseGeometry(g.geometry);
    if (scene) core::embree().rtcReleaseScene(scene);
}

namespace {

// Reports the BVH build's progress (Embree calls from its build threads) as the last 70 % of
// building the scene, one call at a time and never backwards.
struct BuildMonitor {
    const ProgressCallback* progress;
    std::mutex lock;
    double last = 0.0;

    static bool report(void* self, double done) {
        auto& m = *static_cast<BuildMonitor*>(self);
        const std::lock_guard<std::mutex> hold(m.lock);
        const double fraction = 0.3 + 0.7 * std::clamp(done, 0.0, 1.0);
        if (fraction >= m.last + 0.01 && fraction < 1.0) {
            m.last = fraction;
            (*m.progress)("building scene", fraction);
        }
        return true;  // never cancels the build
    }
};

}  // namespace

void buildScene(SceneData& data, const Context& ctx, const RenderSceneOptions& options) {
    // ---- materials and textures --------------------------------------------------------
    struct MaterialInfo {
        vec3 albedo;
        std::int32_t texture = -1;
        bool inAtlas = false;  // reads its part of the texture atlas through `transform`
        io::UVTransform transform;
    };
    std::vector<MaterialInfo> materials(ctx.materialCount());
    std::map<std::string, std::int32_t> textureIndex;
    for (MaterialID m = 0; m < materials.size(); ++m) {
        const Material& mat = ctx.material(m);
        materials[m].albedo = srgbToLinear(glm::clamp(mat.color, vec3(0.0f), vec3(1.0f)));
        if (mat.texture.empty()) continue;
        auto [it, inserted] = textureIndex.try_emplace(mat.texture, -1);
        if (inserted) {
            try {
                data.textures.push_back(loadTexture(mat.texture));
                it->second = std::int32_t(data.textures.size() - 1);
            } catch (const Error&) {
                if (!options.ignoreMissingTextures) throw;
            }
        }
        materials[m].texture = it->second;
    }
    if (options.appearance.style == MaterialStyle::Textured) {  // procedural textures
        const Context* contexts[] = {&ctx};
        io::MaterialLooks looks(contexts, options.appearance, false, true, {.keepPixels = true});
        const auto first = std::int32_t(data.textures.size());
        for (const io::MaterialMaps& maps : looks.maps())
            data.textures.push_back(
                textureOfPixels(maps.pixels.size, maps.pixels.rows(), maps.pixels.baseColor));
        for (MaterialID m = 0; m < materials.size(); ++m) {
            const io::MaterialLook& look = looks.look(ctx.material(m));
            if (look.maps >= 0) materials[m].texture = first + look.maps;
            materials[m].inAtlas = look.inAtlas;
            materials[m].transform = look.transform;
        }
    }

    // ---- objects -----------------------------------------------------------------------
    const bool organIsString = ctx.objectDataType("organ") == DataType::String;
    std::vector<Placement> placements;
    std::size_t vertexCount[2] = {0, 0}, triangleCount[2] = {0, 0};
    bool textured[2] = {false, false};
    for (ObjectID id : ctx.objectIDs()) {
        if (ctx.isObjectHidden(id)) continue;
        const ObjectView view = ctx.object(id);
        if (view.triangleCount() == 0) continue;
        ObjectInfo info;
        info.id = id;
        const MaterialInfo& mat = materials.at(view.material);
        info.albedo = mat.albedo;
        std::uint8_t geometry = 0;
        if (mat.texture >= 0) {
            const Texture& tex = data.textures[std::size_t(mat.texture)];
            if (view.uvs.empty()) {
                info.albedo = tex.meanColor;  // no UVs: the texture's mean colour
            } else {
                info.texture = mat.texture;
                geometry = tex.hasMask ? 1 : 0;
                textured[geometry] = true;
            }
        }
        if (organIsString) info.organ = organIndex(ctx.objectDataString(id, "organ"));
        placements.push_back({id, std::uint32_t(data.objects.size()), geometry,
                              vertexCount[geometry], triangleCount[geometry]});
        data.objects.push_back(info);
        vertexCount[geometry] += view.positions.size();
        triangleCount[geometry] += view.triangleCount();
        data.bounds.add(ctx.objectBoundingBox(id));
    }
    data.triangles = triangleCount[0] + triangleCount[1];

    // ---- Embree scene and buffers ---------------------------------------------------------
    const RTCBuildQuality quality[] = {RTC_BUILD_QUALITY_LOW, RTC_BUILD_QUALITY_MEDIUM,
                                       RTC_BUILD_QUALITY_HIGH};
    // Robust traversal: no cracks between neighbouring triangles in the label masks.
    data.scene = core::newScene(quality[int(options.bvhQuality)], RTC_SCENE_FLAG_ROBUST);

    float* positions[2] = {nullptr, nullptr};
    std::uint32_t* indices[2] = {nullptr, nullptr};
    for (int k = 0; k < 2; ++k) {
        GeometryData& g = data.geometries[k];
        g.scene = &data;
        if (triangleCount[k] == 0) continue;
        const core::TriangleGeometry made = core::newTriangleGeometry(
            vertexCount[k], triangleCount[k], quality[int(options.bvhQuality)]);
        g.geometry = made.geometry;
        positions[k] = made.positions;
        indices[k] = made.indices;
        core::throwOnEmbreeError("allocating buffers");
        g.positions = positions[k];
        g.vertexCount = vertexCount[k];
        g.indices = indices[k];
        g.triangleObject.resize(triangleCount[k]);
        if (options.smoothNormals) g.normals.assign(vertexCount[k], vec3(0.0f));
        if (textured[k]) g.uvs.assign(vertexCount[k], vec2(0.0f));
    }

    // ---- fill, one object per iteration (objects are independent) -------------------------
    const std::ptrdiff_t n = std::ptrdiff_t(placements.size());
    ParallelErrors errors;
#pragma omp parallel for schedule(dynamic, 64)
    for (std::ptrdiff_t i = 0; i < n; ++i) {
        errors.run(i, [&] {
            const Placement& p = placements[std::size_t(i)];
            const ObjectView view = ctx.object(p.id);
            GeometryData& g = data.geometries[p.geometry];
            float* pos = positions[p.geometry] + 3 * p.firstVertex;
            for (std::size_t v = 0; v < view.positions.size(); ++v) {
                pos[3 * v] = view.positions[v].x;
                pos[3 * v + 1] = view.positions[v].y;
                pos[3 * v + 2] = view.positions[v].z;
            }
            std::uint32_t* idx = indices[p.geometry] + 3 * p.firstTriangle;
            const auto base = std::uint32_t(p.firstVertex);
            for (std::size_t j = 0; j < view.indices.size(); ++j) idx[j] = base + view.indices[j];
            std::fill_n(g.triangleObject.begin() + std::ptrdiff_t(p.firstTriangle),
                        view.triangleCount(), p.slot);
            if (!g.uvs.empty() && !view.uvs.empty()) {
                std::copy(view.uvs.begin(), view.uvs.end(),
                          g.uvs.begin() + std::ptrdiff_t(p.firstVertex));
                const MaterialInfo& mat = materials[view.material];
                if (mat.inAtlas)  // the material's square onto its part of the atlas
                    for (std::size_t v = 0; v < view.uvs.size(); ++v)
                        g.uvs[p.firstVertex + v] = mat.transform.apply(view.uvs[v]);
            }
            if (!g.normals.empty()) {
                // Area-weighted face normals summed at shared vertices.
                vec3* normal = g.normals.data() + p.firstVertex;
                for (std::size_t t = 0; t + 2 < view.indices.size(); t += 3) {
                    const std::uint32_t a = view.indices[t], b = view.indices[t + 1],
                                        c = view.indices[t + 2];
                    const vec3 face = glm::cross(view.positions[b] - view.positions[a],
                                                 view.positions[c] - view.positions[a]);
                    normal[a] += face;
                    normal[b] += face;
                    normal[c] += face;
                }
                for (std::size_t v = 0; v < view.positions.size(); ++v) {
                    const float len = glm::length(normal[v]);
                    normal[v] = len > 0.0f ? normal[v] / len : vec3(0.0f);
                }
            }
        });
    }
    errors.rethrow();

    for (int k = 0; k < 2; ++k) {
        GeometryData& g = data.geometries[k];
        if (!g.geometry) continue;
        core::embree().rtcSetGeometryUserData(g.geometry, &g);
        if (k == 1) {
            core::embree().rtcSetGeometryIntersectFilterFunction(g.geometry, alphaMaskFilter);
            core::embree().rtcSetGeometryOccludedFilterFunction(g.geometry, alphaMaskFilter);
        }
        core::embree().rtcCommitGeometry(g.geometry);
        core::embree().rtcAttachGeometryByID(data.scene, g.geometry, unsigned(k));
    }
    BuildMonitor monitor{&options.progress, {}, 0.3};
    if (options.progress) {
        options.progress("building scene", 0.3);
        core::embree().rtcSetSceneProgressMonitorFunction(data.scene, &BuildMonitor::report,
                                                          &monitor);
    }
    core::embree().rtcCommitScene(data.scene);
    if (options.progress) options.progress("building scene", 1.0);
    core::throwOnEmbreeError("building the BVH");
}

}  // namespace plantarch::render_detail
