// The actions species node rules take on one phytomer (plantarch/PhytomerActions.h).

#include <cmath>
#include <string>

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
    static const state::FieldInfo length = state::fieldInfo<Petiole>("petiole_length");
    static const state::FieldInfo radius = state::fieldInfo<Petiole>("petiole_radius");
    static const state::FieldInfo curvature = state::fieldInfo<Petiole>("petiole_curvature");
    const auto refuse = [&](const std::string& why, const state::FieldInfo& field) {
        throw Error(why, {.parameter = "factor",
                          .value = text::formatFloat(factor),
                          .validRange = "a finite number keeping every " + std::string(field.name) +
                                        " within " + rangeText(field.range())});
    };
    const auto check = [&](const state::FieldInfo& field, float from, float to) {
        if (!state::inside(field, to))
            refuse("makes " + std::string(field.name) + " " + text::formatFloat(to) + " from " +
                       text::formatFloat(from),
                   field);
    };
    if (!std::isfinite(factor)) refuse("not a finite number", size);
    for (const Petiole& p : ph.petioles)
        for (const LeafOrgan& l : p.leaves) check(size, l.scale, l.scale * factor);
    // A leaf made smaller has a petiole as much shorter and thinner, bending by the same
    // angle over its length (its curvature, degrees per metre, divided by the factor).
    for (const Petiole& p : ph.petioles) {
        check(length, p.length, p.length * factor);
        check(radius, p.radius, p.radius * factor);
        if (factor > 0.0f) check(curvature, p.curvature, p.curvature / factor);
    }
    for (Petiole& p : ph.petioles) {
        for (LeafOrgan& l : p.leaves) l.scale *= factor;
        p.length *= factor;
        p.radius *= factor;
        if (factor > 0.0f) p.curvature /= factor;
    }
}

}  // namespace plantarch
