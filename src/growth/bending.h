#pragma once
// Shoots bending under load (docs/measured-plants.md, "Shoots bending under load"): every
// shoot a chain of elastic rods, one per internode, loaded by its own weight, what its nodes
// carry and the shoots growing from it, solved for its large-deflection equilibrium. The
// result is state: each internode's InternodeBend, the turn geometry applies to its rest
// shape (geometry/tessellate.cpp).

#include <functional>
#include <span>
#include <vector>

#include "geometry/prototype_cache.h"
#include "model/plant_store.h"
#include "plantarch/PlantState.h"

namespace plantarch::bending {

/// Standard gravity, m s-2.
inline constexpr double kGravity = 9.80665;

/// A force on a node from outside the plant (a hand or a robot pulling a branch): node `node`
/// of shoot `shoot` is the top of its internode `node` (where phytomer `node`'s petioles are).
struct NodeForce {
    unsigned shoot = 0;
    unsigned node = 0;
    glm::dvec3 force{0.0};  ///< N, world
};

/// The one-side area of a leaf now, m².
using LeafArea = std::function<double(const Phytomer&, const LeafOrgan&)>;

/// What a solve found.
struct Solution {
    bool converged = false;
    unsigned iterations = 0;
    /// Per shoot (by ID), node positions 0..n after bending (empty for removed shoots).
    std::vector<std::vector<glm::dvec3>> nodes;
    /// Per shoot, the force and moment (about its base node) the shoot and all it carries put
    /// on its support (the parent's node, or the ground), N and N m.
    std::vector<glm::dvec3> baseForce, baseMoment;
    /// Per shoot, per internode: the whole turn from the rest shape, as a rotation vector
    /// (world axis times angle, radians).
    std::vector<std::vector<glm::dvec3>> turns;
};

/// Solves the plant's equilibrium under gravity and `forces`, with its phenology's mechanics
/// parameters (whether enabled or not). `start` (may be null): turns to start iterating
/// from (a previous Solution's). Deterministic: no random numbers, one thread.
Solution solve(const PlantInstance& plant, const MechanicsParameters& mechanics,
               const LeafArea& leafArea, std::span<const NodeForce> forces,
               const Solution* start = nullptr);

/// The turns stored as the internodes' bends.
void store(PlantInstance& plant, const Solution& solution);

/// The rest-shape turns a plant's state holds now, as a Solution to start from (nodes and
/// forces empty).
Solution currentTurns(const PlantInstance& plant);

/// Leaf areas from the leaves' prototypes: a prototype's area times the leaf's size squared.
LeafArea prototypeLeafArea(const PlantStore& store, PrototypeCache& prototypes,
                           PlantInstance& plant);

/// Solves the plant under gravity alone (starting from the bends it holds) and stores the
/// result: what growth does after each step for a plant whose mechanics are enabled.
void bendPlant(const PlantStore& store, PrototypeCache& prototypes, PlantInstance& plant);

}  // namespace plantarch::bending
