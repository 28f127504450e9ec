#pragma once
// The fields of CollisionStats by name, for anything that lists them (the Python binding's
// dict, statistics output): one list beside the struct, checked against it by a test that
// reads plantarch/Collision.h.

#include "plantarch/Collision.h"

namespace plantarch {

/// Calls visit(name, value) for every field of `s`, in declaration order.
template <class Visit>
void visitCollisionStats(const CollisionStats& s, Visit&& visit) {
    visit("softCones", s.softCones);
    visit("softRays", s.softRays);
    visit("softSteered", s.softSteered);
    visit("solidCones", s.solidCones);
    visit("solidSteered", s.solidSteered);
    visit("attractionQueries", s.attractionQueries);
    visit("attracted", s.attracted);
    visit("organsTurned", s.organsTurned);
    visit("organsUnresolved", s.organsUnresolved);
    visit("sceneRefreshes", s.sceneRefreshes);
    visit("plantsRebuilt", s.plantsRebuilt);
    visit("plantsUnchanged", s.plantsUnchanged);
    visit("sceneTriangles", s.sceneTriangles);
    visit("refreshSeconds", s.refreshSeconds);
    visit("coneSeconds", s.coneSeconds);
}

}  // namespace plantarch
