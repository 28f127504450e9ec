#pragma once
// What growth asks while it makes new organs: which way to point them. Growth knows nothing
// of what steers; collision avoidance (collision/steering.h) implements this with the
// perception cones, attraction points and solid obstacles. Without a Steering new organs
// point as their parameters say.

#include "plantarch/PlantState.h"

namespace plantarch {

class Steering {
public:
    virtual ~Steering() = default;
    /// Turns a new internode of `shoot` (its guide and roll reference set, not yet pushed onto
    /// the shoot). `lengthMax`: its full length, m.
    virtual void steerShootAxis(const PlantInstance& plant, const Shoot& shoot, Internode& in,
                                float lengthMax) = 0;
    /// After the internode's direction is set: keeps its full length out of obstacles.
    virtual void keepInternodeClear(const PlantInstance& plant, const Shoot& shoot,
                                    Internode& in) = 0;
    /// Turns a new petiole (its pitch and azimuth). `in` is its internode, `internodeFraction`
    /// the internode's current length over its full length.
    virtual void steerPetiole(const PlantInstance& plant, const Shoot& shoot, const Internode& in,
                              float internodeFraction, unsigned petioleIndex, Petiole& petiole) = 0;
    /// Turns a new peduncle (its pitch and roll): an axillary bud (petiole, bud) of `node`, or
    /// the shoot's terminal bud `bud` when `terminal`.
    virtual void steerPeduncle(const PlantInstance& plant, const Shoot& shoot, unsigned node,
                               unsigned petiole, unsigned bud, bool terminal, FloralBud& fb) = 0;
};

}  // namespace plantarch
