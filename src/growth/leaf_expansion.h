#pragma once
// Leaf expansion: a petiole and its leaves grow from their fraction at creation toward their
// full size, in growth steps of the plant's step.
//
// Each step a leaf gains `elongation rate x step` of its full size, and its new fraction is
// that length measured against its type's nominal leaf size (the mean reciprocal of the leaf
// prototype_scale distribution), not against its own full size. A leaf whose full size is
// the nominal one grows linearly, f0 + rate x age, until it is full grown. A leaf made
// smaller by a node rule (the first leaves of a seedling, a spur's leaves, a grass's lowest
// blades) or drawn small levels off below its full size: with r = its full size / the
// nominal size < 1, the fraction tends to rate x step x r / (1 - r) (a seedling's first
// leaf, made at half the nominal size, with rate 0.1 and a 2-day step, stays at a fifth).
// A leaf drawn larger than the nominal size grows faster. The steps are the plant's growth
// step (growthStep); between steps the closed form is evaluated at fractional step counts,
// so a plant grown in any number of calls has the same leaves.

#include "plantarch/PlantState.h"

namespace plantarch {

/// The plant's growth step, days: the shortest mean phyllochron among its shoot types (the
/// types it has made shoots of). 1 when it has none.
double growthStep(const PlantInstance& plant);

/// 1 / a type's nominal leaf size: the mean of 1 / P for P drawn from its leaf
/// `prototype_scale` (ln(b/a)/(b-a) for uniform(a, b); 1 / mean for a normal or Weibull
/// draw); 0 where a size can be 0 or less.
double nominalReciprocal(const RandomFloat& leafPrototypeScale);

/// Full size of a phytomer's tip leaf (its first petiole's) times `reciprocal`
/// (nominalReciprocal of its type); 1 where either is not positive.
float leafSizeRatio(const Phytomer& ph, double reciprocal);

/// A phytomer's leaf fraction `age` days after creation (at most 1), for fraction `f0` at
/// creation, elongation rate `rate` per day, size ratio `ratio` (leafSizeRatio) and the
/// plant's growth step `step`.
float leafFractionAt(float f0, float rate, double age, float ratio, double step);

}  // namespace plantarch
