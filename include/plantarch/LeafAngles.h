#pragma once
// Leaf angles of plants and canopies: the area-weighted histogram and mean of the leaf
// inclination measured on the triangles in the Context, and the distributions a species'
// leaves are drawn from (LeafAngleParameters, docs/measured-plants.md "Leaf angle
// distributions"): their expected histogram, their draws and their projection function G.
//
// A triangle's inclination is the angle of its normal from vertical, folded to 0 to 90
// degrees (either side of a blade): 0 a horizontal surface, 90 a vertical one. Angles are
// degrees.

#include <vector>

#include "plantarch/Parameters.h"
#include "plantarch/PlantState.h"
#include "plantarch/Random.h"

namespace plantarch {

class PlantArchitecture;

/// The leaf area of one or more plants by inclination.
struct LeafInclinationHistogram {
    std::vector<double> edges;      ///< the bins' edges, degrees (one more than the bins)
    std::vector<double> fractions;  ///< share of the leaf area in each bin (all 0 without any)
    double leafArea = 0.0;          ///< one-sided leaf area of the triangles measured, m²
    double meanInclination = 0.0;   ///< area-weighted mean inclination, degrees (0 without any)
};

/// 0, 10, 20, ... 90: nine bins of ten degrees.
std::vector<double> defaultInclinationEdges();

/// The leaf inclination histogram of plant `plantID` from its leaves' triangles, area
/// weighted, in the bins between `edges` (increasing, from 0 to 90, at least two; a bin
/// holds its lower edge, the last one also its upper). Throws plantarch::Error for a plant
/// that does not exist or edges that are not so.
LeafInclinationHistogram leafInclinationHistogram(
    const PlantArchitecture& arch, unsigned plantID,
    const std::vector<double>& edges = defaultInclinationEdges());
/// The same over several plants together (a canopy): each triangle by its area.
LeafInclinationHistogram leafInclinationHistogram(
    const PlantArchitecture& arch, const std::vector<unsigned>& plantIDs,
    const std::vector<double>& edges = defaultInclinationEdges());

/// The area-weighted mean leaf inclination of a plant, or of several plants together,
/// degrees (0 without leaf area).
double meanLeafInclination(const PlantArchitecture& arch, unsigned plantID);
double meanLeafInclination(const PlantArchitecture& arch, const std::vector<unsigned>& plantIDs);

/// The share of the leaves of distribution `p` whose inclination falls in each bin between
/// `edges` (the histogram a large canopy of flat leaves approaches); all 0 for `none`. Throws
/// plantarch::Error for parameters out of range or edges as above.
std::vector<double> leafInclinationFractions(
    const LeafAngleParameters& p, const std::vector<double>& edges = defaultInclinationEdges());

/// The probability density of distribution `p` at an inclination, per degree (0 for none).
double leafInclinationDensity(const LeafAngleParameters& p, double degrees);

/// One leaf's draw, as a leaf of a plant with distribution `p` makes it: the inclination,
/// then the azimuth (two uniform draws of `rng`). Throws plantarch::Error for `none` or
/// parameters out of range.
LeafAngleTarget drawLeafAngle(const LeafAngleParameters& p, Rng& rng);

/// Ross's G function of distribution `p` with azimuths uniform: the mean projection of unit
/// leaf area on a plane square to a direction `zenith` degrees from vertical. A canopy of
/// such leaves of leaf area index L lets exp(-G L / cos(zenith)) of a beam through, so its
/// extinction coefficient is G / cos(zenith) (0.5 / cos(zenith) for a spherical one).
double leafProjection(const LeafAngleParameters& p, double zenith);

}  // namespace plantarch
