// The exact visibility map: what every engine produces and every exporter writes.
// Numbers are exact rationals (GMP); no CGAL type appears here.
#pragma once
#include <gmpxx.h>

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "vismap/vismap.h"

namespace vismap {

struct Point2 {
  mpq_class x, y;
};
bool operator<(const Point2& a, const Point2& b);   // lexicographic (x, then y)
bool operator==(const Point2& a, const Point2& b);

// A hidden line (spec: "hidden"): its own end points, from < to (lexicographic).
struct HiddenSegment {
  Point2 from, to;
  EdgeKind kind = EdgeKind::Border;
  std::vector<int> faces;                     // ascending
};

// Free-form counters and phase timings, written in insertion order.
struct Stats {
  std::vector<std::pair<std::string, double>> seconds;
  std::vector<std::pair<std::string, std::int64_t>> counts;
  void time(const std::string& name, double s) { seconds.emplace_back(name, s); }
  void count(const std::string& name, std::int64_t n) { counts.emplace_back(name, n); }
  std::int64_t counted(const std::string& name) const {   // 0 if never counted
    for (const auto& [k, v] : counts)
      if (k == name) return v;
    return 0;
  }
};

using Matrix4 = std::array<std::array<mpq_class, 4>, 4>;

struct VisibilityMap {
  std::string scene_file;
  std::size_t scene_faces = 0;
  bool perspective = false;
  Matrix4 view;                               // the exact matrix the engine used
  std::vector<Point2> vertices;               // distinct, in lexicographic order
  std::vector<Region> regions;                // canonical order (see map_canonical.cpp)
  bool has_regions = true;                    // false: computed for its lines alone (a lines-only
                                              // drawing); the JSON then has no "regions" key
  std::vector<Segment> segments;              // canonical order
  bool has_hidden = false;                    // hidden lines were asked for: the JSON has "hidden"
  std::vector<HiddenSegment> hidden;          // sorted by (from, to)
  const Point2& at(std::uint32_t v) const { return vertices[v]; }
  std::vector<Point2> points(const Ring& r) const {   // (for readers that want coordinates)
    std::vector<Point2> out;
    out.reserve(r.size());
    for (auto v : r) out.push_back(vertices[v]);
    return out;
  }
  Stats stats;
};

}  // namespace vismap
