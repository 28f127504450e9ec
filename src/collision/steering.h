#pragma once
// Steering of new organs during growth: soft avoidance, attraction points and solid
// obstacles, asked by phytomer creation (internodes, petioles) and flowering (peduncles)
// through growth's Steering interface.

#include <cstdint>
#include <vector>

#include "growth/steering.h"

namespace plantarch::collision {

class World;
class AttractionIndex;

/// Position of node `internodes` of a shoot (0: its base) at plant age `now`; with `mature`,
/// as if every internode had reached its full length.
vec3 nodePosition(const PlantInstance& plant, unsigned shootID, std::size_t internodes, double now,
                  bool mature);

/// What one plant steers by while it grows: the collision scene and its attraction points.
class SceneSteering final : public Steering {
public:
    /// `world` null: no scene; `attraction` null: no attraction points.
    SceneSteering(const World* world, const AttractionIndex* attraction, std::uint64_t seed)
        : world(world), attraction(attraction), seed(seed) {}

    /// Turns the internode by attraction points, soft avoidance and solid obstacles.
    void steerShootAxis(const PlantInstance& plant, const Shoot& shoot, Internode& in,
                        float lengthMax) override;
    /// Keeps the internode's full length out of solid obstacles.
    void keepInternodeClear(const PlantInstance& plant, const Shoot& shoot, Internode& in) override;
    /// Soft avoidance of a new petiole (pitch and azimuth changed).
    void steerPetiole(const PlantInstance& plant, const Shoot& shoot, const Internode& in,
                      float internodeFraction, unsigned petioleIndex, Petiole& petiole) override;
    /// Soft avoidance of a new peduncle (pitch and roll changed).
    void steerPeduncle(const PlantInstance& plant, const Shoot& shoot, unsigned node,
                       unsigned petiole, unsigned bud, bool terminal, FloralBud& fb) override;

    const World* const world;
    const AttractionIndex* const attraction;  ///< the plant's own points, else the global
    const std::uint64_t seed;                 ///< scene seed (cone rays are drawn from it)
};

}  // namespace plantarch::collision
