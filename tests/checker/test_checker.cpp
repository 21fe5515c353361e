// The checker on hand-made scenes with hand-written correct maps: the correct
// map passes, and every mutation of it is caught.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "verify/checker.h"
#include "verify/json.h"
#include "verify/rational.h"
#include "verify/screen.h"
#include "verify/union_area.h"

namespace vc = vismap_check;
using vismap::Scene;
using vismap::Vec3;

namespace {

// ---- building scenes and maps in code ---------------------------------------

std::uint64_t mix(std::uint64_t& s) {
  std::uint64_t z = (s += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}


Scene scene_of(std::vector<Vec3> v, std::vector<std::vector<std::uint32_t>> f) {
  Scene s;
  s.file = "test.off";
  s.vertices = std::move(v);
  s.faces = std::move(f);
  return s;
}

using Pt = std::pair<std::string, std::string>;
struct Region {
  int face;
  std::vector<Pt> outer;
  std::vector<std::vector<Pt>> holes;
};
struct Segment {
  Pt from, to;
  std::string kind;
  std::vector<int> faces;
};
struct Map {
  std::size_t faces = 0;
  std::string projection = "orthographic";
  // Looking along (0,0,-1): r = (1,0,0), u = (0,1,0), depth = -z.
  std::vector<std::vector<std::string>> m = {{"1", "0", "0", "0"}, {"0", "1", "0", "0"}, {"0", "0", "-1", "0"}, {"0", "0", "0", "1"}};
  std::vector<Region> regions;
  std::vector<Segment> segments;
};

std::string q(const std::string& s) { return "\"" + s + "\""; }
std::string pt(const Pt& p) { return "[" + q(p.first) + "," + q(p.second) + "]"; }
std::string ring(const std::vector<Pt>& r) {
  std::string s = "[";
  for (std::size_t i = 0; i < r.size(); ++i) s += (i ? "," : "") + pt(r[i]);
  return s + "]";
}

std::string json(const Map& m) {
  std::string s = "{\"format\":\"vismap\",\"version\":1,\"scene\":{\"file\":\"test.off\",\"faces\":" +
                  std::to_string(m.faces) + "},\"projection\":" + q(m.projection) + ",\"view_matrix\":[";
  for (std::size_t i = 0; i < m.m.size(); ++i) {
    s += i ? ",[" : "[";
    for (std::size_t j = 0; j < m.m[i].size(); ++j) s += (j ? "," : "") + q(m.m[i][j]);
    s += "]";
  }
  s += "],\n\"regions\":[";
  for (std::size_t i = 0; i < m.regions.size(); ++i) {
    const Region& r = m.regions[i];
    s += std::string(i ? ",\n" : "") + "{\"face\":" + std::to_string(r.face) + ",\"outer\":" + ring(r.outer) + ",\"holes\":[";
    for (std::size_t h = 0; h < r.holes.size(); ++h) s += (h ? "," : "") + ring(r.holes[h]);
    s += "]}";
  }
  s += "],\n\"segments\":[";
  for (std::size_t i = 0; i < m.segments.size(); ++i) {
    const Segment& g = m.segments[i];
    s += std::string(i ? ",\n" : "") + "{\"from\":" + pt(g.from) + ",\"to\":" + pt(g.to) + ",\"kind\":" + q(g.kind) + ",\"faces\":[";
    for (std::size_t k = 0; k < g.faces.size(); ++k) s += (k ? "," : "") + std::to_string(g.faces[k]);
    s += "]}";
  }
  return s + "],\n\"stats\":{}}";
}

vc::Report check(const Scene& s, const Map& m, vc::Options opt = {}) {
  opt.samples = 400;
  return vc::check_map(s, json(m), opt);
}

std::string all(const vc::Report& r) {
  std::string s;
  for (const auto& f : r.failures) s += f + "\n";
  return s;
}

#define EXPECT_PASSES(rep)                   \
  do {                                       \
    vc::Report r_ = (rep);                   \
    EXPECT_TRUE(r_.ok) << all(r_);           \
  } while (0)
#define EXPECT_FAILS_WITH(rep, text)                                           \
  do {                                                                         \
    vc::Report r_ = (rep);                                                     \
    EXPECT_FALSE(r_.ok);                                                       \
    EXPECT_NE(all(r_).find(text), std::string::npos) << "wanted \"" << (text) << "\" in:\n" << all(r_); \
  } while (0)

// ---- the scenes ---------------------------------------------------------------

// One unit square in z = 0, facing +z, seen from above.
Scene square() { return scene_of({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2, 3}}); }
Map square_map() {
  Map m;
  m.faces = 1;
  m.regions = {{0, {{"0", "0"}, {"1", "0"}, {"1", "1"}, {"0", "1"}}, {}}};
  m.segments = {{{"0", "0"}, {"1", "0"}, "border", {0}},
                {{"1", "0"}, {"1", "1"}, "border", {0}},
                {{"0", "1"}, {"1", "1"}, "border", {0}},
                {{"0", "0"}, {"0", "1"}, "border", {0}}};
  return m;
}

// Face 0: [0,2]^2 at z = 0; face 1: [1,3]^2 at z = 1, nearer.
Scene two_squares() {
  return scene_of({{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {1, 1, 1}, {3, 1, 1}, {3, 3, 1}, {1, 3, 1}},
                  {{0, 1, 2, 3}, {4, 5, 6, 7}});
}
Map two_squares_map() {
  Map m;
  m.faces = 2;
  m.regions = {{0, {{"0", "0"}, {"2", "0"}, {"2", "1"}, {"1", "1"}, {"1", "2"}, {"0", "2"}}, {}},
               {1, {{"1", "1"}, {"2", "1"}, {"3", "1"}, {"3", "3"}, {"1", "3"}, {"1", "2"}}, {}}};
  m.segments = {{{"0", "0"}, {"2", "0"}, "border", {0}}, {{"2", "0"}, {"2", "1"}, "border", {0}},
                {{"0", "2"}, {"1", "2"}, "border", {0}}, {{"0", "0"}, {"0", "2"}, "border", {0}},
                {{"1", "1"}, {"2", "1"}, "border", {1}}, {{"2", "1"}, {"3", "1"}, "border", {1}},
                {{"3", "1"}, {"3", "3"}, "border", {1}}, {{"1", "3"}, {"3", "3"}, "border", {1}},
                {{"1", "2"}, {"1", "3"}, "border", {1}}, {{"1", "1"}, {"1", "2"}, "border", {1}}};
  return m;
}

// Face 0: [0,2]^2 at z = 0, behind face 1: triangle (1,1) (5/2,1) (1,5/2) at z = 1.
// The square shows as an L and, separately, its corner beyond the hypotenuse.
Scene square_behind_triangle() {
  return scene_of({{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {1, 1, 1}, {2.5, 1, 1}, {1, 2.5, 1}},
                  {{0, 1, 2, 3}, {4, 5, 6}});
}
Map square_behind_triangle_map() {
  Map m;
  m.faces = 2;
  m.regions = {
      {0, {{"0", "0"}, {"2", "0"}, {"2", "1"}, {"1", "1"}, {"1", "2"}, {"0", "2"}}, {}},
      {0, {{"2", "3/2"}, {"2", "2"}, {"3/2", "2"}}, {}},
      {1, {{"1", "1"}, {"2", "1"}, {"5/2", "1"}, {"2", "3/2"}, {"3/2", "2"}, {"1", "5/2"}, {"1", "2"}}, {}}};
  m.segments = {{{"0", "0"}, {"2", "0"}, "border", {0}},       {{"2", "0"}, {"2", "1"}, "border", {0}},
                {{"2", "3/2"}, {"2", "2"}, "border", {0}},     {{"3/2", "2"}, {"2", "2"}, "border", {0}},
                {{"0", "2"}, {"1", "2"}, "border", {0}},       {{"0", "0"}, {"0", "2"}, "border", {0}},
                {{"1", "1"}, {"2", "1"}, "border", {1}},       {{"2", "1"}, {"5/2", "1"}, "border", {1}},
                {{"2", "3/2"}, {"5/2", "1"}, "border", {1}},   {{"3/2", "2"}, {"2", "3/2"}, "border", {1}},
                {{"1", "5/2"}, {"3/2", "2"}, "border", {1}},   {{"1", "2"}, {"1", "5/2"}, "border", {1}},
                {{"1", "1"}, {"1", "2"}, "border", {1}}};
  return m;
}

// A roof seen from above: two slopes meeting at a right angle along x = 1.
Scene roof() {
  return scene_of({{0, 0, 0}, {1, 0, 1}, {1, 1, 1}, {0, 1, 0}, {2, 0, 0}, {2, 1, 0}},
                  {{0, 1, 2, 3}, {1, 4, 5, 2}});
}
Map roof_map() {
  Map m;
  m.faces = 2;
  m.regions = {{0, {{"0", "0"}, {"1", "0"}, {"1", "1"}, {"0", "1"}}, {}},
               {1, {{"1", "0"}, {"2", "0"}, {"2", "1"}, {"1", "1"}}, {}}};
  m.segments = {{{"0", "0"}, {"1", "0"}, "border", {0}}, {{"0", "1"}, {"1", "1"}, "border", {0}},
                {{"0", "0"}, {"0", "1"}, "border", {0}}, {{"1", "0"}, {"2", "0"}, "border", {1}},
                {{"2", "0"}, {"2", "1"}, "border", {1}}, {{"1", "1"}, {"2", "1"}, "border", {1}},
                {{"1", "0"}, {"1", "1"}, "crease", {0, 1}}};
  return m;
}

// Face 0: [0,2]^2 at z = 0; face 1 over the same square in the plane z = x - 1:
// they cross along x = 1, each showing on its own side.
Scene crossing() {
  return scene_of({{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {0, 0, -1}, {2, 0, 1}, {2, 2, 1}, {0, 2, -1}},
                  {{0, 1, 2, 3}, {4, 5, 6, 7}});
}
Map crossing_map() {
  Map m;
  m.faces = 2;
  m.regions = {{0, {{"0", "0"}, {"1", "0"}, {"1", "2"}, {"0", "2"}}, {}},
               {1, {{"1", "0"}, {"2", "0"}, {"2", "2"}, {"1", "2"}}, {}}};
  m.segments = {{{"0", "0"}, {"1", "0"}, "border", {0}},       {{"0", "2"}, {"1", "2"}, "border", {0}},
                {{"0", "0"}, {"0", "2"}, "border", {0}},       {{"1", "0"}, {"2", "0"}, "border", {1}},
                {{"1", "2"}, {"2", "2"}, "border", {1}},       {{"2", "0"}, {"2", "2"}, "border", {1}},
                {{"1", "0"}, {"1", "2"}, "intersection", {0, 1}}};
  return m;
}

// Perspective: eye at the origin looking down -z; near plane z = -1 (depth 0).
// X = x, Y = y, Z = -z - 1, W = -z.
std::vector<std::vector<std::string>> perspective_matrix() {
  return {{"1", "0", "0", "0"}, {"0", "1", "0", "0"}, {"0", "0", "-1", "-1"}, {"0", "0", "-1", "0"}};
}

// ---- the tests ----------------------------------------------------------------

TEST(Rational, CanonicalForms) {
  mpq_class v;
  std::string why;
  for (const char* ok : {"0", "-3", "7/16", "-123456789/1099511627776", "1"}) EXPECT_TRUE(vc::parse_canonical(ok, v, why)) << ok;
  for (const char* bad : {"2/4", "3/1", "-0", "+1", " 1", "01", "1/0", "0/5", "1.5", "", "-", "1/", "/2", "1/-2", "1/02", "-0/3", "1e3"})
    EXPECT_FALSE(vc::parse_canonical(bad, v, why)) << bad;
  ASSERT_TRUE(vc::parse_canonical("-7/16", v, why));
  EXPECT_EQ(v, mpq_class(-7, 16));
}

TEST(Json, ParsesAndRejects) {
  vc::Json j = vc::parse_json(R"( {"a": [1, -2.5e3, "x\u00e9\n"], "b": {"c": null, "d": true}} )");
  ASSERT_TRUE(j.is(vc::Json::Type::Object));
  EXPECT_EQ(j.get("a")->items[1].text, "-2.5e3");
  EXPECT_EQ(j.get("a")->items[2].text, "x\xc3\xa9\n");
  EXPECT_TRUE(j.get("b")->get("d")->boolean);
  for (const char* bad : {"{", "[1,]", "{\"a\":1,\"a\":2}", "01", "[1] x", "\"\\q\"", "{'a':1}", "nul"})
    EXPECT_THROW(vc::parse_json(bad), vc::JsonError) << bad;
  EXPECT_THROW(vc::parse_json(std::string(1000, '[')), vc::JsonError);
}

TEST(Screen, CreaseThresholdIsExact) {
  std::array<mpq_class, 3> a{1, 0, 0}, b{1, 1, 0}, c{0, 1, 0}, d{-1, 0, 0};
  mpq_class cos30(std::cos(30 * 3.14159265358979323846 / 180));
  EXPECT_TRUE(vc::is_crease(a, b, cos30));   // 45 degrees
  EXPECT_TRUE(vc::is_crease(a, c, cos30));
  EXPECT_FALSE(vc::is_crease(a, a, cos30));
  mpq_class cos100(std::cos(100 * 3.14159265358979323846 / 180));
  EXPECT_FALSE(vc::is_crease(a, c, cos100));   // 90 < 100
  EXPECT_TRUE(vc::is_crease(a, d, cos100));    // 180 > 100
  // cos = 3/5 and -3/5 exactly: equal is not below (strict <), either sign of c.
  std::array<mpq_class, 3> x{1, 0, 0}, p{3, 4, 0}, n{-3, 4, 0};
  mpq_class tiny(1, 1000000);
  EXPECT_FALSE(vc::is_crease(x, p, mpq_class(3, 5)));
  EXPECT_TRUE(vc::is_crease(x, p, mpq_class(3, 5) + tiny));
  EXPECT_FALSE(vc::is_crease(x, p, mpq_class(3, 5) - tiny));
  EXPECT_FALSE(vc::is_crease(x, n, mpq_class(-3, 5)));
  EXPECT_TRUE(vc::is_crease(x, n, mpq_class(-3, 5) + tiny));
  EXPECT_FALSE(vc::is_crease(x, n, mpq_class(-3, 5) - tiny));
  std::array<mpq_class, 3> g{1, 1, 0}, h{1, -1, 0};   // 90 degrees, dot 0
  EXPECT_FALSE(vc::is_crease(g, h, mpq_class(0)));
  EXPECT_TRUE(vc::is_crease(g, h, mpq_class(1, 1000)));
}

TEST(UnionArea, OverlapsAndHoles) {
  vc::Failures fail;
  vc::MapDoc doc;
  doc.usable = true;
  for (int i = 0; i < 4; ++i) doc.m[i][i] = 1;
  doc.m[2][2] = -1;
  EXPECT_EQ(vc::union_area(vc::make_screen(two_squares(), doc, 30, false, fail)), mpq_class(7));
  EXPECT_EQ(vc::union_area(vc::make_screen(square_behind_triangle(), doc, 30, false, fail)), mpq_class(17, 4));
  // A polygon drawn twice, and an unequal bow tie: not simple, so fanned from
  // its first corner, (2,0) (4,2) (4,0) and (2,0) (4,0) (2,1), areas 2 and 1,
  // overlapping in (2,0) (4,0) (8/3,2/3) of area 2/3.
  Scene s = scene_of({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {4, 2, 0}, {4, 0, 0}, {2, 1, 0}},
                     {{0, 1, 2, 3}, {0, 1, 2, 3}, {4, 5, 6, 7}});
  EXPECT_EQ(vc::union_area(vc::make_screen(s, doc, 30, false, fail)), mpq_class(1) + 2 + 1 - mpq_class(2, 3));
  EXPECT_EQ(fail.count(), 0u);
}

TEST(Geom, OrientAgreesWithCross) {
  std::uint64_t seed = 5;
  auto r = [&]() {
    std::uint64_t a = mix(seed), b = mix(seed);
    long num = long(a % 21) - 10;
    long den = long(b % 4) + 1;   // small: many exact zeros and ties
    return mpq_class(num, den);
  };
  for (int i = 0; i < 20000; ++i) {
    vc::P2 o{r(), r()}, a{r(), r()}, b{r(), r()};
    o.x.canonicalize();
    o.y.canonicalize();
    a.x.canonicalize();
    a.y.canonicalize();
    b.x.canonicalize();
    b.y.canonicalize();
    if (i % 3 == 0) b = vc::P2{o.x + (a.x - o.x) * 3, o.y + (a.y - o.y) * 3};   // collinear
    ASSERT_EQ(vc::orient(o, a, b), sgn(vc::cross(o, a, b)));
  }
}

TEST(Screen, DepthCmpAgreesWithDepthAt) {
  // Perspective pieces have big denominators: compare the integer shortcut
  // with plain rational evaluation at random points and depths.
  Scene s = scene_of({{-1, -1, -2.3}, {1.1, -1, -2}, {1, 1.3, -3.7}, {0.1, 0.2, -1.5}, {2, 0.3, -4}, {-0.7, 1.9, -2.2}},
                     {{0, 1, 2}, {3, 4, 5}});
  vc::Failures fail;
  vc::MapDoc doc;
  doc.usable = true;
  doc.perspective = true;
  doc.m[0][0] = 1;
  doc.m[1][1] = 1;
  doc.m[2][2] = -1;
  doc.m[2][3] = -1;
  doc.m[3][2] = -1;
  vc::Screen sc = vc::make_screen(s, doc, 30, false, fail);
  ASSERT_EQ(sc.pieces.size(), 2u);
  std::uint64_t seed = 3;
  for (const vc::Piece& p : sc.pieces)
    for (int i = 0; i < 2000; ++i) {
      vc::P2 q{mpq_class(long(mix(seed) % 2001) - 1000, 997), mpq_class(long(mix(seed) % 2001) - 1000, 1009)};
      q.x.canonicalize();
      q.y.canonicalize();
      mpq_class d = p.depth_at(q);
      if (i % 3 == 1) d += mpq_class(1, long(mix(seed) % 1000) + 1);
      if (i % 3 == 2) d -= mpq_class(1, long(mix(seed) % 1000) + 1);
      ASSERT_EQ(p.depth_cmp(q, d), sgn(mpq_class(p.depth_at(q) - d)));
    }
}

// Convex polygon (ccw) clipped by the ccw triangle t: their exact intersection.
std::vector<vc::P2> clip_convex(std::vector<vc::P2> poly, const std::vector<vc::P2>& t) {
  for (std::size_t e = 0; e < t.size() && !poly.empty(); ++e) {
    const vc::P2& a = t[e];
    const vc::P2& b = t[(e + 1) % t.size()];
    std::vector<vc::P2> out;
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const vc::P2& p = poly[i];
      const vc::P2& q = poly[(i + 1) % poly.size()];
      mpq_class sp = vc::cross(a, b, p), sq = vc::cross(a, b, q);
      if (sp >= 0) out.push_back(p);
      if ((sp > 0 && sq < 0) || (sp < 0 && sq > 0)) {
        mpq_class k = sp / (sp - sq);
        out.push_back(vc::P2{p.x + k * (q.x - p.x), p.y + k * (q.y - p.y)});
      }
    }
    poly = out;
  }
  return poly;
}

TEST(UnionArea, AgreesWithInclusionExclusion) {
  // Up to five random triangles on a small integer grid (shared vertices,
  // collinear and overlapping edges, containment...), union area by
  // inclusion-exclusion over exact convex intersections.
  std::uint64_t seed = 11;
  vc::MapDoc doc;
  doc.usable = true;
  for (int i = 0; i < 4; ++i) doc.m[i][i] = 1;
  for (int trial = 0; trial < 300; ++trial) {
    int n = 1 + int(mix(seed) % 5);
    Scene s;
    std::vector<std::vector<vc::P2>> tris;
    for (int k = 0; k < n; ++k) {
      std::vector<vc::P2> t;
      for (int v = 0; v < 3; ++v) {
        double x = double(mix(seed) % 5), y = double(mix(seed) % 5);
        s.vertices.push_back({x, y, double(k)});
        t.push_back(vc::P2{x, y});
      }
      s.faces.push_back({std::uint32_t(3 * k), std::uint32_t(3 * k + 1), std::uint32_t(3 * k + 2)});
      mpq_class a = vc::cross(t[0], t[1], t[2]);
      if (a < 0) std::swap(t[1], t[2]);
      if (a != 0) tris.push_back(t);
    }
    mpq_class want = 0;
    for (unsigned mask = 1; mask < (1u << tris.size()); ++mask) {
      std::vector<vc::P2> poly;
      int bits = 0;
      for (std::size_t k = 0; k < tris.size(); ++k)
        if (mask & (1u << k)) {
          poly = bits++ == 0 ? tris[k] : clip_convex(poly, tris[k]);
        }
      mpq_class area = poly.size() >= 3 ? mpq_class(vc::area2(poly) / 2) : mpq_class(0);
      want += bits % 2 ? area : mpq_class(-area);
    }
    vc::Failures fail;
    EXPECT_EQ(vc::union_area(vc::make_screen(s, doc, 30, false, fail)), want) << "trial " << trial;
  }
}

TEST(Checker, SquarePasses) {
  vc::Report r = check(square(), square_map());
  EXPECT_TRUE(r.ok) << all(r);
  EXPECT_GT(r.samples_checked, 100u);
  EXPECT_GT(r.segment_points_checked, 8u);
  EXPECT_EQ(r.edge_points_checked, 4u);   // one stretch per edge
}

TEST(Checker, SquareMutations) {
  Scene s = square();
  {
    Map m = square_map();   // clockwise outer ring
    std::reverse(m.regions[0].outer.begin(), m.regions[0].outer.end());
    EXPECT_FAILS_WITH(check(s, m), "not counter-clockwise");
  }
  {
    Map m = square_map();   // a closing vertex repeated
    m.regions[0].outer.push_back({"0", "0"});
    EXPECT_FAILS_WITH(check(s, m), "closing vertex");
  }
  {
    Map m = square_map();
    m.regions[0].outer[1] = {"2/2", "0"};
    EXPECT_FAILS_WITH(check(s, m), "not in lowest terms");
    m.regions[0].outer[1] = {"1/1", "0"};
    EXPECT_FAILS_WITH(check(s, m), "denominator 1");
    m.regions[0].outer[1] = {"1", "-0"};
    EXPECT_FAILS_WITH(check(s, m), "\"-0\"");
  }
  {
    Map m = square_map();
    m.segments[0].from = {"1", "0"};
    EXPECT_FAILS_WITH(check(s, m), "from == to");
  }
  {
    Map m = square_map();
    m.segments[0].kind = "outline";
    EXPECT_FAILS_WITH(check(s, m), "kind is not one of");
  }
  {
    Map m = square_map();
    m.segments[0].faces = {};
    EXPECT_FAILS_WITH(check(s, m), "non-empty");
  }
  {
    Map m = square_map();
    m.m[3] = {"0", "0", "1/2", "1"};
    EXPECT_FAILS_WITH(check(s, m), "last row");
  }
  {
    Map m = square_map();
    m.faces = 2;
    EXPECT_FAILS_WITH(check(s, m), "scene.faces");
  }
  {
    Map m = square_map();   // the map of a square seen from the other side
    m.m = {{"-1", "0", "0", "0"}, {"0", "1", "0", "0"}, {"0", "0", "1", "0"}, {"0", "0", "0", "1"}};
    EXPECT_FAILS_WITH(check(s, m), "regions:");
  }
  EXPECT_FAILS_WITH(vc::check_map(s, json(square_map()).substr(1), {}), "format: JSON");
  {
    std::string j = json(square_map());
    j.replace(j.find("\"version\":1"), 11, "\"version\":2");
    EXPECT_FAILS_WITH(vc::check_map(s, j, {}), "version");
  }
}

TEST(Checker, TwoSquaresPassAndMutationsFail) {
  Scene s = two_squares();
  EXPECT_PASSES(check(s, two_squares_map()));
  {
    Map m = two_squares_map();   // relabelled region
    m.regions[1].face = 0;
    EXPECT_FAILS_WITH(check(s, m), "the visible surface is face 1");
  }
  {
    Map m = two_squares_map();   // region removed
    m.regions.erase(m.regions.begin());
    EXPECT_FAILS_WITH(check(s, m), "but the map has no region");
    EXPECT_FAILS_WITH(check(s, m), "area:");
  }
  {
    Map m = two_squares_map();   // the back square drawn whole: overlap
    m.regions[0].outer = {{"0", "0"}, {"2", "0"}, {"2", "2"}, {"0", "2"}};
    EXPECT_FAILS_WITH(check(s, m), "overlap at");
  }
  {
    Map m = two_squares_map();   // a hidden line added
    m.segments.push_back({{"2", "1"}, {"2", "2"}, "border", {0}});
    EXPECT_FAILS_WITH(check(s, m), "hidden");
  }
  {
    Map m = two_squares_map();   // a visible line removed
    m.segments.erase(m.segments.begin());
    EXPECT_FAILS_WITH(check(s, m), "coverage: no segment");
  }
  {
    Map m = two_squares_map();   // wrong faces
    m.segments[4].faces = {0};
    EXPECT_FAILS_WITH(check(s, m), "the first visible line there is border [1]");
  }
  {
    Map m = two_squares_map();   // two segments where the canonical map has them split, overlapping
    m.segments.push_back({{"1", "1"}, {"3", "1"}, "border", {1}});
    EXPECT_FAILS_WITH(check(s, m), "topology:");
  }
  {
    Map m = two_squares_map();   // non-canonical numbers
    m.regions[1].outer[2] = {"3/1", "1"};
    EXPECT_FAILS_WITH(check(s, m), "denominator 1");
    m = two_squares_map();
    m.regions[1].outer[2] = {"6/2", "1"};
    EXPECT_FAILS_WITH(check(s, m), "lowest terms");
  }
  {
    Map m = two_squares_map();   // a segment across a region: not a line of the scene
    m.segments.push_back({{"1/2", "1/2"}, {"1/2", "3/2"}, "border", {0}});
    EXPECT_FAILS_WITH(check(s, m), "no edge piece or intersection line");
  }
}

TEST(Checker, SquareBehindTrianglePassesAndMutationsFail) {
  Scene s = square_behind_triangle();
  vc::Report r = check(s, square_behind_triangle_map());
  EXPECT_TRUE(r.ok) << all(r);
  {
    Map m = square_behind_triangle_map();   // the small corner region lost
    m.regions.erase(m.regions.begin() + 1);
    EXPECT_FAILS_WITH(check(s, m), "area: the regions cover 33/8 but the union of the projected faces is 17/4");
  }
  {
    Map m = square_behind_triangle_map();   // the corner given to the triangle
    m.regions[1].face = 1;
    EXPECT_FAILS_WITH(check(s, m), "region 1 (face 1)");
  }
  {
    Map m = square_behind_triangle_map();   // the hidden piece of the square's edge
    m.segments.push_back({{"2", "1"}, {"2", "3/2"}, "border", {0}});
    EXPECT_FAILS_WITH(check(s, m), "hidden (border [0])");
  }
  {
    Map m = square_behind_triangle_map();
    m.regions[2].outer[3] = {"4/2", "3/2"};
    EXPECT_FAILS_WITH(check(s, m), "\"4/2\" is not canonical");
    m.regions[2].outer[3] = {"2", "6/4"};
    EXPECT_FAILS_WITH(check(s, m), "\"6/4\" is not canonical");
  }
  {
    Map m = square_behind_triangle_map();   // the hypotenuse segment ends too early
    m.segments[8].to = {"9/4", "5/4"};
    EXPECT_FAILS_WITH(check(s, m), "coverage:");
    m.segments[8].to = {"17/8", "11/8"};
    EXPECT_FAILS_WITH(check(s, m), "coverage: no segment at (37/16, 19/16)");
  }
  {
    Map m = square_behind_triangle_map();   // a visible piece split for nothing
    m.segments[8].to = {"9/4", "5/4"};
    m.segments.push_back({{"9/4", "5/4"}, {"5/2", "1"}, "border", {1}});
    EXPECT_FAILS_WITH(check(s, m), "topology: superfluous vertex at (9/4, 5/4)");
  }
}

TEST(Checker, RoofCreaseKindsAndAngle) {
  Scene s = roof();
  EXPECT_PASSES(check(s, roof_map()));
  {
    Map m = roof_map();   // wrong kind
    m.segments[6].kind = "silhouette";
    EXPECT_FAILS_WITH(check(s, m), "the first visible line there is crease [0,1]");
  }
  {
    Map m = roof_map();   // wrong faces
    m.segments[0].faces = {1};
    EXPECT_FAILS_WITH(check(s, m), "the first visible line there is border [0]");
  }
  {
    Map m = roof_map();   // crease missing
    m.segments.pop_back();
    EXPECT_FAILS_WITH(check(s, m), "coverage: no segment");
  }
  // At a 100-degree threshold the right-angle ridge is smooth: not drawn...
  vc::Options wide;
  wide.crease_deg = 100;
  EXPECT_FAILS_WITH(check(s, roof_map(), wide), "not drawn (smooth [0,1])");
  Map no_ridge = roof_map();
  no_ridge.segments.pop_back();
  EXPECT_PASSES(check(s, no_ridge, wide));
  // ...unless smooth edges are asked for.
  wide.smooth = true;
  Map smooth_ridge = roof_map();
  smooth_ridge.segments[6].kind = "smooth";
  EXPECT_PASSES(check(s, smooth_ridge, wide));
  EXPECT_FAILS_WITH(check(s, smooth_ridge), "smooth edges were not asked for");
}

TEST(Checker, RoofFromBelowIsSilhouetteFree) {
  // Seen from below both faces are back-facing: still regions, still a crease.
  Scene s = roof();
  Map m = roof_map();
  m.m = {{"1", "0", "0", "0"}, {"0", "-1", "0", "0"}, {"0", "0", "1", "0"}, {"0", "0", "0", "1"}};
  for (auto& r : m.regions) {
    for (auto& p : r.outer) p.second = p.second == "0" ? "0" : "-" + p.second;
    std::reverse(r.outer.begin(), r.outer.end());
  }
  for (auto& g : m.segments) {
    g.from.second = g.from.second == "0" ? "0" : "-" + g.from.second;
    g.to.second = g.to.second == "0" ? "0" : "-" + g.to.second;
  }
  EXPECT_PASSES(check(s, m));
}

TEST(Checker, SilhouetteOfAFold) {
  // Face 0 faces the eye; face 1 folds back under it: shared edge is a silhouette.
  Scene s = scene_of({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 1, -1}},
                     {{0, 1, 2, 3}, {0, 3, 5, 4}});
  // Face 1 (x = 0 .. 0) is edge-on here: it projects onto the segment x = 0.
  Map m;
  m.faces = 2;
  m.regions = {{0, {{"0", "0"}, {"1", "0"}, {"1", "1"}, {"0", "1"}}, {}}};
  m.segments = {{{"0", "0"}, {"1", "0"}, "border", {0}},
                {{"1", "0"}, {"1", "1"}, "border", {0}},
                {{"0", "1"}, {"1", "1"}, "border", {0}},
                {{"0", "0"}, {"0", "1"}, "silhouette", {0, 1}}};
  EXPECT_PASSES(check(s, m));
  m.segments[3] = {{"0", "0"}, {"0", "1"}, "border", {0}};
  EXPECT_FAILS_WITH(check(s, m), "silhouette [0,1]");
}

TEST(Checker, IntersectionLine) {
  Scene s = crossing();
  EXPECT_PASSES(check(s, crossing_map()));
  {
    Map m = crossing_map();
    m.segments.pop_back();
    EXPECT_FAILS_WITH(check(s, m), "coverage: no segment at (1, ");
  }
  {
    Map m = crossing_map();
    m.segments.back().kind = "crease";
    EXPECT_FAILS_WITH(check(s, m), "the first visible line there is intersection [0,1]");
  }
  {
    Map m = crossing_map();   // the nearer edge of the coincident pair is face 0's on the left
    m.segments[2].faces = {1};
    EXPECT_FAILS_WITH(check(s, m), "border [0]");
  }
  {
    Map m = crossing_map();   // the bottom edge not split where the two edges cross in 3D
    m.segments[0] = {{"0", "0"}, {"2", "0"}, "border", {0}};
    m.segments.erase(m.segments.begin() + 3);
    EXPECT_FAILS_WITH(check(s, m), "border [1]");
  }
}

TEST(Checker, CoplanarOverlapLowestIndexWins) {
  // Two equal squares in the same plane: face 0 is visible, edges shared.
  Scene s = scene_of({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2, 3}, {0, 1, 2, 3}});
  Map m = square_map();
  m.faces = 2;
  // Both faces share every edge; both front-facing, parallel normals: smooth, not drawn.
  m.segments.clear();
  EXPECT_PASSES(check(s, m));
  m.regions[0].face = 1;
  EXPECT_FAILS_WITH(check(s, m), "the visible surface is face 0");
}

TEST(Checker, NonPlanarQuadIsAFan) {
  // A non-planar quad: fan from vertex 0 splits it along (0,0)-(1,1); the
  // diagonal is never drawn and the face is one region.
  Scene s = scene_of({{0, 0, 0}, {1, 0, 0.25}, {1, 1, 0}, {0, 1, 0.5}}, {{0, 1, 2, 3}});
  Map m = square_map();
  EXPECT_PASSES(check(s, m));
  m.segments.push_back({{"0", "0"}, {"1", "1"}, "border", {0}});
  EXPECT_FAILS_WITH(check(s, m), "no edge piece or intersection line");
}

TEST(Checker, DegenerateFacesAreDropped) {
  Scene s = scene_of({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 2, 0}, {5, 5, 5}},
                     {{0, 1, 2, 3}, {0, 2, 4}, {5, 5, 5}, {0, 1}});
  Map m = square_map();
  m.faces = 4;
  EXPECT_PASSES(check(s, m));
}

