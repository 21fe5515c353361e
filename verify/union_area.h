// Exact area of the union of the projected faces that are not edge-on.
#pragma once
#include <gmpxx.h>

#include "verify/screen.h"

namespace vismap_check {

// Vertical slabs between consecutive critical x (vertices, and crossings of
// edges that are not buried inside another piece): inside a slab no two
// boundary edges of the union cross, so the covered set is a union of
// trapezoids whose area is exact. Each piece is filled with the even-odd rule.
mpq_class union_area(const Screen& sc);

}  // namespace vismap_check
