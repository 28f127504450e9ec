#pragma once
// Options of collision avoidance and attraction points (docs/collision.md).
//
// Growing tips perceive their surroundings through a perception cone: rays from the tip
// within `halfAngle` of the candidate growth direction, `lookAhead` metres long. Three
// steering rules use it when an internode (optionally a petiole or peduncle) is made:
//   soft avoidance    turns growth toward the largest open gap among plant organs and obstacles
//   solid obstacles   turns growth along the surface of the nearest obstacle, never into it
//   attraction points turn growth toward the nearest point in the cone (wires, trellises)
// Each blends the candidate direction with its target by an inertia factor: 0 takes the
// target exactly, 1 leaves growth unchanged. Solid obstacles always act last (priority).

#include <cstdint>
#include <string>
#include <vector>

#include "plantarch/Context.h"

namespace plantarch {

/// A perception cone at a growing tip.
struct PerceptionCone {
    float halfAngle = 80.0f;  ///< degrees from the growth direction, (0, 180)
    float lookAhead = 0.1f;   ///< ray length, m, (0, 100]
    unsigned rays = 256;      ///< rays per cone, 8 to 16384 (soft avoidance only)
    float inertia = 0.4f;     ///< 0 turns fully to the target, 1 leaves growth unchanged
};

/// Which plant organs are obstacles in the collision scene (each kind added costs rays).
struct CollisionOrgans {
    bool internodes = false;  ///< stem tubes
    bool leaves = true;       ///< leaf blades (as light proxies)
    bool petioles = false;    ///< petiole and peduncle tubes
    bool flowers = false;     ///< closed and open flowers
    bool fruit = false;       ///< fruit
};

/// Soft collision avoidance: growth tends toward open space. It does not strictly prevent
/// collisions (that would need a costly global iteration).
struct SoftCollisionOptions {
    PerceptionCone cone;
    bool steerInternodes = true;  ///< steer new internodes (the shoot axis)
    bool steerPetioles = false;   ///< steer new petioles (and so their leaves)
    bool steerPeduncles = false;  ///< steer new peduncles (and so their flowers and fruit)
    CollisionOrgans obstacles;    ///< plant organs that are obstacles (leaves by default)
    /// Context objects (not plant organs) that are obstacles too: ground, walls, a house...
    std::vector<ObjectID> objects;
    /// Days between refreshes of the collision scene (plants see each other as they stood at
    /// the last refresh), 1/1024 to 365. Refreshes fall on whole multiples of the interval of
    /// the collision clock, so growth stays independent of how advanceTime calls are split.
    double updateInterval = 1.0;
};

/// Solid obstacles: growth never enters them.
struct SolidObstacleOptions {
    std::vector<ObjectID> obstacles;  ///< Context objects that are solid
    float avoidanceDistance = 0.2f;   ///< m: obstacles nearer than this turn growth, (0, 100]
    /// Turns fruit about their attachment point until their bounds clear every obstacle, then
    /// back toward it in small steps while still clear (strawberries resting on the ground).
    bool fruitAdjustment = false;
    /// Turns petioles with their leaves, and peduncles with their flowers, out of obstacles
    /// the same way, so no leaf or flower reaches through a wall.
    bool organClearance = true;
    float coneHalfAngle = 60.0f;  ///< degrees, (0, 180)
    unsigned rays = 64;           ///< rays per cone, 8 to 16384
};

/// Attraction points: shoots grow toward the nearest point they see (e.g. along a wire).
/// A plant's own points are part of its state (PlantInstance::attraction): they are saved in
/// its plant structure file and travel with it.
struct AttractionPoints {
    std::vector<vec3> points;  ///< world positions, m
    float halfAngle = 80.0f;   ///< degrees, (0, 180)
    float lookAhead = 0.1f;    ///< m, (0, 100]
    float inertia = 0.4f;      ///< 0 to 1
    /// Shoot types that are attracted (empty: all).
    std::vector<std::string> shootTypes;
    bool operator==(const AttractionPoints&) const = default;
};

/// Reads attraction points from a CSV file: one "x,y,z" per line (m); blank lines, '#'
/// comments and a header line of names (the first line, none of its fields a number) are
/// skipped. A field that reads as a number but is not finite ("nan", "inf") is an error, on
/// the first line too, as is a file without points. Errors name the file, the line and
/// `parameter` (what named the file: "--attraction-points", "attraction/file").
std::vector<vec3> readAttractionPointsCSV(const std::string& path, const std::string& parameter);

/// Counts of the work collision avoidance did (since it was enabled or the counts were reset).
/// Everything but the seconds is the same for any thread count.
struct CollisionStats {
    std::uint64_t softCones = 0;  ///< perception cones cast for soft avoidance
    std::uint64_t softRays = 0;
    std::uint64_t softSteered = 0;  ///< cones that found an obstacle and turned growth
    std::uint64_t solidCones = 0;
    std::uint64_t solidSteered = 0;  ///< internodes turned by a solid obstacle
    std::uint64_t attractionQueries = 0;
    std::uint64_t attracted = 0;         ///< internodes turned toward an attraction point
    std::uint64_t organsTurned = 0;      ///< petioles, peduncles and fruit turned out of obstacles
    std::uint64_t organsUnresolved = 0;  ///< ... that no turn could clear (left as grown)
    std::uint64_t sceneRefreshes = 0;    ///< refreshes of the collision scene
    std::uint64_t plantsRebuilt = 0;     ///< plants whose proxies changed at refreshes (re-binned)
    std::uint64_t plantsUnchanged = 0;   ///< plants whose geometry had not changed (kept)
    std::uint64_t sceneTriangles = 0;    ///< plant proxy triangles in the scene now
    double refreshSeconds = 0.0;         ///< time of refreshes: preparing the plants' proxies
                                         ///< (thread time over the threads) and installing
                                         ///< them (wall time); varies run to run
    double coneSeconds = 0.0;            ///< thread time in soft avoidance cones (varies)
};

}  // namespace plantarch