TEST(Checker, EmptyScene) {
  Scene s = scene_of({}, {});
  Map m;
  EXPECT_PASSES(check(s, m));
}

TEST(Checker, PerspectiveSquare) {
  Scene s = scene_of({{-1, -1, -2}, {1, -1, -2}, {1, 1, -2}, {-1, 1, -2}}, {{0, 1, 2, 3}});
  Map m;
  m.faces = 1;
  m.projection = "perspective";
  m.m = perspective_matrix();
  m.regions = {{0, {{"-1/2", "-1/2"}, {"1/2", "-1/2"}, {"1/2", "1/2"}, {"-1/2", "1/2"}}, {}}};
  m.segments = {{{"-1/2", "-1/2"}, {"1/2", "-1/2"}, "border", {0}},
                {{"1/2", "-1/2"}, {"1/2", "1/2"}, "border", {0}},
                {{"-1/2", "1/2"}, {"1/2", "1/2"}, "border", {0}},
                {{"-1/2", "-1/2"}, {"-1/2", "1/2"}, "border", {0}}};
  EXPECT_PASSES(check(s, m));
  m.projection = "orthographic";
  EXPECT_FAILS_WITH(check(s, m), "last row");
}

TEST(Checker, PerspectiveClipsAtTheNearPlane) {
  // A floor strip from z = -1/2 (in front of the near plane z = -1) to z = -3.
  Scene s = scene_of({{-1, -1, -0.5}, {1, -1, -0.5}, {1, -1, -3}, {-1, -1, -3}}, {{0, 1, 2, 3}});
  Map m;
  m.faces = 1;
  m.projection = "perspective";
  m.m = perspective_matrix();
  m.regions = {{0, {{"-1", "-1"}, {"1", "-1"}, {"1/3", "-1/3"}, {"-1/3", "-1/3"}}, {}}};
  m.segments = {{{"1", "-1"}, {"1/3", "-1/3"}, "border", {0}},
                {{"-1/3", "-1/3"}, {"1/3", "-1/3"}, "border", {0}},
                {{"-1", "-1"}, {"-1/3", "-1/3"}, "border", {0}}};
  EXPECT_PASSES(check(s, m));   // the cut at the near plane need not be drawn...
  m.segments.push_back({{"-1", "-1"}, {"1", "-1"}, "border", {0}});
  EXPECT_PASSES(check(s, m));   // ...but may be, as a border
  m.regions[0].outer[0] = {"-2", "-2"};
  m.regions[0].outer[1] = {"2", "-2"};
  EXPECT_FAILS_WITH(check(s, m), "regions:");
}

