#pragma once
// Procedural leaf blades: outline families, a mesh that follows the outline, the deformations
// of the reference's procedural leaf, and outlines traced from a PNG's alpha channel.
//
// Prototype frame (the convention of every organ prototype): the blade lies in the xy plane
// with its upper side facing +z, the midrib runs along +x from the petiole attachment to the
// tip at (1, 0) and the width runs along y. A flat outline spans x in [0, 1]; its widest
// point has half-width leaf_aspect_ratio / 2. For the families with a notched base (cordate,
// reniform, sagittate, hastate, palmate) the basal lobes reach back to x = 0 and the
// petiole attaches in the sinus at (sinus_depth, 0); species then set `leaf_offset` to
// (-sinus_depth, 0, 0) to put the sinus on the petiole tip. Bending a blade (longitudinal
// curvature, buckle) keeps its length along the midrib: the prototype's unit length is its
// length along the blade, and a bent blade's projection on x is shorter than 1.
//
// The pieces can be used alone: leafOutline() gives the polygon, meshLeafOutline() a flat
// triangle mesh of it, deformLeafMesh() bends it; buildLeafPrototype() does everything from
// a LeafPrototype, drawing its random fields from the caller's stream.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "plantarch/Mesh.h"
#include "plantarch/Parameters.h"
#include "plantarch/Random.h"

namespace plantarch {

// ---- outline families ----------------------------------------------------------------

// LeafShape (the outline families) is declared in plantarch/Parameters.h; the name and
// description of each are in the parameter table (docs/parameters.md).

/// Every family, in declaration order.
const std::vector<LeafShape>& allLeafShapes();
/// Lower-case name used in parameter files ("palmate").
std::string_view leafShapeName(LeafShape shape);
/// The family named `name` exactly as files spell it; throws plantarch::Error listing the
/// valid names.
LeafShape leafShapeFromName(std::string_view name);

/// Realized (non-random) outline parameters. Lengths are fractions of the leaf length,
/// angles are degrees.
struct LeafOutlineParams {
    LeafShape shape = LeafShape::Elliptic;
    float aspect_ratio = 0.5f;  ///< maximum width / length, 0.01 to 4
    float widest_point = 0.5f;  ///< x of the widest point, 0.05 to 0.95
    /// Included angle between the two margins at the tip, 1 to 180 (180: rounded tip).
    /// An angle much smaller than the taper of the blade gives a drawn-out (acuminate) tip.
    /// Palmate lobes: the angle at every lobe tip.
    float tip_angle = 60.0f;
    /// Included angle between the two margins at the base, measured through the blade:
    /// below 180 a wedge-shaped base, 180 a rounded one. Cordate, reniform and palmate take
    /// 184 to 356 (smaller values act as 184): the larger, the narrower the sinus. Not used by
    /// sagittate and hastate, whose lobe direction follows from sinus_depth and the width.
    float base_angle = 90.0f;
    /// Width of a truncate base (margins start at (0, +-w/2)), fraction of the maximum
    /// width, 0 to 0.95; 0 = the margins meet at the base. Not used by notched families.
    float base_width = 0.0f;
    /// Notched families: depth of the basal sinus, from the back of the basal lobes to the
    /// petiole attachment, fraction of the length, 0.01 to 0.6.
    float sinus_depth = 0.15f;
    /// Total number of lobes including the terminal one (3, 5, 7...; an even count acts as
    /// the odd count below it; 0 or 1: unlobed). Notched families lobe radially from the
    /// petiole attachment (palmate); the others pinnately along the midrib.
    int lobes = 0;
    /// Depth of the sinuses between lobes, 0 to 0.9 (below 0.02: unlobed): palmate lobes meet
    /// at (1 - lobe_depth) of their length from the petiole attachment; pinnate sinuses
    /// narrow the half-width by this fraction. Sagittate/hastate: depth of the notch between
    /// the basal lobes and the body, fraction of the half-width.
    float lobe_depth = 0.0f;
    /// Teeth along each margin, 0 to 200. Serrate teeth (pointing to the tip) run over the part
    /// of the margin wide enough for a full notch; lobe tips and the widest point are tooth
    /// tips, so teeth never change the blade's extent.
    int serrations = 0;
    float serration_depth = 0.0f;  ///< depth of the notches, fraction of the length, 0 to 0.1
    /// Largest distance between the polygon and the exact curve, fraction of the length (it
    /// is scaled down for narrow blades so that the area error stays below 0.2 %).
    float tolerance = 5e-4f;
};

/// Typical numbers for a family (as drawn in docs/images/leaf-shapes.png).
LeafOutlineParams leafShapePreset(LeafShape shape);

/// The outline as a simple counter-clockwise polygon in the prototype frame, symmetric about
/// the x axis. Out-of-range values are clamped to the ranges documented above. The first
/// vertex is the base (the petiole attachment on the midrib); the tip (1, 0) is a vertex.
/// Teeth or lobes too deep for the shape (they would make the margin cross itself) are made
/// shallower, then dropped; a combination that still fails falls back to the plain elliptic
/// form with the same proportions, so every realized parameter set gives a valid outline.
std::vector<vec2> leafOutline(const LeafOutlineParams& params);

// ---- PNG outlines ------------------------------------------------------------------------

/// An outline traced from an image's alpha channel and the map from the prototype frame to
/// the image's texture coordinates.
///
/// The image's left edge is the leaf base and its right edge the tip; its vertical centre is
/// the midrib. The opaque part is scaled uniformly (the image's proportions are kept) so it
/// spans x in [0, 1]. Texture coordinates are those of OBJ: u from the left edge, v from the
/// bottom row.
struct TracedLeafOutline {
    std::vector<vec2> outline;  ///< simple, counter-clockwise, prototype frame
    float uAtBase = 0.0f;       ///< u of x = 0
    float uPerX = 1.0f;         ///< du/dx
    float vPerY = 1.0f;         ///< dv/dy (v = 0.5 at y = 0)
    float aspect_ratio = 0.0f;  ///< opaque height / opaque width

