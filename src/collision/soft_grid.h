#pragma once
// The soft obstacles of the collision scene in a hashed uniform grid, for the one query
// perception cones make: every triangle within a radius of a point.
//
// Two consecutive triangles (a, b, c) and (a, c, d) of one organ, as a leaf's outline is
// made, are kept as one quad (a, b, c, d); a lone triangle is a quad whose last two corners
// are the same. Quads are binned by the centre of their bounding sphere in cells somewhat
// larger than the look-ahead distance (World::gridCell); a query visits the cells near its
// sphere and keeps the triangles whose bounding spheres reach it. Triangles larger than a
// cell (walls, the ground) are kept in a list every query scans. The grid is rebuilt from the
// plants' proxies at each refresh by a counting sort, which costs less than keeping a tree up
// to date for plants that all grow.

#include <cstdint>
#include <vector>

#include "plantarch/Mesh.h"

namespace plantarch::collision {

struct Ignore;

/// A quad of the scene (two triangles, or one): its first triangle's three consecutive
/// corners (a quad's fourth corner is the third of the triangle after), the plant it belongs
/// to (plant ID + 1; 0 for obstacle objects), its organ tag and whether it is two triangles.
struct SoftTriangle {
    const vec3* corners = nullptr;
    unsigned owner = 0;
    bool quad = false;
    std::uint64_t tag = 0;
    vec3 last() const { return quad ? corners[5] : corners[2]; }
};

/// Quads a query gathered, in blocks of four with each coordinate of each corner in a row of
/// its own (x of corner a of the four quads, then y, z, then corner b, ..., corner d), so the
/// perception cones can work on four at once. Rows past size() hold zeros.
class TriangleBatch {
public:
    static constexpr std::size_t kFloatsPerBlock = 48;
    void clear() {
        size_ = 0;
        data_.clear();
    }
    void push(const vec3* corners) {
        const std::size_t lane = size_ & 3;
        if (lane == 0) data_.resize(data_.size() + kFloatsPerBlock, 0.0f);
        float* block = data_.data() + data_.size() - kFloatsPerBlock;
        for (int c = 0; c < 4; ++c)
            for (int k = 0; k < 3; ++k) block[(3 * c + k) * 4 + lane] = corners[c][k];
        ++size_;
    }
    /// Appends zero blocks up to a whole multiple of `n` blocks, so that blocks can be read n
    /// at a time (after the last push: the next one must follow clear()).
    void padBlocks(std::size_t n) {
        const std::size_t want = (blocks() + n - 1) / n * n;
        data_.resize(want * kFloatsPerBlock, 0.0f);
    }
    std::size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }
    std::size_t blocks() const { return (size_ + 3) / 4; }
    /// Row `row` (corner row / 3, coordinate row % 3) of block `b`: four floats.
    const float* row(std::size_t b, int row) const {
        return data_.data() + b * kFloatsPerBlock + 4 * row;
    }
    /// Corner `c` (0 to 3) of quad `t`.
    vec3 corner(std::size_t t, int c) const {
        const float* r = row(t / 4, 3 * c);
        const std::size_t lane = t & 3;
        return {r[lane], r[4 + lane], r[8 + lane]};
    }

private:
    std::vector<float> data_;
    std::size_t size_ = 0;
};

/// Bounding spheres of a triangle soup (centre, radius), three corners per triangle: a
/// triangle that makes a quad with the one before it (same tag, if `tags` are given) gets a
/// negative radius, and that one the quad's sphere.
void boundingSpheres(const std::vector<vec3>& soup, std::vector<glm::vec4>& spheres,
                     const std::vector<std::uint64_t>* tags = nullptr);

class SoftGrid {
public:
    /// One block of triangles: corners, their spheres and cell keys (cellKeys, for the cell
    /// size the grid is built with), their tags (null: obstacle objects).
    struct Source {
        const std::vector<vec3>* soup = nullptr;
        const std::vector<glm::vec4>* spheres = nullptr;
        const std::vector<std::uint64_t>* keys = nullptr;
        const std::vector<std::uint64_t>* tags = nullptr;
        unsigned owner = 0;
    };

    /// The cell of each sphere's centre for cells of `cell` metres (spheres larger than a
    /// cell get a mark that keeps them out of the cells, the second triangles of quads one
    /// that keeps them out of the grid).
    static void cellKeys(const std::vector<glm::vec4>& spheres, float cell,
                         std::vector<std::uint64_t>& keys);
    /// Rebuilds the grid over `sources` with cells of `cell` metres, on up to `threads`
    /// threads (the same grid for any number).
    void build(const std::vector<Source>& sources, float cell, int threads = 1);
    /// Appends to `out` the triangles whose bounding spheres come within `radius` of
    /// `centre`, except the organs in `ignore` and, given `front` (unit), those whose spheres
    /// lie wholly behind the plane through `centre` facing it; in a fixed order.
    void near(vec3 centre, float radius, const Ignore* ignore, TriangleBatch& out,
              const vec3* front = nullptr) const;
    /// Every triangle (three corners), except the organs in `ignore`.
    template <class F>
    void forEach(const Ignore* ignore, F&& f) const {
        for (const auto* list : {&small_, &large_})
            for (const SoftTriangle& t : *list) {
                if (ignored(t, ignore)) continue;
                f(t.corners);
                if (t.quad) {
                    const vec3 second[3] = {t.corners[0], t.corners[2], t.corners[5]};
                    f(second);
                }
            }
    }
    std::size_t size() const { return small_.size() + large_.size(); }

private:
    static constexpr float kMinCell = 1e-4f;
    static constexpr std::uint64_t kLarge = ~std::uint64_t(0);
    static constexpr std::uint64_t kSecond = ~std::uint64_t(0) - 1;  ///< a quad's second triangle
    static bool ignored(const SoftTriangle& t, const Ignore* ignore);
    std::size_t bucketOf(std::uint64_t key) const {
        return std::size_t((key * 0x9e3779b97f4a7c15ULL) >> shift_);
    }

    float cell_ = 1.0f, inverse_ = 1.0f, maxRadius_ = 0.0f;
    int shift_ = 63;
    std::vector<std::uint32_t> start_;                ///< bucket b: [start_[b], start_[b + 1])
    std::vector<std::vector<std::uint32_t>> counts_;  ///< scratch of build: per run and bucket
    std::vector<std::uint64_t> keys_;  ///< cell key per small triangle (bucket order), padded
    /// Bounding spheres of the small triangles (bucket order): centres' x, y, z and radii in
    /// rows of their own, padded with four far-away spheres (so tests go four at a time).
    std::vector<float> sphereRows_[4];
    std::vector<SoftTriangle> small_;  ///< bucket order
    std::vector<vec3> corners_;        ///< of small_, four each, in bucket order (locality)
    std::vector<glm::vec4> largeSpheres_;
    std::vector<SoftTriangle> large_;
};

}  // namespace plantarch::collision