TEST(Checker, PerspectiveIntersectionAndHiding) {
  // Face 0: z = -3 over [-1,1]^2; face 1: z = x - 3 over the same x, y. They
  // cross along x = 0; the eye sees face 1 on the right, face 0 on the left.
  Scene s = scene_of({{-1, -1, -3}, {1, -1, -3}, {1, 1, -3}, {-1, 1, -3}, {-1, -1, -4}, {1, -1, -2}, {1, 1, -2}, {-1, 1, -4}},
                     {{0, 1, 2, 3}, {4, 5, 6, 7}});
  Map m;
  m.faces = 2;
  m.projection = "perspective";
  m.m = perspective_matrix();
  m.regions = {{0, {{"-1/3", "-1/3"}, {"0", "-1/3"}, {"0", "1/3"}, {"-1/3", "1/3"}}, {}},
               {1, {{"0", "-1/3"}, {"1/2", "-1/2"}, {"1/2", "1/2"}, {"0", "1/3"}}, {}}};
  m.segments = {{{"-1/3", "-1/3"}, {"0", "-1/3"}, "border", {0}},   {{"-1/3", "-1/3"}, {"-1/3", "1/3"}, "border", {0}},
                {{"-1/3", "1/3"}, {"0", "1/3"}, "border", {0}},     {{"0", "-1/3"}, {"1/2", "-1/2"}, "border", {1}},
                {{"1/2", "-1/2"}, {"1/2", "1/2"}, "border", {1}},   {{"0", "1/3"}, {"1/2", "1/2"}, "border", {1}},
                {{"0", "-1/3"}, {"0", "1/3"}, "intersection", {0, 1}}};
  EXPECT_PASSES(check(s, m));
  {
    Map bad = m;   // face 0's hidden right edge
    bad.segments.push_back({{"1/3", "-1/3"}, {"1/3", "1/3"}, "border", {0}});
    EXPECT_FAILS_WITH(check(s, bad), "hidden (border [0])");
  }
  {
    Map bad = m;   // face 1's hidden left edge
    bad.segments.push_back({{"-1/4", "-1/4"}, {"-1/4", "1/4"}, "border", {1}});
    EXPECT_FAILS_WITH(check(s, bad), "hidden (border [1])");
  }
  {
    Map bad = m;   // the regions swapped
    std::swap(bad.regions[0].face, bad.regions[1].face);
    EXPECT_FAILS_WITH(check(s, bad), "regions:");
  }
}

