// Organs followed through frames, each frame's geometry fitted as a similarity transform of a
// stored shape (organ_tracks.h). The rotation is Horn's closed form: the unit quaternion that
// best maps one centred point set onto another is the eigenvector of the largest eigenvalue of
// a symmetric 4x4 matrix built from their cross-covariance (core/symmetric_eigen.h).

#include "scene_io/organ_tracks.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <span>
#include <tuple>

#include "core/symmetric_eigen.h"

namespace plantarch::io {

namespace {

using Matrix4 = std::array<std::array<double, 4>, 4>;

// The eigenvector of the largest eigenvalue of a symmetric 4x4 matrix.
std::array<double, 4> largestEigenvector(const Matrix4& a) {
    const SymmetricEigen<4> e = symmetricEigen<4>(a);
    std::size_t best = 0;
    for (std::size_t i = 1; i < 4; ++i)
        if (e.values[i] > e.values[best]) best = i;
    return e.vectors[best];
}

// Largest coordinate extent of a point set.
float extent(std::span<const vec3> points) {
    vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const vec3& p : points) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    return points.empty() ? 0.0f : std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
}

// The placement of `shape` (stored about `centre`) that shows `target`, vertex for vertex, or
// none when no similarity transform reproduces it within the tolerance.
std::optional<OrganPlacement> fit(std::span<const vec3> shape, vec3 centre,
                                  std::span<const vec3> target) {
    const std::size_t n = shape.size();
    if (n == 0 || n != target.size()) return std::nullopt;
    glm::dvec3 ms(0.0), mt(0.0);
    for (std::size_t i = 0; i < n; ++i) {
        ms += glm::dvec3(shape[i]);
        mt += glm::dvec3(target[i]);
    }
    ms /= double(n);
    mt /= double(n);
    double m[3][3] = {}, norm = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec3 a = glm::dvec3(shape[i]) - ms, b = glm::dvec3(target[i]) - mt;
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) m[r][c] += a[r] * b[c];
        norm += glm::dot(a, a);
    }
    glm::dquat q(1.0, 0.0, 0.0, 0.0);
    double scale = 0.0;
    if (norm > 0.0) {
        const double sxx = m[0][0], sxy = m[0][1], sxz = m[0][2], syx = m[1][0], syy = m[1][1],
                     syz = m[1][2], szx = m[2][0], szy = m[2][1], szz = m[2][2];
        const Matrix4 k = {{{sxx + syy + szz, syz - szy, szx - sxz, sxy - syx},
                            {syz - szy, sxx - syy - szz, sxy + syx, szx + sxz},
                            {szx - sxz, sxy + syx, -sxx + syy - szz, syz + szy},
                            {sxy - syx, szx + sxz, syz + szy, -sxx - syy + szz}}};
        const std::array<double, 4> e = largestEigenvector(k);
        q = glm::normalize(glm::dquat(e[0], e[1], e[2], e[3]));
        if (q.w < 0.0) q = -q;  // one sign for one rotation
        double dot = 0.0;
        for (std::size_t i = 0; i < n; ++i)
            dot += glm::dot(glm::dvec3(target[i]) - mt, q * (glm::dvec3(shape[i]) - ms));
        scale = std::max(dot / norm, 0.0);
    }
    OrganPlacement p;
    p.rotation = glm::quat(q);
    p.scale = float(scale);
    p.translation = vec3(mt - scale * (q * (ms - glm::dvec3(centre))));
    // Checked in floats, as a viewer computes it.
    // 1e-5 of the organ's size, and a few float steps of its coordinates (the frame's own
    // vertices carry rounding of that size from the transforms that placed them).
    float reach = 0.0f;
    for (const vec3& v : target)
        reach = std::max({reach, std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    const float tolerance =
        1e-5f * std::max(extent(target), extent(shape) * p.scale) + 2e-6f * reach + 1e-7f;
    for (std::size_t i = 0; i < n; ++i) {
        const vec3 shown = p.translation + p.scale * (p.rotation * (shape[i] - centre));
        const vec3 d = glm::abs(shown - target[i]);
        if (std::max({d.x, d.y, d.z}) > tolerance) return std::nullopt;
    }
    return p;
}

// What must be equal for two objects to share a shape or its topology.
struct Signature {
    std::size_t vertices, triangles;
    std::size_t material;  // index among the frames' distinct materials
    std::int32_t plant;
    std::uint8_t organ;
    bool uvs;
    auto operator<=>(const Signature&) const = default;
};

bool sameTopology(const ObjectView& a, const ObjectView& b, bool uvs) {
    return std::equal(a.indices.begin(), a.indices.end(), b.indices.begin(), b.indices.end()) &&
           (!uvs || std::equal(a.uvs.begin(), a.uvs.end(), b.uvs.begin(), b.uvs.end()));
}

// A hash of an object's indices and UVs (FNV-1a over their bytes).
std::uint64_t topologyHash(const ObjectView& o, bool uvs) {
    std::uint64_t h = 1469598103934665603ull;
    auto add = [&h](const void* data, std::size_t bytes) {
        const auto* b = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < bytes; ++i) h = (h ^ b[i]) * 1099511628211ull;
    };
    add(o.indices.data(), o.indices.size_bytes());
    if (uvs) add(o.uvs.data(), o.uvs.size_bytes());
    return h;
}

