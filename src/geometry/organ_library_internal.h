#pragma once
// Shared pieces of the organ library (OrganLibrary.h): the family table entry, the parameter
// reader every family uses, the part collector that applies the prototype convention, and
// the mesh helpers (grids, closed bodies, tubes, petal sheets) the families are built from.

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/math.h"
#include "plantarch/OrganLibrary.h"

namespace plantarch::organs {

// ---- family table -----------------------------------------------------------------------

class Params;
/// Builds a family's prototype from a request whose parameters are already validated.
using FamilyBuilder = OrganPrototype (*)(const FloralPrototypeRequest&, const Params&, Rng&);

/// One family: its declaration (name, parameters) and its builder.
struct Family {
    FloralFamilyInfo info;
    FamilyBuilder build;
};

// Declarations, one per source file; each returns its families in table order.
std::vector<Family> flowerFamilies();
std::vector<Family> fruitFamilies();
std::vector<Family> podAndDrupeFamilies();
std::vector<Family> cerealFamilies();

/// The parameters of one request, validated against the family table. Reading a name the
/// family did not declare is a programming error (std::logic_error), so every parameter a
/// builder reads is declared (and documented) in exactly one place.
class Params {
public:
    /// Validates `given` against `info` (throws plantarch::Error).
    Params(const FloralFamilyInfo& info, const std::map<std::string, float>& given);
    float operator()(std::string_view name) const;
    int count(std::string_view name) const;  ///< a whole-number parameter
    bool flag(std::string_view name) const { return count(name) != 0; }
    /// Colour from the three parameters <prefix>_r, <prefix>_g, <prefix>_b.
    vec3 color(std::string_view prefix) const;

private:
    const FloralFamilyInfo* info_;
    const std::map<std::string, float>* given_;
};

/// Shorthand for the table: {name, default, min, max, doc}.
FloralParameterInfo real(const char* name, float def, float min, float max, const char* doc);
/// A whole-number parameter.
FloralParameterInfo whole(const char* name, int def, int min, int max, const char* doc);
/// Three parameters <prefix>_r/_g/_b (0..1) with the given default colour.
void addColor(std::vector<FloralParameterInfo>& table, const char* prefix, vec3 def,
              const char* what);

/// Resolution from `subdivisions`: base + perStep * s, with s = max(2, subdivisions).
unsigned resolution(unsigned subdivisions, float perStep, unsigned base);

/// Collects parts by material name and finishes the prototype: the main part first, empty
/// parts dropped, degenerate triangles removed, then one uniform scale and an x translation
/// so the bounding box spans x = 0 to 1.
class PartSet {
public:
    /// Declares the parts in output order (the first is the main part) with their colours.
    void declare(const std::string& name, vec3 color);
    /// Appends `mesh` to the part `name` (declared before).
    void add(const std::string& name, const Mesh& mesh);
    OrganPrototype finish();

private:
    std::vector<PrototypePart> parts_;
};

// ---- mesh helpers -------------------------------------------------------------------------

/// A grid of quads: rows + 1 rows of vertices (i = 0..rows) by `cols` (wrap) or cols + 1
/// (open) columns. An apex row is a single vertex (point(i, 0)), joined by a fan.
struct Grid {
    unsigned rows = 1;
    unsigned cols = 1;
    bool wrap = false;
    bool apexStart = false;
    bool apexEnd = false;
};
Mesh gridMesh(const Grid& grid, const std::function<vec3(unsigned i, unsigned j)>& point);

/// A closed body between two poles: point(u, theta) for u in [0, 1] (poles at u = 0 and 1,
/// asked with theta = 0) and theta in [0, 2 pi). Rows are spaced evenly in u. Triangles face
/// outward (the winding is fixed from the signed volume).
Mesh closedBody(unsigned rows, unsigned sides,
                const std::function<vec3(float u, float theta)>& point);

/// An ellipsoid with the given centre and semi-axis vectors (ax is the pole axis).
Mesh ellipsoid(vec3 centre, vec3 ax, vec3 ay, vec3 az, unsigned rows, unsigned sides);

/// A closed tube along `path` (>= 2 points) with one radius per point. Ends with a radius
/// above zero are capped flat; an end of radius zero becomes a point.
Mesh tube(std::span<const vec3> path, std::span<const float> radii, unsigned sides);
/// A straight tube tapering from r0 to r1 in `segments` pieces.
Mesh tube(vec3 a, vec3 b, float r0, float r1, unsigned sides, unsigned segments = 1);

/// A curved centre line: `segments` steps of length / segments from `start`, heading along
/// `direction` and turning by `bendDeg` degrees in total toward `toward` (perpendicular to
/// the direction), the turn spread evenly along the length. Returns segments + 1 points.
std::vector<vec3> arcPath(vec3 start, vec3 direction, vec3 toward, float length, float bendDeg,
                          unsigned segments);

/// A closed body around a centre line (>= 2 points): the cross-section at fraction u of the
/// length (0 and 1 are the pointed ends) is section(u, theta) = (along side, along normal),
/// where the normal starts as `up` (made perpendicular to the first segment) and is carried
/// along the path without twist, and side = tangent x normal.
Mesh sweptBody(std::span<const vec3> path, vec3 up, unsigned rows, unsigned sides,
               const std::function<vec2(float u, float theta)>& section);

/// Position, tangent, normal and side at fraction u of a path's length (frames as in
/// sweptBody).
struct PathPoint {
    vec3 position, tangent, normal, side;
};
PathPoint pathAt(std::span<const vec3> path, vec3 up, float u);

double signedVolume(const Mesh& mesh);
void flipWinding(Mesh& mesh);

/// A thin sheet shaped like a petal, sepal or bract. It starts at `origin` and leans from
/// `axis` toward `radial` (unit vectors, perpendicular) by an angle that changes from
/// baseAngle at its base to tipAngle at its tip; its width lies along axis x radial.
struct PetalSpec {
    float length = 1.0f;
    float width = 0.5f;       ///< full width at the widest point
    float widest = 0.6f;      ///< position of the widest point, fraction of the length
    float tip = 0.0f;         ///< 0 rounded tip .. 1 pointed tip
    float claw = 0.15f;       ///< width at the base, fraction of the width
    float baseAngle = 90.0f;  ///< degrees from `axis` at the base
    float tipAngle = 90.0f;   ///< degrees from `axis` at the tip
    /// Cross curvature: the margins rise toward the inner side (the side of +axis when the
    /// sheet is spread flat) by this fraction of the width; negative curls them outward.
    float cupping = 0.0f;
    float wave = 0.0f;      ///< margin wave amplitude, fraction of the width
    float waves = 3.0f;     ///< wave count along each margin
    float twistDeg = 0.0f;  ///< twist about the midrib from base to tip
    /// Offset along the sheet's inner normal, fraction of the length (avoids coincident
    /// overlapping petals).
    float lift = 0.0f;
};
Mesh petalMesh(const PetalSpec& spec, vec3 origin, vec3 axis, vec3 radial, unsigned rows,
               unsigned cols);

/// `count` pointed sepals around the +x axis, based on the circle of radius r0 at x = x0,
/// each leaning from +x by baseAngle (degrees) at its base to tipAngle at its tip; `phase`
/// turns the ring (radians). Calyces of fruit and flowers.
Mesh sepalStar(int count, float x0, float r0, float length, float width, float baseAngle,
               float tipAngle, float phase, unsigned rows, unsigned cols);

/// Half-width of a petal outline at u in [0, 1] for a width of 1 (see PetalSpec).
float petalHalfWidth(const PetalSpec& spec, float u);

/// The axes of an organ's own frame (+x along the organ).
inline const vec3 kX{1.0f, 0.0f, 0.0f};
inline const vec3 kY{0.0f, 1.0f, 0.0f};
inline const vec3 kZ{0.0f, 0.0f, 1.0f};

/// Unit vector (0, cos a, sin a): the radial direction at azimuth `a` about +x.
inline vec3 radialDir(float a) {
    return {0.0f, std::cos(a), std::sin(a)};
}

/// pow of the non-negative part of x (sin(pi) is slightly negative in floats).
inline float ppow(float x, float e) {
    return std::pow(std::max(x, 0.0f), e);
}

/// Smooth step from 0 (x <= a) to 1 (x >= b).
float smooth(float a, float b, float x);

/// Mixes a colour toward white (t > 0) or black (t < 0).
vec3 tint(vec3 color, float t);

}  // namespace plantarch::organs