TEST(Checker, NonFiniteInputIsAFailureNotACrash) {
  Scene s = square();
  s.vertices[2].x = std::nan("");
  EXPECT_FAILS_WITH(check(s, square_map()), "not finite");
  vc::Options o;
  o.crease_deg = std::numeric_limits<double>::infinity();
  EXPECT_FAILS_WITH(check(square(), square_map(), o), "crease angle");
}

TEST(Checker, StatsAndUnknownKeys) {
  std::string j = json(square_map());
  std::string k = j;
  k.replace(k.find("\"stats\":{}"), 10, "\"stats\":{\"seconds\":{\"total\":0.5}},\"extra\":1");
  EXPECT_FAILS_WITH(vc::check_map(square(), k, {}), "unknown top-level key \"extra\"");
  k = j;
  k.replace(k.find("\"stats\":{}"), 10, "\"stats\":{\"faces_dropped\":0}");
  EXPECT_TRUE(vc::check_map(square(), k, {}).ok);
}

TEST(Checker, TJunctionMatchesEdgesGeometrically) {
  // Face 0 = [0,2]x[0,1]; faces 1, 2 = [0,1]x[1,2], [1,2]x[1,2], all in z = 0:
  // face 0's top edge is shared with face 1 on x < 1 and with face 2 on x > 1.
  Scene s = scene_of({{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}, {2, 2, 0}},
                     {{0, 1, 2, 3}, {3, 4, 5, 6}, {4, 2, 7, 5}});
  Map m;
  m.faces = 3;
  m.regions = {{0, {{"0", "0"}, {"2", "0"}, {"2", "1"}, {"1", "1"}, {"0", "1"}}, {}},
               {1, {{"0", "1"}, {"1", "1"}, {"1", "2"}, {"0", "2"}}, {}},
               {2, {{"1", "1"}, {"2", "1"}, {"2", "2"}, {"1", "2"}}, {}}};
  m.segments = {{{"0", "0"}, {"2", "0"}, "border", {0}}, {{"2", "0"}, {"2", "1"}, "border", {0}},
                {{"2", "1"}, {"2", "2"}, "border", {2}}, {{"1", "2"}, {"2", "2"}, "border", {2}},
                {{"0", "2"}, {"1", "2"}, "border", {1}}, {{"0", "1"}, {"0", "2"}, "border", {1}},
                {{"0", "0"}, {"0", "1"}, "border", {0}}};
  EXPECT_PASSES(check(s, m));
  vc::Options smooth;
  smooth.smooth = true;
  Map ms = m;
  ms.segments.push_back({{"0", "1"}, {"1", "1"}, "smooth", {0, 1}});
  ms.segments.push_back({{"1", "1"}, {"2", "1"}, "smooth", {0, 2}});
  ms.segments.push_back({{"1", "1"}, {"1", "2"}, "smooth", {1, 2}});
  EXPECT_PASSES(check(s, ms, smooth));
  EXPECT_FAILS_WITH(check(s, m, smooth), "coverage: no segment");
  Map merged = ms;   // the two pieces of the T written as one
  merged.segments.erase(merged.segments.end() - 3, merged.segments.end() - 1);
  merged.segments.push_back({{"0", "1"}, {"2", "1"}, "smooth", {0, 1}});
  EXPECT_FAILS_WITH(check(s, merged, smooth), "smooth [0,2]");
}