// The shapes to try for a new placement before storing a new one, newest first.
constexpr std::size_t kShapesTried = 8;

}  // namespace

std::string organName(const OrganTrack& t) {
    std::string name(kOrganLabels[t.labels.organ]);
    if (t.labels.shoot >= 0) name += "_s" + std::to_string(t.labels.shoot);
    if (t.labels.node >= 0) name += "_n" + std::to_string(t.labels.node);
    if (t.labels.leaf >= 0) name += "_l" + std::to_string(t.labels.leaf);
    if (t.ordinal > 0) name += "_" + std::to_string(t.ordinal + 1);
    return name;
}

OrganTracks trackOrgans(const std::vector<const Context*>& frames, bool includeHidden,
                        bool instancing, const std::function<bool(const Material&)>& uvsMatter) {
    OrganTracks out;
    using Key = std::tuple<std::int32_t, std::uint8_t, std::int32_t, std::int32_t, std::int32_t,
                           std::int32_t>;
    std::map<Key, std::size_t> trackOf;
    std::map<Signature, std::vector<std::size_t>> shapesOf;  // newest last
    // The first shape of each topology, by signature and topology hash.
    std::map<std::pair<Signature, std::uint64_t>, std::vector<std::size_t>> topologies;
    auto view = [&](const OrganShape& s) { return frames[s.frame]->object(s.id); };
    std::vector<Signature> signatures;  // of each shape
    std::vector<Material> materials;    // distinct materials of all frames
    auto materialIndex = [&](const Material& m) {
        const auto at = std::find(materials.begin(), materials.end(), m);
        if (at != materials.end()) return std::size_t(at - materials.begin());
        materials.push_back(m);
        return materials.size() - 1;
    };
    // From the last frame back: an organ's shape is taken where it is largest, so the rounding
    // in its stored vertices shrinks, never grows, as it is scaled down to earlier frames.
    for (std::uint32_t f = std::uint32_t(frames.size()); f-- > 0;) {
        const Context& ctx = *frames[f];
        const LabelReader labelsOf(ctx);
        std::map<std::tuple<std::int32_t, std::uint8_t, std::int32_t, std::int32_t, std::int32_t>,
                 std::int32_t>
            ordinals;
        for (ObjectID id : exportedObjects(ctx, includeHidden)) {
            const ObjectLabels l = labelsOf(id);
            const std::int32_t ordinal = ordinals[{l.plant, l.organ, l.shoot, l.node, l.leaf}]++;
            const Key key{l.plant, l.organ, l.shoot, l.node, l.leaf, ordinal};
            auto [at, fresh] = trackOf.emplace(key, out.tracks.size());
            if (fresh) {
                OrganTrack track;
                track.frames.resize(frames.size());
                track.ordinal = ordinal;
                track.labels = l;
                track.lastFrame = f;
                track.lastID = id;
                out.tracks.push_back(std::move(track));
            }
            const std::size_t t = at->second;
            OrganTrack& track = out.tracks[t];
            const ObjectView o = ctx.object(id);
            const Material& material = ctx.material(o.material);
            const bool uvs = uvsMatter(material);
            const Signature sig{
                o.positions.size(), o.triangleCount(), materialIndex(material), l.plant, l.organ,
                !o.uvs.empty()};
            // Candidates: the shape this track placed last, then (with instancing) others.
            std::vector<std::size_t> candidates;
            for (std::uint32_t g = f + 1; g < frames.size(); ++g)
                if (track.frames[g]) {
                    candidates.push_back(track.frames[g]->shape);
                    break;
                }
            std::vector<std::size_t>& group = shapesOf[sig];
            if (instancing)
                for (std::size_t k = group.size(); k-- > 0 && candidates.size() <= kShapesTried;)
                    if (std::find(candidates.begin(), candidates.end(), group[k]) ==
                        candidates.end())
                        candidates.push_back(group[k]);
            std::optional<OrganPlacement> placed;
            for (std::size_t s : candidates) {
                const ObjectView shape = view(out.shapes[s]);
                if (signatures[s] != sig || !sameTopology(shape, o, uvs)) continue;
                placed = fit(shape.positions, out.shapes[s].centre, o.positions);
                if (placed) {
                    placed->shape = s;
                    break;
                }
            }
            if (!placed) {  // a new shape, about the centre of its bounding box
                OrganShape shape{f, id, vec3(0.0f), out.shapes.size(), {}};
                AABB box;
                for (const vec3& p : o.positions) box.add(p);
                shape.centre = box.empty() ? vec3(0.0f) : box.center();
                std::vector<std::size_t>& roots = topologies[{sig, topologyHash(o, uvs)}];
                const auto root = std::find_if(roots.begin(), roots.end(), [&](std::size_t s) {
                    return sameTopology(view(out.shapes[s]), o, uvs);
                });
                if (root != roots.end())
                    shape.topology = *root;
                else
                    roots.push_back(out.shapes.size());
                placed = OrganPlacement{out.shapes.size(), shape.centre, {1, 0, 0, 0}, 1.0f};
                group.push_back(out.shapes.size());
                signatures.push_back(sig);
                out.shapes.push_back(std::move(shape));
            }
            std::vector<std::size_t>& users = out.shapes[placed->shape].users;
            if (std::find(users.begin(), users.end(), t) == users.end()) users.push_back(t);
            track.frames[f] = placed;
        }
    }
    return out;
}

}  // namespace plantarch::io
