#pragma once
// Solid obstacles as something side organs are kept out of (growth/organ_clearance.h).

#include <vector>

#include "collision/collision_state.h"
#include "collision/proxies.h"
#include "growth/organ_clearance.h"

namespace plantarch::collision {

class World;

/// The world's solid obstacles for the side organs of the plants one worker grows: petioles
/// and peduncles with their leaves and flowers (organClearance), fruit (fruitAdjustment). Tubes
/// are tested as triangles, prototype parts by their bounding boxes.
class SolidClearance final : public OrganObstacle {
public:
    SolidClearance(const Worker& worker, const World& world);
    /// Whether there are solid obstacles and either option is on.
    bool active() const { return active_; }

    bool near(vec3 p, float reach) override;
    bool crosses(const TrialSink& trial) override;
    /// One axis: across the direction from the attachment to the organ's middle and the
    /// normal of the nearest obstacle surface.
    void turnAxes(const TrialSink& trial, vec3 attachment, std::vector<vec3>& axes) override;

private:
    // The trial's prototype parts as boxes, and the bounds of everything it holds.
    void shape(const TrialSink& trial);

    const Worker& worker_;
    const World& world_;
    bool active_ = false;
    std::vector<OrientedBox> boxes_;
    AABB bounds_;
    std::vector<unsigned> candidates_;
};

/// Adds the counts of one plant's clearance to the world's statistics.
void countClearance(const World& world, const ClearanceCounts& counts);

/// Sets the clearance turns of the plant's side organs from its current shape: out of the
/// world's solid obstacles and, with the plant's ground clearance on, out of the ground.
void clearOrgans(const Worker& worker, const World& world, PlantInstance& plant);

}  // namespace plantarch::collision