TEST(Checker, PolygonSoupSharesEdgesByPosition) {
  // The roof again, every face with its own copies of the vertices.
  Scene s = scene_of({{0, 0, 0}, {1, 0, 1}, {1, 1, 1}, {0, 1, 0}, {1, 0, 1}, {2, 0, 0}, {2, 1, 0}, {1, 1, 1}},
                     {{0, 1, 2, 3}, {4, 5, 6, 7}});
  EXPECT_PASSES(check(s, roof_map()));
}

TEST(Checker, SilhouetteOverABackFace) {
  // Face 1 folds back under face 0 from their shared edge x = 0: back-facing,
  // hidden, and the shared edge is a silhouette.
  Scene s = scene_of({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 1, -1}, {0.5, 0, -1}},
                     {{0, 1, 2, 3}, {0, 3, 4, 5}});
  Map m = square_map();
  m.faces = 2;
  m.segments[3] = {{"0", "0"}, {"0", "1"}, "silhouette", {0, 1}};
  EXPECT_PASSES(check(s, m));
  m.segments.push_back({{"1/2", "0"}, {"1/2", "1"}, "border", {1}});
  EXPECT_FAILS_WITH(check(s, m), "hidden (border [1])");
}

TEST(Checker, CoplanarOverlapWithHole) {
  // Same plane: the lower index wins where they overlap.
  Scene small_first = scene_of({{1, 1, 0}, {2, 1, 0}, {2, 2, 0}, {1, 2, 0}, {0, 0, 0}, {3, 0, 0}, {3, 3, 0}, {0, 3, 0}},
                               {{0, 1, 2, 3}, {4, 5, 6, 7}});
  Map m;
  m.faces = 2;
  std::vector<Pt> inner{{"1", "1"}, {"2", "1"}, {"2", "2"}, {"1", "2"}};
  std::vector<Pt> outer{{"0", "0"}, {"3", "0"}, {"3", "3"}, {"0", "3"}};
  std::vector<Pt> hole(inner.rbegin(), inner.rend());
  m.regions = {{0, inner, {}}, {1, outer, {hole}}};
  for (int i = 0; i < 4; ++i) {
    m.segments.push_back({inner[i], inner[(i + 1) % 4], "border", {0}});
    m.segments.push_back({outer[i], outer[(i + 1) % 4], "border", {1}});
  }
  EXPECT_PASSES(check(small_first, m));
  {
    Map bad = m;   // hole written counter-clockwise
    bad.regions[1].holes[0] = inner;
    EXPECT_FAILS_WITH(check(small_first, bad), "(hole) is not clockwise");
  }
  {
    Map bad = m;   // hole forgotten: the regions overlap
    bad.regions[1].holes.clear();
    EXPECT_FAILS_WITH(check(small_first, bad), "overlap at");
  }
  // Big square first: it wins everywhere and the small one's edges are hidden.
  Scene big_first = scene_of({{0, 0, 0}, {3, 0, 0}, {3, 3, 0}, {0, 3, 0}, {1, 1, 0}, {2, 1, 0}, {2, 2, 0}, {1, 2, 0}},
                             {{0, 1, 2, 3}, {4, 5, 6, 7}});
  Map b;
  b.faces = 2;
  b.regions = {{0, outer, {}}};
  for (int i = 0; i < 4; ++i) b.segments.push_back({outer[i], outer[(i + 1) % 4], "border", {0}});
  EXPECT_PASSES(check(big_first, b));
  b.segments.push_back({inner[0], inner[1], "border", {1}});
  EXPECT_FAILS_WITH(check(big_first, b), "hidden (border [1])");
}

