#pragma once
// Leaf angle distributions (plantarch/Parameters.h, LeafAngleParameters): the density of each
// inclination family, the probability of a range of inclinations, and the draws a leaf makes
// of its target inclination and azimuth (docs/measured-plants.md, "Leaf angle distributions").
//
// Inclinations are degrees from 0 (a horizontal blade, its normal at the zenith) to 90 (a
// vertical one); azimuths degrees clockwise from north (+y; 90 is east, +x), the compass
// direction the blade's upper side faces.

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "plantarch/Parameters.h"
#include "plantarch/PlantState.h"
#include "plantarch/Random.h"

namespace plantarch::leaf_angles {

/// A histogram declaration's bins in order: upper edges (degrees, increasing, the first bin
/// starting at 0) and their weights.
struct Bins {
    std::vector<double> upper;
    std::vector<double> weight;
};

/// The bins of `histogram` (keys: upper edges in degrees). Throws plantarch::Error naming
/// `path` + "." + key for a key that is not a number above 0 and at most 90, or an edge given
/// twice.
Bins histogramBins(const std::map<std::string, float>& histogram, const std::string& path);

/// The checks across the fields of `p` (each field's own range is the table's): histogram
/// edges, a histogram with weight when it is the family, beta_mean with a beta_sd that a beta
/// distribution can have. `path` is the group's ("leaf_angles", "phenology.leaf_angles").
void check(const LeafAngleParameters& p, const std::string& path);

/// The beta family's (mu, nu): beta_mu and beta_nu, or those of beta_mean and beta_sd.
std::pair<double, double> betaShape(const LeafAngleParameters& p);

/// The density of the inclination at `degrees` (per degree; 0 for none).
double inclinationDensity(const LeafAngleParameters& p, double degrees);

/// Draws of a distribution: its cumulative table, built once per parameters.
class Sampler {
public:
    explicit Sampler(const LeafAngleParameters& p);
    /// The share of leaves with an inclination from `lo` to `hi` degrees.
    double probability(double lo, double hi) const;
    /// A target inclination (one uniform draw) and azimuth (one uniform draw), in that order.
    LeafAngleTarget draw(Rng& rng) const;
    const LeafAngleParameters& parameters() const { return p_; }

private:
    double cdf(double degrees) const;
    LeafAngleParameters p_;
    Bins bins_;                    // histogram family
    std::vector<double> cumul_;    // inclination: cumulative share at each cell edge
    std::vector<double> azimuth_;  // von Mises: cumulative share, -180 to 180 degrees
};

/// The sampler of `p`, kept for the last parameters asked for on this thread.
const Sampler& sampler(const LeafAngleParameters& p);

}  // namespace plantarch::leaf_angles
