#pragma once
// The soft obstacles of the collision scene in a hashed uniform grid, for the one query
// perception cones make: every triangle within a radius of a point.
//
// Triangles are binned by the centre of their bounding sphere in cells about as large as the
// look-ahead distance; a query visits the cells near its sphere and keeps the triangles whose
// bounding spheres reach it. Triangles larger than a cell (walls, the ground) are kept in a
// list every query scans. The grid is rebuilt from the plants' proxies at each refresh by a
// counting sort, which costs less than keeping a tree up to date for plants that all grow.

#include <cstdint>
#include <vector>

#include "plantarch/Mesh.h"

namespace plantarch::collision {

struct Ignore;

/// A triangle of the scene: its three consecutive corners, the plant it belongs to (plant
/// ID + 1; 0 for obstacle objects) and its organ tag.
struct SoftTriangle {
    const vec3* corners = nullptr;
    unsigned owner = 0;
    std::uint64_t tag = 0;
};

/// Triangles a query gathered, in blocks of four with each coordinate of each corner in a row
/// of its own (x0 of the four triangles, then y0, ..., z2), so the perception cones can work
/// on four triangles at once. Rows past size() hold zeros.
class TriangleBatch {
public:
    static constexpr std::size_t kFloatsPerBlock = 36;
    void clear() {
        size_ = 0;
        data_.clear();
    }
    void push(const vec3* corners) {
        const std::size_t lane = size_ & 3;
        if (lane == 0) data_.resize(data_.size() + kFloatsPerBlock, 0.0f);
        float* block = data_.data() + data_.size() - kFloatsPerBlock;
        for (int c = 0; c < 3; ++c)
            for (int k = 0; k < 3; ++k) block[(3 * c + k) * 4 + lane] = corners[c][k];
        ++size_;
    }
    std::size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }
    std::size_t blocks() const { return (size_ + 3) / 4; }
    /// Row `row` (corner row / 3, coordinate row % 3) of block `b`: four floats.
    const float* row(std::size_t b, int row) const { return data_.data() + b * kFloatsPerBlock + 4 * row; }
    /// Corner `c` of triangle `t`.
    vec3 corner(std::size_t t, int c) const {
        const float* r = row(t / 4, 3 * c);
        const std::size_t lane = t & 3;
        return {r[lane], r[4 + lane], r[8 + lane]};
    }

private:
    std::vector<float> data_;
    std::size_t size_ = 0;
};

/// Bounding spheres of a triangle soup (centre, radius), three corners per triangle.
void boundingSpheres(const std::vector<vec3>& soup, std::vector<glm::vec4>& spheres);

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
    /// cell get a mark that keeps them out of the cells).
    static void cellKeys(const std::vector<glm::vec4>& spheres, float cell,
                         std::vector<std::uint64_t>& keys);
    /// Rebuilds the grid over `sources` with cells of `cell` metres.
    void build(const std::vector<Source>& sources, float cell);
    /// Appends to `out` the triangles whose bounding spheres come within `radius` of
    /// `centre`, except the organs in `ignore` and, given `front` (unit), those whose spheres
    /// lie wholly behind the plane through `centre` facing it; in a fixed order.
    void near(vec3 centre, float radius, const Ignore* ignore, TriangleBatch& out,
              const vec3* front = nullptr) const;
    /// Every triangle, except the organs in `ignore`.
    template <class F>
    void forEach(const Ignore* ignore, F&& f) const {
        for (const auto* list : {&small_, &large_})
            for (const SoftTriangle& t : *list)
                if (!ignored(t, ignore)) f(t.corners);
    }
    std::size_t size() const { return small_.size() + large_.size(); }

private:
    static constexpr float kMinCell = 1e-4f;
    static constexpr std::uint64_t kLarge = ~std::uint64_t(0);
    static bool ignored(const SoftTriangle& t, const Ignore* ignore);
    std::size_t bucketOf(std::uint64_t key) const { return std::size_t((key * 0x9e3779b97f4a7c15ULL) >> shift_); }

    float cell_ = 1.0f, inverse_ = 1.0f, maxRadius_ = 0.0f;
    int shift_ = 63;
    std::vector<std::uint32_t> start_;      ///< bucket b: [start_[b], start_[b + 1])
    std::vector<std::uint32_t> fill_;       ///< scratch of build
    std::vector<std::uint64_t> keys_;       ///< cell key per small triangle (bucket order), padded
    /// Bounding spheres of the small triangles (bucket order): centres' x, y, z and radii in
    /// rows of their own, padded with four far-away spheres (so tests go four at a time).
    std::vector<float> sphereRows_[4];
    std::vector<SoftTriangle> small_;       ///< bucket order
    std::vector<vec3> corners_;             ///< of small_, copied in bucket order (locality)
    std::vector<glm::vec4> largeSpheres_;
    std::vector<SoftTriangle> large_;
};

}  // namespace plantarch::collision