TEST(Checker, NonPlanarFaceHidesAlongItsDiagonal) {
  // A non-planar quad in front; behind it a triangle whose hypotenuse lies
  // exactly under the fan diagonal (0,0)-(2,2): hidden there too.
  Scene s = scene_of({{0, 0, 1}, {2, 0, 1.5}, {2, 2, 1}, {0, 2, 1.5}, {0, 0, 0}, {2, 0, 0}, {2, 2, 0}},
                     {{0, 1, 2, 3}, {4, 5, 6}});
  Map m;
  m.faces = 2;
  m.regions = {{0, {{"0", "0"}, {"2", "0"}, {"2", "2"}, {"0", "2"}}, {}}};
  m.segments = {{{"0", "0"}, {"2", "0"}, "border", {0}}, {{"2", "0"}, {"2", "2"}, "border", {0}},
                {{"0", "2"}, {"2", "2"}, "border", {0}}, {{"0", "0"}, {"0", "2"}, "border", {0}}};
  EXPECT_PASSES(check(s, m));
  m.segments.push_back({{"0", "0"}, {"2", "2"}, "border", {1}});
  EXPECT_FAILS_WITH(check(s, m), "hidden (border [1])");
}

TEST(Checker, EdgeOnFaceHidesNothingButHasEdges) {
  // Face 1 is a wall in the plane x = 1 above the square: edge-on, it hides
  // nothing, but its (border) edges are lines, drawn over face 0's region.
  Scene s = scene_of({{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {1, 0, 0.5}, {1, 2, 0.5}, {1, 2, 1.5}, {1, 0, 1.5}},
                     {{0, 1, 2, 3}, {4, 5, 6, 7}});
  Map m;
  m.faces = 2;
  m.regions = {{0, {{"0", "0"}, {"1", "0"}, {"2", "0"}, {"2", "2"}, {"1", "2"}, {"0", "2"}}, {}}};
  m.segments = {{{"0", "0"}, {"1", "0"}, "border", {0}}, {{"1", "0"}, {"2", "0"}, "border", {0}},
                {{"2", "0"}, {"2", "2"}, "border", {0}}, {{"1", "2"}, {"2", "2"}, "border", {0}},
                {{"0", "2"}, {"1", "2"}, "border", {0}}, {{"0", "0"}, {"0", "2"}, "border", {0}},
                {{"1", "0"}, {"1", "2"}, "border", {1}}};
  EXPECT_PASSES(check(s, m));
  m.segments.pop_back();
  EXPECT_FAILS_WITH(check(s, m), "coverage: no segment at (1, ");
}

TEST(Checker, ThreeFacesOnAnEdgeMakeACrease) {
  // Two coplanar squares side by side, and a fin on their shared edge x = 1.
  for (double fin_z : {-1.0, 1.0}) {
    Scene s = scene_of({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {2, 1, 0}, {1, 0, fin_z}, {1, 1, fin_z}},
                       {{0, 1, 2, 3}, {1, 4, 5, 2}, {1, 2, 7, 6}});
    Map m;
    m.faces = 3;
    m.regions = {{0, {{"0", "0"}, {"1", "0"}, {"1", "1"}, {"0", "1"}}, {}},
                 {1, {{"1", "0"}, {"2", "0"}, {"2", "1"}, {"1", "1"}}, {}}};
    m.segments = {{{"0", "0"}, {"1", "0"}, "border", {0}}, {{"0", "1"}, {"1", "1"}, "border", {0}},
                  {{"0", "0"}, {"0", "1"}, "border", {0}}, {{"1", "0"}, {"2", "0"}, "border", {1}},
                  {{"2", "0"}, {"2", "1"}, "border", {1}}, {{"1", "1"}, {"2", "1"}, "border", {1}}};
    // Below the floor the fin's far edge is behind the shared edge: crease of
    // all three. Above it, the fin's top edge is nearer: its border is drawn.
    if (fin_z < 0) m.segments.push_back({{"1", "0"}, {"1", "1"}, "crease", {0, 1, 2}});
    else m.segments.push_back({{"1", "0"}, {"1", "1"}, "border", {2}});
    EXPECT_PASSES(check(s, m)) ;
    m.segments.back() = {{"1", "0"}, {"1", "1"}, "smooth", {0, 1}};
    EXPECT_FAILS_WITH(check(s, m), fin_z < 0 ? "crease [0,1,2]" : "border [2]");
  }
}

// A heightfield seen from above: no face hides another, so the correct map is
// simply every triangle as its own region, the outline as borders and every
// inner edge sharper than the crease angle as a crease. Kinds are decided here
// in doubles (the test avoids angles near the threshold), independently of the
// checker's exact test.
struct Heightfield {
  Scene scene;
  Map map;
};

Heightfield heightfield(int n, std::uint64_t seed, bool smooth) {
  Heightfield hf;
  std::vector<Vec3> v;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) v.push_back({double(i), double(j), double(mix(seed) % 5) * 0.37});
  auto id = [&](int i, int j) { return std::uint32_t(j * (n + 1) + i); };
  std::vector<std::vector<std::uint32_t>> f;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      f.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      f.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  hf.scene = scene_of(v, f);
  hf.map.faces = f.size();
  auto normal = [&](const std::vector<std::uint32_t>& t) {
    const Vec3 &a = v[t[0]], &b = v[t[1]], &c = v[t[2]];
    double ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z, wx = c.x - a.x, wy = c.y - a.y, wz = c.z - a.z;
    return std::array<double, 3>{uy * wz - uz * wy, uz * wx - ux * wz, ux * wy - uy * wx};
  };
  const double c30 = std::cos(30 * 3.14159265358979323846 / 180);
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<int>> edges;
  for (std::size_t k = 0; k < f.size(); ++k) {
    Region r{int(k), {}, {}};
    for (int e = 0; e < 3; ++e) {
      const Vec3& p = v[f[k][e]];
      r.outer.push_back({std::to_string(int(p.x)), std::to_string(int(p.y))});
      std::uint32_t a = f[k][e], b = f[k][(e + 1) % 3];
      edges[{std::min(a, b), std::max(a, b)}].push_back(int(k));
    }
    hf.map.regions.push_back(r);
  }
  for (const auto& [e, fs] : edges) {
    const Vec3 &a = v[e.first], &b = v[e.second];
    Segment s{{std::to_string(int(a.x)), std::to_string(int(a.y))}, {std::to_string(int(b.x)), std::to_string(int(b.y))}, "border", fs};
    if (fs.size() == 2) {
      auto n1 = normal(f[fs[0]]), n2 = normal(f[fs[1]]);
      double cosang = (n1[0] * n2[0] + n1[1] * n2[1] + n1[2] * n2[2]) /
                      std::sqrt((n1[0] * n1[0] + n1[1] * n1[1] + n1[2] * n1[2]) * (n2[0] * n2[0] + n2[1] * n2[1] + n2[2] * n2[2]));
      EXPECT_GT(std::abs(cosang - c30), 1e-9) << "pick another seed";
      s.kind = cosang < c30 ? "crease" : "smooth";
      if (s.kind == "smooth" && !smooth) continue;
      std::sort(s.faces.begin(), s.faces.end());
    }
    hf.map.segments.push_back(s);
  }
  return hf;
}

