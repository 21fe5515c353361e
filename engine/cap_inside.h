// Stage 3, from inside: culling.h culls a closed component's faces seen from
// behind where every ray towards them starts outside the solid. Where every ray
// towards a face starts inside the solid instead (the eye inside it: a close-up
// within a mesh, the near plane cutting it), the faces seen from the front are
// the hidden ones, by the same argument with the solid and its outside swapped:
// such a ray leaves the solid before it can enter it at the face.
//
// A ray starts on the near plane, so "inside" is the cap: the part of the near
// plane the component's cut curves enclose (the solid's section, or for an
// inward-oriented component the hollow's). On the screen the cap is bounded by
// the images of the cut segments, and a facet's image lies wholly inside it when
// it meets none of them (its box apart from theirs) and one of its points is
// inside (an odd number of them cross a ray from it). The same test tells where
// an image lies outside every cap (its point outside): every ray towards it
// starts outside the solid, so a face seen from behind is hidden there, though
// its box meets a cap's (culling.h decides on the boxes first).
#pragma once
#include <CGAL/Bbox_2.h>

#include <cstdint>
#include <vector>

#include "engine/culling.h"
#include "engine/exact_kernel.h"

namespace vismap::engine {
using namespace vismap::exact;
VISMAP_KERNEL_BEGIN

// One segment of the near plane's cut through a closed component, on the screen:
// the images of its ends (exact), a box containing them.
struct CutSegment {
  int component;
  P2 a, b;
  CGAL::Bbox_2 box;
};

// Per facet, for the facets marked in `candidate`: where its image (contained
// in box[f], with point[f] one of its points) lies against the caps its
// component's segments in `cut` enclose: +1 strictly inside one, -1 strictly
// outside them all (apart from every segment, its point outside), 0 not known
// (its box meets a segment's, or not a candidate, or its component has no cut).
// Every segment of a candidate's component must be in `cut`: the caller leaves
// out components whose cut it cannot list (a vertex on the near plane). On
// `threads` threads.
std::vector<std::int8_t> cap_sides(const ClosedComponents& cc, const std::vector<CutSegment>& cut,
                                   const std::vector<char>& candidate, const std::vector<CGAL::Bbox_2>& box,
                                   const std::vector<const P2*>& point, int threads = 1);

VISMAP_KERNEL_END
}  // namespace vismap::engine
