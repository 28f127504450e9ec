#pragma once
// Steering of new organs during growth: soft avoidance, attraction points and solid
// obstacles, called by phytomer creation (internodes, petioles) and flowering (peduncles).

#include <cstdint>
#include <vector>

#include "model/architecture_impl.h"

namespace plantarch::collision {

class World;
class AttractionIndex;

/// What the plant being grown steers by. Set on the Impl while growth runs.
struct Steering {
    const World* world = nullptr;
    const AttractionIndex* attraction = nullptr;  ///< the plant's own points, else the global
    std::uint64_t seed = 0;                       ///< scene seed (cone rays are drawn from it)
};

class World;
struct Ignore;

/// The rays of a perception cone (rings of equal solid angle from the axis out, each split
/// into equal sectors, one jittered ray per cell, ring-major) and which of them are blocked.
struct ConeSample {
    int rings = 1, sectors = 1;
    std::vector<vec3> dirs;     ///< empty when nothing was within reach (no ray cast)
    std::vector<char> blocked;  ///< per cell
    int hits = 0;
};

/// Casts the cone's rays against the soft obstacles: the triangles the scene finds within
/// reach are tested against the rays of the cells they can cover (or, with `embreeRays`, every
/// ray is traced by Embree: the reference the tests compare with).
void sampleCone(const World& world, vec3 apex, vec3 axis, const PerceptionCone& cone, Rng& rng,
                float tnear, const Ignore& ignore, ConeSample& out, bool embreeRays = false);

/// Position of node `internodes` of a shoot (0: its base) at plant age `now`; with `mature`,
/// as if every internode had reached its full length.
vec3 nodePosition(const PlantInstance& plant, unsigned shootID, std::size_t internodes,
                  double now, bool mature);

/// Turns a new internode of `shoot` (its guide and roll reference set, not yet pushed onto
/// the shoot) by attraction points, soft avoidance and solid obstacles. `lengthMax`: its full
/// length, m.
void steerShootAxis(PlantArchitecture::Impl& impl, const PlantInstance& plant, const Shoot& shoot,
                    Internode& in, float lengthMax);
/// After the internode's direction is set: keeps its full length out of solid obstacles.
void keepInternodeClear(PlantArchitecture::Impl& impl, const PlantInstance& plant,
                        const Shoot& shoot, Internode& in);
/// Soft avoidance of a new petiole (pitch and azimuth changed). `in` is its internode.
void steerPetiole(PlantArchitecture::Impl& impl, const PlantInstance& plant, const Shoot& shoot,
                  const Internode& in, float internodeFraction, unsigned petioleIndex,
                  Petiole& petiole);
/// Soft avoidance of a new peduncle (pitch and roll changed).
void steerPeduncle(PlantArchitecture::Impl& impl, const PlantInstance& plant, const Shoot& shoot,
                   unsigned node, unsigned petiole, unsigned bud, bool terminal, FloralBud& fb);

}  // namespace plantarch::collision
