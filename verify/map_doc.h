// The map as read from JSON, after the format checks (check 1 of the checker).
#pragma once
#include <gmpxx.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/scene.h"
#include "verify/failures.h"
#include "verify/geom.h"

namespace vismap_check {

enum class Kind { Border, Silhouette, Crease, Smooth, Intersection };
const char* kind_name(Kind k);

struct MapRegion {
  std::uint32_t face = 0;
  std::vector<P2> outer;
  std::vector<std::vector<P2>> holes;
  Box box;                                  // of the outer ring
};

struct MapSegment {
  P2 from, to;
  Kind kind = Kind::Border;
  std::vector<std::uint32_t> faces;         // ascending, non-empty
  Box box;
};

struct MapDoc {
  bool usable = false;                      // false: too broken to check geometry
  bool perspective = false;
  std::array<std::array<mpq_class, 4>, 4> m;
  std::vector<MapRegion> regions;
  std::vector<MapSegment> segments;
  bool has_hidden = false;                  // the map has "hidden" (hidden lines were asked for)
  std::vector<MapSegment> hidden;
  BoxGrid region_grid, segment_grid;        // over the outer rings' and segments' boxes
  BoxGrid hidden_grid;                      // over the hidden segments' boxes
  std::vector<P2> vertices;                 // every ring vertex and segment end, by (x, y), unique
};

// The map's vertices on the closed segment [a, b].
std::vector<const P2*> vertices_on(const MapDoc& doc, const P2& a, const P2& b);

// Parses and checks the format (keys, canonical numbers, ring orientation, ...).
// Every problem goes to `fail`; returns what could be read.
MapDoc read_map(const std::string& json_text, const vismap::Scene& scene, Failures& fail);

std::string describe(const MapSegment& s);   // "from (..) to (..) kind [faces]"

}  // namespace vismap_check
