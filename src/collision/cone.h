#pragma once
// Perception cones: which of a cone's rays are blocked by the soft obstacles, and the largest
// open gap among them (docs/collision.md, "Soft avoidance").
//
// A cone's rays are stratified over equal solid angles: rings of equal area on the unit
// sphere from the axis out, each split into equal sectors, one jittered ray per cell. The
// jittered sets are made once per cone shape, in the cone's own frame (axis +z); each cone
// takes one of them and a roll about its axis from its own random stream, so no two
// neighbouring cones share their rays while no cone pays for trigonometry.

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "plantarch/Collision.h"
#include "plantarch/Random.h"

namespace plantarch::collision {

class World;
struct Ignore;

/// The jittered ray sets of one cone shape, in the cone's frame (axis +z), cell-major
/// (ring * sectors + sector), as separate x, y, z arrays so tests run several rays at once.
class ConePatterns {
public:
    static constexpr int kSets = 32;
    ConePatterns(unsigned rays, float halfAngleDegrees);

    int rings = 1, sectors = 3;
    float halfAngle = 0.0f;  ///< degrees
    float cosHalf = 1.0f, sinHalf = 0.0f;
    int cells() const { return rings * sectors; }
    /// Each array holds cells() rays and four zeros past them (so rays go four at a time).
    int stride() const { return cells() + 4; }
    const float* x(int set) const {
        return xyz_.data() + std::size_t(set) * 3 * std::size_t(stride());
    }
    const float* y(int set) const { return x(set) + stride(); }
    const float* z(int set) const { return x(set) + 2 * stride(); }

private:
    std::vector<float> xyz_;
};

/// The patterns of a cone shape (made on first use, shared by every thread).
std::shared_ptr<const ConePatterns> conePatterns(unsigned rays, float halfAngleDegrees);

/// A cone's frame and which of its cells are blocked.
struct ConeSample {
    int rings = 1, sectors = 1;
    bool cast = false;                             ///< false: nothing within reach, no ray was cast
    vec3 e1{1, 0, 0}, e2{0, 1, 0}, axis{0, 0, 1};  ///< the rolled frame (world)
    std::shared_ptr<const ConePatterns> patterns;  ///< keeps the ray set alive
    const float* x = nullptr;                      ///< the ray set used, in the frame
    const float* y = nullptr;
    const float* z = nullptr;
    std::vector<std::uint32_t> blocked;  ///< per cell, 0 or 1
    int hits = 0;
    /// Direction of cell k in world coordinates.
    vec3 direction(int k) const { return x[k] * e1 + y[k] * e2 + z[k] * axis; }
};

/// The code that marks blocked cells: kPortable runs on any processor; kWide, on x86-64
/// processors with AVX2, marks four cells of two rings at a time. Both mark the same cells to
/// the bit (the same operations on each ray).
enum class ConeKernel { kPortable, kWide };
/// Whether this processor (and build) can run `kernel`.
bool coneKernelAvailable(ConeKernel kernel);
/// The kernel every cone uses from now on; nothing: the widest available (the default). For
/// tests and benchmarks. Throws an Error for a kernel this processor cannot run.
void setConeKernel(std::optional<ConeKernel> kernel);
/// The kernel cones use now.
ConeKernel coneKernel();

/// Casts the cone's rays against the soft obstacles within reach (apex + t * ray, t in
/// [tnear, look-ahead]), the organs in `ignore` excepted. With `traced`, every ray is traced
/// on its own against every triangle (World::softOccluded), the reference the tests compare
/// the cell-wise sampling with. Two draws from `rng`: the ray set and the roll.
void sampleCone(const World& world, vec3 apex, vec3 axis, const PerceptionCone& cone, Rng& rng,
                float tnear, const Ignore& ignore, ConeSample& out, bool traced = false);

/// The centre of the best open gap of a sampled cone (open cells connected through shared
/// edges; sectors wrap around, the innermost ring's cells all meet at the axis), scored by its
/// size times 1 - 0.5 x (angle of its centre from the axis) / half-angle. Nothing when every
/// cell is open or every cell is blocked.
std::optional<vec3> bestGap(const ConeSample& sample, float halfAngleDegrees);

}  // namespace plantarch::collision
