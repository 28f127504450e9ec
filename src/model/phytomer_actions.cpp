// The actions species node rules take on one phytomer (plantarch/PhytomerActions.h).

#include <cmath>

#include "core/value_text.h"
#include "plantarch/Error.h"
#include "plantarch/PhytomerActions.h"
#include "plantarch/PlantStateTable.h"

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

void scaleLeaves(Phytomer& ph, float factor) {
    static const state::FieldInfo size = state::fieldInfo<LeafOrgan>("leaf_scale");
    const auto refuse = [&](const std::string& why) {
        throw Error(why, {.parameter = "factor",
                          .value = text::formatFloat(factor),
                          .validRange = "a finite number keeping every leaf_scale within " +
                                        rangeText(size.range())});
    };
    if (!std::isfinite(factor)) refuse("not a finite number");
    for (const Petiole& p : ph.petioles)
        for (const LeafOrgan& l : p.leaves)
            if (!state::inside(size, l.scale * factor))
                refuse("makes leaf_scale " + text::formatFloat(l.scale * factor) + " from " +
                       text::formatFloat(l.scale));
    for (Petiole& p : ph.petioles)
        for (LeafOrgan& l : p.leaves) l.scale *= factor;
}

}  // namespace plantarch
