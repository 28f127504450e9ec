#pragma once
// Growth: making shoots and phytomers as state (shoot_builder.cpp) and advancing a plant in
// time (growth.cpp). Geometry is not touched: the caller tessellates afterwards.

#include <functional>
#include <span>
#include <vector>

#include "geometry/prototype_cache.h"
#include "growth/organ_clearance.h"
#include "growth/steering.h"
#include "model/function_registry.h"
#include "model/plant_store.h"
#include "plantarch/ShootSpec.h"

namespace plantarch {

/// What growing a plant uses besides the plant: the shoot types and functions (read only,
/// so threads growing different plants may share them), a prototype cache of the thread's
/// own (girth reads leaf areas), the steering of new organs (none: unsteered), what side
/// organs are kept out of besides the ground (solid obstacles; see clearSideOrgans) and where
/// their turns are counted (may be null).
struct GrowthContext {
    const PlantStore& store;
    const FunctionRegistry& functions;
    PrototypeCache& prototypes;
    Steering* steering = nullptr;
    std::span<OrganObstacle* const> obstacles = {};
    ClearanceCounts* clearanceCounts = nullptr;
};

/// How a new shoot starts: the plant's base stem, continuing a shoot's tip, from an axil by
/// hand (at the pitch its spec gives), from an axillary bud breaking as the plant grows (at
/// its own type's insertion angle for the bud's place below the parent's tip), or as a water
/// sprout from the wood at a node (upright, its spec's pitch from the vertical; no bud used).
enum class StartMode { Base, Append, Child, Bud, Epicormic };

/// Throws if a shoot's start options are out of range (naming the option and its range).
void checkShootSpec(const ShootSpec& spec);
/// Checks the sizes of phytomers made by hand (radius, full length, fractions).
void checkPhytomerSize(const PhytomerSize& size);

/// Creates a shoot (and its first spec.phytomers phytomers) as state; no geometry.
unsigned createShoot(const GrowthContext& growth, PlantInstance& plant, const ShootSpec& spec,
                     StartMode mode, int parentID, unsigned parentNode, unsigned parentPetiole);
/// Appends one phytomer to a shoot as state (calls the creation function when named).
void createPhytomer(const GrowthContext& growth, PlantInstance& plant, Shoot& shoot,
                    const PhytomerParameters& pp, float radius, float lengthMax,
                    float internodeFraction, float leafFraction, const Internode* start);

/// Grows one plant by `days`; object IDs of organs that fell off are added to `deletes`. Ends
/// with the turns of its side organs set from its shape (clearSideOrgans, with the context's
/// obstacles), then ground clipping when the store has it on (clipBelowGround).
/// `onDay` (may be empty) is called after each day with the fraction of `days` done (0 to 1);
/// it must not throw.
void growPlant(const GrowthContext& growth, PlantInstance& plant, double days,
               std::vector<ObjectID>& deletes, const std::function<void(double)>& onDay = {});
/// The node of `shoot` that holds the point `position` (a fraction, (0, 1]) along it: the
/// phytomer ceil(position x count) - 1.
unsigned epicormicNode(const Shoot& shoot, float position);
/// Ends the plant's growing season now (`begin` false: as at senescence, unless it is not in
/// one) or begins one (`begin` true: as at dormancy break, if it is dormant). Geometry is not
/// touched.
void changeSeason(const GrowthContext& growth, PlantInstance& plant, bool begin);
/// Draws a floral bud's peduncle and flowers from the phytomer parameters.
void realizeInflorescence(PlantInstance& plant, FloralBud& bud, const PhytomerParameters& pp);
/// Starts a newly created shoot's clock: its apical bud, its axillary buds.
void scheduleNewShoot(const GrowthContext& growth, PlantInstance& plant, Shoot& shoot);

}  // namespace plantarch
