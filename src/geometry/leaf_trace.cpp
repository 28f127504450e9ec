// Leaf outlines traced from a PNG's alpha channel: marching squares on the alpha field at
// 0.5 with sub-pixel crossings, the largest loop (the outer boundary of the largest opaque
// region), Douglas-Peucker, then the map into the prototype frame.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <tuple>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "core/image_file.h"
#include "geometry/polygon_mesh.h"
#include "plantarch/Error.h"
#include "plantarch/LeafShapes.h"

namespace plantarch {

namespace {

using glm::dvec2;
constexpr double kThreshold = 0.5;

struct AlphaImage {
    int width = 0, height = 0;
    std::vector<float> alpha;  // row 0 at the top
    // Alpha at sample (i, j), zero outside the image.
    double at(int i, int j) const {
        if (i < 0 || j < 0 || i >= width || j >= height) return 0.0;
        return alpha[std::size_t(j) * width + i];
    }
};

AlphaImage loadAlpha(const std::string& path) {
    const io::DecodedImage image = io::readTextureFile(path);
    if (image.fileChannels != 2 && image.fileChannels != 4)
        throw Error("leaf image has no alpha channel (its alpha gives the leaf outline)",
                    {.file = path});
    const unsigned char* data = image.pixels.data();
    const int w = image.width, h = image.height;
    AlphaImage img{w, h, std::vector<float>(std::size_t(w) * h)};
    std::size_t opaque = 0;
    for (std::size_t i = 0; i < img.alpha.size(); ++i) {
        img.alpha[i] = data[4 * i + 3] / 255.0f;
        if (img.alpha[i] >= kThreshold) ++opaque;
    }
    if (opaque == 0) throw Error("leaf image is fully transparent: no outline", {.file = path});
    if (opaque == img.alpha.size())
        throw Error("leaf image is fully opaque: its alpha channel does not outline a leaf",
                    {.file = path});
    return img;
}

// ---- marching squares ------------------------------------------------------------------

// Crossings live on the edges between neighbouring samples; an edge id names each one.
struct Crossing {
    dvec2 point;
    std::array<std::int64_t, 2> link{-1, -1};
};

class Tracer {
public:
    explicit Tracer(const AlphaImage& img) : img_(img), stride_(img.width + 2) {}

    std::vector<std::vector<dvec2>> loops() {
        for (int j = -1; j < img_.height; ++j)
            for (int i = -1; i < img_.width; ++i) cell(i, j);
        // Start every loop at its smallest edge id so the result does not depend on the
        // hash table's order.
        std::vector<std::int64_t> ids;
        ids.reserve(crossings_.size());
        for (const auto& entry : crossings_) ids.push_back(entry.first);
        std::sort(ids.begin(), ids.end());
        std::vector<std::vector<dvec2>> out;
        for (std::int64_t id : ids) {
            if (crossings_.at(id).link[0] < 0 || visited_.count(id)) continue;
            std::vector<dvec2> loop;
            std::int64_t prev = -1, cur = id;
            while (cur >= 0 && !visited_.count(cur)) {
                visited_.insert(cur);
                const Crossing& x = crossings_.at(cur);
                loop.push_back(x.point);
                const std::int64_t next = x.link[0] != prev ? x.link[0] : x.link[1];
                prev = cur;
                cur = next;
            }
            if (loop.size() >= 3) out.push_back(std::move(loop));
        }
        return out;
    }

private:
    // Sample (i, j) sits at the pixel centre (i + 0.5, j + 0.5), y down.
    std::int64_t horizontalEdge(int i, int j) const {
        return 2 * (std::int64_t(j + 1) * stride_ + (i + 1));
    }
    std::int64_t verticalEdge(int i, int j) const { return horizontalEdge(i, j) + 1; }

    dvec2 crossing(int i0, int j0, int i1, int j1) const {
        const double a = img_.at(i0, j0), b = img_.at(i1, j1);
        const double t = std::clamp((kThreshold - a) / (b - a), 0.0, 1.0);
        return {i0 + 0.5 + t * (i1 - i0), j0 + 0.5 + t * (j1 - j0)};
    }

    void link(std::int64_t e0, dvec2 p0, std::int64_t e1, dvec2 p1) {
        for (auto [from, to, p] : {std::tuple{e0, e1, p0}, std::tuple{e1, e0, p1}}) {
            Crossing& c = crossings_[from];
            c.point = p;
            (c.link[0] < 0 ? c.link[0] : c.link[1]) = to;
        }
    }