TEST(Checker, HeightfieldPassesAndMutationsFail) {
  for (bool smooth : {false, true}) {
    Heightfield hf = heightfield(6, 7, smooth);
    vc::Options opt;
    opt.smooth = smooth;
    vc::Report r = check(hf.scene, hf.map, opt);
    EXPECT_TRUE(r.ok) << all(r);
    std::size_t creases = 0, smooths = 0;
    for (const Segment& s : hf.map.segments) (s.kind == "crease" ? creases : smooths) += s.kind != "border";
    EXPECT_GT(creases, 10u);
    if (smooth) {
      EXPECT_GT(smooths, 10u);
    }
  }
  Heightfield hf = heightfield(6, 7, false);
  std::uint64_t seed = 99;
  for (int trial = 0; trial < 12; ++trial) {
    Map m = hf.map;
    std::size_t k = mix(seed) % m.segments.size();
    switch (trial % 4) {
      case 0:   // a line lost
        m.segments.erase(m.segments.begin() + std::ptrdiff_t(k));
        EXPECT_FAILS_WITH(check(hf.scene, m), "coverage: no segment");
        break;
      case 1:   // a crease called smooth, or a border called crease
        if (m.segments[k].kind == "crease") {
          m.segments[k].kind = "smooth";
          EXPECT_FAILS_WITH(check(hf.scene, m), "the first visible line there is crease");
        } else {
          m.segments[k].kind = "silhouette";
          EXPECT_FAILS_WITH(check(hf.scene, m), "format:");
        }
        break;
      case 2: {   // a region given to its neighbour's face
        std::size_t r = mix(seed) % m.regions.size();
        m.regions[r].face = int((r + 1) % m.regions.size());
        EXPECT_FAILS_WITH(check(hf.scene, m), "regions:");
        break;
      }
      case 3: {   // an inner grid point moved in every ring and segment: still a tiling
        std::string x = std::to_string(1 + mix(seed) % 5), y = std::to_string(1 + mix(seed) % 5);
        Pt from{x, y}, to{x + "/1", y};
        to.first = std::to_string(std::stoi(x)) == x ? (std::to_string(2 * std::stoi(x) + 1) + "/2") : x;
        for (auto& reg : m.regions)
          for (auto& p : reg.outer)
            if (p == from) p = to;
        for (auto& s : m.segments) {
          if (s.from == from) s.from = to;
          if (s.to == from) s.to = to;
        }
        vc::Report rep = check(hf.scene, m);
        EXPECT_FALSE(rep.ok) << "moved " << x << "," << y;
        break;
      }
    }
  }
}

TEST(Checker, SpeedOnThreeHundredFaces) {
  // 12 x 12 heightfield: 288 faces, a few thousand samples.
  Heightfield hf = heightfield(12, 3, false);
  vc::Options opt;
  opt.samples = 3000;
  auto t0 = std::chrono::steady_clock::now();
  vc::Report r = vc::check_map(hf.scene, json(hf.map), opt);
  double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_TRUE(r.ok) << all(r);
  std::cout << "288-face heightfield: " << s << " s, " << r.samples_checked << " samples, "
            << r.segment_points_checked << " segment points, " << r.edge_points_checked << " edge points\n";
  EXPECT_LT(s, 60.0);
}

}  // namespace
