#pragma once
// Planar polygons: area, containment, simplicity, Douglas-Peucker simplification and a
// constrained Delaunay triangulation of a simple polygon refined with lattice points.
// Used by the leaf blades; not installed.

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace plantarch::polygon {

using glm::dvec2;

/// Shoelace area: positive for a counter-clockwise polygon.
double signedArea(const std::vector<dvec2>& poly);
/// Even-odd containment (points exactly on the boundary may go either way).
bool contains(const std::vector<dvec2>& poly, dvec2 p);
/// Distance from p to the nearest boundary edge.
double boundaryDistance(const std::vector<dvec2>& poly, dvec2 p);
/// Distance from p to the segment ab.
double segmentDistance(dvec2 p, dvec2 a, dvec2 b);
/// True when no two non-adjacent edges touch and no vertex repeats (O(n^2)).
bool isSimple(const std::vector<dvec2>& poly);
/// Douglas-Peucker simplification of an open polyline (both ends and the points listed in
/// `keep` are kept): the result stays within `tolerance` of every dropped point.
std::vector<dvec2> simplifyPolyline(const std::vector<dvec2>& line, double tolerance,
                                    const std::vector<std::size_t>& keep = {});

/// A triangle mesh of points; triangles counter-clockwise.
struct Triangulation {
    std::vector<dvec2> points;
    std::vector<std::array<std::uint32_t, 3>> triangles;
};

/// Triangulates a simple counter-clockwise polygon: ear clipping, then Lawson flips to the
/// constrained Delaunay triangulation (the polygon edges are the constraints), then
/// boundary edges are split into pieces no longer than `spacing` and points of a triangular
/// lattice of that spacing are inserted where they lie at least spacing / 2 inside. The
/// lattice has a row on y = 0, so a straight midrib there becomes a line of edges. The first
/// poly.size() points are the polygon's vertices in order. Throws plantarch::Error when the
/// polygon is degenerate (fewer than 3 vertices, zero area or not counter-clockwise).
/// `interior`, when not empty, replaces the lattice: those of its points that lie at least
/// spacing / 2 inside are inserted instead.
Triangulation triangulate(const std::vector<dvec2>& poly, double spacing,
                          const std::vector<dvec2>& interior = {});

}  // namespace plantarch::polygon