    /// Texture coordinates of a point of the flat blade.
    vec2 uvAt(vec2 p) const { return {uAtBase + uPerX * p.x, 0.5f + vPerY * p.y}; }
};

/// Traces the largest opaque region of a PNG (alpha >= 0.5, marching squares with sub-pixel
/// edges, simplified to half a pixel or 0.1 % of the leaf's length, whichever is larger). Throws
/// plantarch::Error naming the file when it cannot be read, has no alpha channel, or is fully
/// transparent or fully opaque.
TracedLeafOutline traceLeafImage(const std::string& path);
/// Just the outline of traceLeafImage().
std::vector<vec2> traceLeafOutlinePNG(const std::string& path);

// ---- meshing and deformation ---------------------------------------------------------------

/// Options of meshLeafOutline().
struct LeafMeshOptions {
    /// Rows of the mesh along the midrib: interior vertices are placed on a triangular
    /// lattice of spacing 1 / subdivisions (so columns follow the width). Values below 4 act
    /// as 4, the fewest rows with which fold and curvature show and triangles stay well
    /// shaped. The boundary always follows the outline (no triangle leaves it).
    unsigned subdivisions = 8;
    /// Mesh each half separately and mirror it, so the midrib (y = 0) is a line of edges and
    /// the fold is a clean crease. Needs an outline symmetric about y = 0 with a single base
    /// vertex on the axis (procedural outlines, as leafOutline() returns them).
    bool symmetric = true;
    /// Interior vertices placed instead of the lattice (empty: the lattice); those closer
    /// than half a row's spacing to the outline are left out. A pleated blade's vertices lie
    /// on its ridges and furrows, so the folds show as creases (buildLeafMesh()).
    std::vector<vec2> interior_points;
};

/// A flat mesh of `outline` (z = 0, upper side +z, counter-clockwise triangles seen from
/// +z). Every outline vertex is a mesh vertex, extra boundary vertices lie on outline edges,
/// so the mesh area equals the polygon area. UVs: u = x, v = 0.5 + y / width where width is
/// the outline's extent in y (the texture is stretched over the blade's bounding box).
/// Throws plantarch::Error for a polygon that is not simple or has fewer than 3 vertices.
Mesh meshLeafOutline(const std::vector<vec2>& outline, const LeafMeshOptions& options = {});

/// Realized deformation values (see LeafPrototype for the fields' meaning and units).
struct LeafDeformation {
    float midrib_fold_fraction = 0.0f;
    float longitudinal_curvature = 0.0f;
    float lateral_curvature = 0.0f;
    float petiole_roll = 0.0f;
    float wave_period = 0.0f;
    float wave_amplitude = 0.0f;
    float leaf_buckle_length = 0.0f;
    float leaf_buckle_angle = 0.0f;
    /// Radial pleats: their number, their height as a fraction of the distance from the
    /// centre, and the centre's x on the midrib (the petiole's attachment: the sinus of a
    /// notched blade, else the base; buildLeafMesh() takes it from the outline).
    int pleats = 0;
    float pleat_depth = 0.0f;
    float pleat_center_x = 0.0f;
    /// Width used to normalize the cross-section of the lateral curvature (the blade's
    /// leaf_aspect_ratio); <= 0 takes the mesh's extent in y.
    float blade_width = 0.0f;
    /// Rescale so the blade's length along the midrib is 1 (see deformLeafMesh()).
    bool normalize_length = true;
};

/// Bends a flat blade mesh (as meshLeafOutline() makes it) in place, in this order:
///  - pleats (n = pleats > 0 and A = pleat_depth != 0): about the centre (pleat_center_x, 0)
///    the blade folds into flat panels between straight creases, a ridge along the midrib
///    and every 360 / n degrees, a furrow halfway between. A point at distance r and angle
///    phi from the midrib moves to angle u = phi / g, g = sqrt(1 + (2 A n / pi)^2), and
///    distance r' = r / sqrt(1 + c^2), and rises by c r', with c = A (2 / pi) asin(cos(n u))
///    (A on a ridge, -A in a furrow): each ray keeps its length and each arc about the centre
///    its length along the folds, so the blade draws in (it spans a smaller angle) and keeps
///    its area to within 1 % and its length along the midrib.
///  - lateral curvature: z += lateral_curvature * (y / w)^2 / 4, with w = blade width, so
///    the margin at the widest point moves by lateral_curvature / 16 leaf lengths (the
///    reference's magnitude, with a smooth parabolic cross-section); + cups the margins up.
///  - waves: z += wave_amplitude * 2|y| * sin(pi x / wave_period + phase), phase 0 on the
///    y < 0 half and pi on the y > 0 half. wave_period is the distance between successive
///    sign changes (half a wavelength) as in the reference; the amplitude grows from 0 on
///    the midrib to wave_amplitude times the local width at the margin.
///  - fold and petiole roll: each half rotates about the midrib by
///    midrib_fold_fraction * 90 deg + petiole_roll * exp(-x / 0.05) deg, raising the margins
///    (fold 1 closes the blade; petiole_roll curls the basal 10-15 % of the blade).
///  - longitudinal curvature and buckle: the midrib becomes a curve of unchanged length with
///    the shape of the curve (x cos t + z sin t, z cos t - x sin t), z = c x^4, t = -c x^4,
///    c = longitudinal_curvature (a droop of c x^4 and a turn of c x^4 radians about the
///    base, which add): at each fraction of the blade's length the midrib's angle to +x is
///    that curve's at the same fraction of its own length. The bend gathers toward the tip,
///    which rises by about 2c leaf lengths for small c (0.47 for 0.3; it points straight
///    down near c = -0.29). From it leaf_buckle_angle degrees are taken, ramped in over
///    x = leaf_buckle_length +- 0.025 (a crease that bends the rest of the blade down).
///    Cross-sections keep their shape and stay perpendicular to the midrib.
///  - normalization: when normalize_length is set the mesh is scaled uniformly about the
///    origin and shifted in x so that the flat blade's extent in x (taken before bending)
///    becomes [0, 1]. Bending keeps lengths along the midrib, so the blade's length along it
///    is 1 however it curls (a leaf's prototype_scale is its length along the blade, the arc
///    length of the midrib); a bent blade's projection on x is shorter than 1.
void deformLeafMesh(Mesh& mesh, const LeafDeformation& deformation);

// ---- building from a LeafPrototype -------------------------------------------------------

/// Every value of a LeafPrototype that buildLeafMesh() uses, realized.
struct RealizedLeafShape {
    LeafOutlineParams outline;
    LeafDeformation deformation;
    unsigned subdivisions = 1;
    bool build_petiolule = false;
    vec3 leaf_offset{0.0f};
    /// PNG whose alpha gives the outline (empty: the procedural outline).
    std::string texture_file;
};

/// The image used for a leaflet: leaf_texture_file[leafletIndex], else [0], else "".
std::string leafTextureFile(const LeafPrototype& proto, int leafletIndex = 0);

/// Draws every random field of `proto` once, in a fixed order that does not depend on the
/// family or on whether a texture is used (so one leaf's draws never shift another's):
/// leaf_aspect_ratio, widest_point, tip_angle, base_angle, base_width, sinus_depth, lobes,
/// lobe_depth, serrations, serration_depth, midrib_fold_fraction, longitudinal_curvature,
/// lateral_curvature, petiole_roll, wave_period, wave_amplitude, leaf_buckle_length,
/// leaf_buckle_angle, pleats, pleat_depth. Draws outside a parameter's range are clamped. Throws
/// plantarch::Error for an unknown `shape`.
RealizedLeafShape realizeLeafShape(const LeafPrototype& proto, Rng& rng, int leafletIndex = 0);

/// Builds the blade: outline (procedural, or traced from texture_file), mesh, deformation,
/// normalization to unit length along the blade (x in [0, 1] while flat), optional
/// petiolule, then leaf_offset. With a petiolule the blade is moved forward by 0.08 and a
/// short tapered stalk fills x in [0, 0.1] before the whole leaf is normalized to unit length
/// along it (the flat leaf on its stalk spanning x in [0, 1]). UVs map the texture image (traced
/// leaves) or the blade's bounding box (procedural leaves) as meshLeafOutline() describes.
Mesh buildLeafMesh(const RealizedLeafShape& leaf);

/// realizeLeafShape() then buildLeafMesh(). The same stream state gives the same bytes.
/// `prototype_function`, `OBJ_model_file`, `color` and `unique_prototypes` are not read
/// here: choosing a custom or OBJ prototype, colouring and caching are the caller's job.
Mesh buildLeafPrototype(const LeafPrototype& proto, Rng& rng, int leafletIndex = 0);

}  // namespace plantarch
