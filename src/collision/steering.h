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

/// Position of node `internodes` of a shoot (0: its base) at plant age `now`; with `mature`,
/// as if every internode had reached its full length.
vec3 nodePosition(const PlantInstance& plant, unsigned shootID, std::size_t internodes, double now,
                  bool mature);

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