    void cell(int i, int j) {
        const double tl = img_.at(i, j), tr = img_.at(i + 1, j);
        const double br = img_.at(i + 1, j + 1), bl = img_.at(i, j + 1);
        const int mask = (tl >= kThreshold ? 1 : 0) | (tr >= kThreshold ? 2 : 0) |
                         (br >= kThreshold ? 4 : 0) | (bl >= kThreshold ? 8 : 0);
        if (mask == 0 || mask == 15) return;
        const std::int64_t top = horizontalEdge(i, j), bottom = horizontalEdge(i, j + 1);
        const std::int64_t left = verticalEdge(i, j), right = verticalEdge(i + 1, j);
        auto pt = [&](std::int64_t e) {
            if (e == top) return crossing(i, j, i + 1, j);
            if (e == bottom) return crossing(i, j + 1, i + 1, j + 1);
            if (e == left) return crossing(i, j, i, j + 1);
            return crossing(i + 1, j, i + 1, j + 1);
        };
        auto seg = [&](std::int64_t a, std::int64_t b) { link(a, pt(a), b, pt(b)); };
        const bool centreIn = 0.25 * (tl + tr + br + bl) >= kThreshold;
        switch (mask) {
            case 1:
            case 14:
                seg(left, top);
                break;
            case 2:
            case 13:
                seg(top, right);
                break;
            case 3:
            case 12:
                seg(left, right);
                break;
            case 4:
            case 11:
                seg(right, bottom);
                break;
            case 6:
            case 9:
                seg(top, bottom);
                break;
            case 7:
            case 8:
                seg(left, bottom);
                break;
            case 5:
                if (centreIn)
                    seg(top, right), seg(bottom, left);
                else
                    seg(left, top), seg(right, bottom);
                break;
            case 10:
                if (centreIn)
                    seg(left, top), seg(right, bottom);
                else
                    seg(top, right), seg(bottom, left);
                break;
            default:
                break;
        }
    }

    const AlphaImage& img_;
    std::int64_t stride_;
    std::unordered_map<std::int64_t, Crossing> crossings_;
    std::unordered_set<std::int64_t> visited_;
};

// Douglas-Peucker on a closed loop: split at the vertex farthest from the first one.
std::vector<dvec2> simplifyLoop(const std::vector<dvec2>& loop, double tolerance) {
    std::size_t far = 0;
    for (std::size_t i = 1; i < loop.size(); ++i)
        if (glm::length(loop[i] - loop[0]) > glm::length(loop[far] - loop[0])) far = i;
    std::vector<dvec2> first(loop.begin(), loop.begin() + far + 1);
    std::vector<dvec2> second(loop.begin() + far, loop.end());
    second.push_back(loop[0]);
    std::vector<dvec2> out = polygon::simplifyPolyline(first, tolerance);
    const std::vector<dvec2> rest = polygon::simplifyPolyline(second, tolerance);
    out.insert(out.end(), rest.begin() + 1, rest.end() - 1);
    return out;
}

}  // namespace

TracedLeafOutline traceLeafImage(const std::string& path) {
    const AlphaImage img = loadAlpha(path);
    std::vector<std::vector<dvec2>> loops = Tracer(img).loops();
    if (loops.empty())
        throw Error("leaf image has no outline in its alpha channel", {.file = path});
    const auto largest =
        std::max_element(loops.begin(), loops.end(), [](const auto& a, const auto& b) {
            return std::abs(polygon::signedArea(a)) < std::abs(polygon::signedArea(b));
        });
    // Simplify to half a pixel, or 0.1 % of the leaf's length on large images; fall back to
    // finer tolerances if simplification made the loop touch itself.
    double width = 0.0;
    {
        double lo = 1e300, hi = -1e300;
        for (const dvec2& p : *largest) lo = std::min(lo, p.x), hi = std::max(hi, p.x);
        width = hi - lo;
    }
    std::vector<dvec2> loop;
    for (double tolerance : {std::max(0.5, 0.001 * width), 0.25, 0.0}) {
        loop = tolerance > 0 ? simplifyLoop(*largest, tolerance) : *largest;
        if (loop.size() >= 3 && polygon::isSimple(loop)) break;
    }
    if (loop.size() < 3) throw Error("leaf image outline is too small", {.file = path});

    // Pixels to the prototype frame: the opaque extent spans x in [0, 1], y up, the image's
    // vertical centre on the midrib.
    double lo = 1e300, hi = -1e300, top = 1e300, bottom = -1e300;
    for (const dvec2& p : loop) {
        lo = std::min(lo, p.x);
        hi = std::max(hi, p.x);
        top = std::min(top, p.y);
        bottom = std::max(bottom, p.y);
    }
    const double length = hi - lo;
    if (!(length > 0)) throw Error("leaf image outline has no width", {.file = path});
    TracedLeafOutline out;
    std::vector<dvec2> mapped;
    mapped.reserve(loop.size());
    for (const dvec2& p : loop)
        mapped.push_back({(p.x - lo) / length, (0.5 * img.height - p.y) / length});
    if (polygon::signedArea(mapped) < 0) std::reverse(mapped.begin(), mapped.end());
    for (const dvec2& p : mapped) out.outline.emplace_back(float(p.x), float(p.y));
    out.uAtBase = float(lo / img.width);
    out.uPerX = float(length / img.width);
    out.vPerY = float(length / img.height);
    out.aspect_ratio = float((bottom - top) / length);
    return out;
}

std::vector<vec2> traceLeafOutlinePNG(const std::string& path) {
    return traceLeafImage(path).outline;
}

}  // namespace plantarch
