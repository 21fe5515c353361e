// What the facet makers (world_facets.cpp, holed_faces.cpp) share about an
// input polygon: its distinct corners, a plane through it, its image in a
// coordinate plane, and whether a ring there is simple. Epick's points hold
// the input's doubles, on which its predicates are exact; nothing is
// constructed. Internal to the engine.
#pragma once
#include <cstdint>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include "engine/scene.h"

namespace vismap::engine {

using Q3 = CGAL::Epick::Point_3;
using Q2 = CGAL::Epick::Point_2;

// The ring's corners with their canonical ids, consecutive repeats (cyclically:
// the same vertex) dropped; into `ids` and `p`, cleared first.
void distinct_corners(const Scene& scene, const std::vector<std::uint32_t>& canon, const IndexRing& ring,
                      std::vector<std::uint32_t>& ids, std::vector<Q3>& p);

// Finds i1, the first corner distinct from p[0], and i2, the first after it not
// collinear with both; false when all corners are collinear (or fewer than 3).
bool find_plane(const std::vector<Q3>& p, std::size_t& i1, std::size_t& i2);

// The coordinate axis to drop so that the plane through a, b, c (not collinear)
// keeps its area: one along which its normal is not zero, decided exactly,
// preferring the largest component; and a point's image with it dropped.
int dominant_axis(const Q3& a, const Q3& b, const Q3& c);
Q2 drop_axis(const Q3& p, int axis);

// Whether a closed ring is simple, exactly: no two edges meet except neighbours
// at their shared corner, and there only (folding back along the same line
// overlaps). Edges are swept by x: only those whose x-ranges overlap are compared.
bool is_simple_ring(const std::vector<Q2>& q);

}  // namespace vismap::engine
