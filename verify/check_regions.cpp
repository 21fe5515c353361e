// Checks 4 and 5: the regions against a brute-force depth test at random
// points, and their total area against the exact area of the union of faces.
#include <array>

#include "verify/checks.h"
#include "verify/local.h"
#include "verify/rational.h"
#include "verify/union_area.h"

namespace vismap_check {
namespace {

std::uint64_t splitmix64(std::uint64_t& s) {
  std::uint64_t z = (s += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

constexpr unsigned kBits = 20;   // sample coordinates are k / 2^20 of the box

enum : long { kBackground = -1, kOnRing = -2 };

// Index of the region whose closure-free interior holds q, kBackground, or
// kOnRing; sets `overlap` to a second region when two hold it.
long map_region_at(const MapDoc& doc, const P2& q, long& overlap) {
  long found = kBackground;
  overlap = kBackground;
  for (std::uint32_t r : doc.region_grid.near(q)) {
    const MapRegion& reg = doc.regions[r];
    if (!reg.box.contains(q)) continue;
    Where w = locate(q, reg.outer);
    if (w == Where::Boundary) return kOnRing;
    if (w == Where::Outside) continue;
    bool in_hole = false;
    for (const auto& h : reg.holes) {
      Where wh = locate(q, h);
      if (wh == Where::Boundary) return kOnRing;
      in_hole = in_hole || wh == Where::Inside;
    }
    if (in_hole) continue;
    if (found == kBackground) found = static_cast<long>(r);
    else if (overlap == kBackground) overlap = static_cast<long>(r);
  }
  return found;
}

std::string label_name(long face) { return face < 0 ? "background" : "face " + std::to_string(face); }

void check_sample(Context& c, const P2& q) {
  PointLabel want = label_at(c.sc, q);
  if (!want.clean) return;
  long overlap = kBackground;
  long r = map_region_at(c.doc, q, overlap);
  if (r == kOnRing) return;
  ++c.rep.samples_checked;
  if (overlap != kBackground) {
    c.fail.add("regions: regions " + std::to_string(r) + " and " + std::to_string(overlap) + " overlap at " + str(q));
    return;
  }
  long got = r == kBackground ? -1 : static_cast<long>(c.doc.regions[r].face);
  if (got != want.face)
    c.fail.add("regions: at " + str(q) + " the visible surface is " + label_name(want.face) + " but the map has " +
               (r == kBackground ? std::string("no region") : "region " + std::to_string(r) + " (" + label_name(got) + ")"));
}

}  // namespace

void check_regions(Context& c) {
  // The box of everything projected and everything in the map, enlarged so
  // that regions outside the faces are sampled too.
  std::vector<P2> pts;
  for (const Piece& p : c.sc.pieces) pts.insert(pts.end(), p.xy.begin(), p.xy.end());
  for (const MapRegion& r : c.doc.regions) pts.insert(pts.end(), r.outer.begin(), r.outer.end());
  if (pts.empty()) return;
  Box b = box_of(pts);
  mpq_class w = b.xmax - b.xmin, h = b.ymax - b.ymin;
  if (w == 0) w = 1;
  if (h == 0) h = 1;
  mpq_class x0 = b.xmin - w / 8, y0 = b.ymin - h / 8;
  mpq_class sx = w * 5 / 4 / (1u << kBits), sy = h * 5 / 4 / (1u << kBits);
  std::uint64_t state = c.opt.seed;
  for (std::size_t i = 0; i < c.opt.samples; ++i) {
    std::uint64_t kx = splitmix64(state) >> (64 - kBits), ky = splitmix64(state) >> (64 - kBits);
    check_sample(c, P2{x0 + sx * kx, y0 + sy * ky});
  }
  // One point just inside each region, beside the middle of its first edge,
  // so that small regions are looked at too.
  for (const MapRegion& r : c.doc.regions) {
    const P2& a = r.outer[0];
    const P2& e = r.outer[1];
    mpq_class dx = e.x - a.x, dy = e.y - a.y;
    mpq_class tiny(1, 1u << kBits);
    check_sample(c, P2{(a.x + e.x) / 2 - dy * tiny, (a.y + e.y) / 2 + dx * tiny});
  }
}

void check_area(Context& c) {
  mpq_class got = 0;
  for (const MapRegion& r : c.doc.regions) {
    got += area2(r.outer);
    for (const auto& h : r.holes) got += area2(h);   // clockwise: negative
  }
  got /= 2;
  mpq_class want = union_area(c.sc);
  if (got != want)
    c.fail.add("area: the regions cover " + str(got) + " but the union of the projected faces is " + str(want));
}

}  // namespace vismap_check
