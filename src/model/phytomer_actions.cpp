// The actions species node rules take on one phytomer (plantarch/PhytomerActions.h).

#include "plantarch/PhytomerActions.h"

namespace plantarch {

void killVegetativeBuds(Phytomer& ph) {
    for (Petiole& p : ph.petioles)
        for (VegetativeBud& b : p.vegetativeBuds)
            if (b.state == BudState::Dormant) b.state = BudState::Dead;
}

void killFloralBuds(Phytomer& ph) {
    for (Petiole& p : ph.petioles)
        for (FloralBud& b : p.floralBuds)
            if (b.stage == FloralStage::Bud) {
                b.state = BudState::Dead;
                b.stage = FloralStage::Removed;
            }
}

void removeLeaves(Phytomer& ph) {
    for (Petiole& p : ph.petioles) {
        for (LeafOrgan& l : p.leaves) l.removed = true;
        p.length = 0.0f;
        p.radius = 0.0f;
    }
}

}  // namespace plantarch
