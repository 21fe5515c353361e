// Whether a closed ring of points in a plane is simple, exactly: no two edges
// meet except neighbours at their shared corner, and there only (folding back
// along the same line overlaps). Edges are swept by x, so only those whose
// x-ranges overlap are compared. Internal to the engine (CGAL's Epick points:
// the input's doubles, on which its predicates are exact).
#pragma once
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

namespace vismap::engine {

bool is_simple_ring(const std::vector<CGAL::Epick::Point_2>& q);

}  // namespace vismap::engine
