// Culling from inside a closed component (engine/cap_inside.h): which facets'
// images lie inside the near plane's cut, told by parity, and whether a
// component meets itself (engine/self_contact.h), where parity would be wrong;
// and which open surfaces are certified never to meet themselves
// (engine/height_fields.h), whose pairs the piercing search passes over.
// The corpus (tests/data/cases.txt: tube_hook.off, tube_through_itself.off)
// checks the maps; these check each step's answer where it is known by hand.
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include <vector>

#include "engine/cap_inside.h"
#include "engine/culling.h"
#include "engine/edge_pieces.h"
#include "engine/height_fields.h"
#include "engine/morton.h"
#include "engine/self_contact.h"
#include "engine/world_facets.h"

namespace {

using namespace vismap;
using namespace vismap::engine;

// A facet's image for cap_sides: its box and its first corner.
struct Image {
  CGAL::Bbox_2 box;
  P2 point;
};
Image triangle(double x0, double y0, double x1, double y1, double x2, double y2) {
  CGAL::Bbox_2 b(x0, y0, x0, y0);
  b += CGAL::Bbox_2(x1, y1, x1, y1);
  b += CGAL::Bbox_2(x2, y2, x2, y2);
  return {b, P2(x0, y0)};
}

// A closed polygon's sides as cut segments of one component.
void add_ring(std::vector<CutSegment>& cut, int component, const std::vector<std::pair<double, double>>& ring) {
  for (std::size_t k = 0; k < ring.size(); ++k) {
    const auto [ax, ay] = ring[k];
    const auto [bx, by] = ring[(k + 1) % ring.size()];
    CGAL::Bbox_2 box(std::min(ax, bx), std::min(ay, by), std::max(ax, bx), std::max(ay, by));
    cut.push_back({component, P2(ax, ay), P2(bx, by), box});
  }
}

TEST(CapSides, ParityOfASquareRingTellsTheRingFromItsHoleAndTheOutside) {
  // The cap: the square [-4,4]^2 less [-1,1]^2 (a near plane through a frame).
  std::vector<CutSegment> cut;
  add_ring(cut, 0, {{-4, -4}, {4, -4}, {4, 4}, {-4, 4}});
  add_ring(cut, 0, {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}});
  const std::vector<Image> images = {
      triangle(2, 2, 3, 2, 2, 3),               // 0: in the ring
      triangle(-0.5, -0.5, 0.5, -0.5, 0, 0.5),  // 1: in the hole (within the cut's box): outside
      triangle(0.5, 0.5, 1.5, 0.5, 1, 1.5),     // 2: across the hole's border
      triangle(5, 5, 6, 5, 5, 6),               // 3: outside the cut's box
      triangle(-3, -1, -2, -1, -2.5, -0.5),     // 4: in the ring, its ray along the hole's side
      triangle(2, 2, 3, 2, 2, 3),               // 5: in the ring, not a candidate
      triangle(2, 2, 3, 2, 2, 3),               // 6: in the ring, of a component with no cut
      triangle(3.5, -0.5, 4.5, -0.5, 4, 0.5),   // 7: across the outer border
      triangle(-6, -3, -5, -3, -5.5, -2),       // 8: left of the ring, its ray through both walls
      triangle(-2, 0.2, -1.5, 0.2, -1.7, 0.6),  // 9: in the ring, its ray through the hole
  };
  const std::size_t n = images.size();
  ClosedComponents cc;
  cc.component.assign(n, 0);
  cc.component[6] = 6;
  cc.side.assign(n, 1);
  std::vector<char> candidate(n, 1);
  candidate[5] = 0;
  std::vector<CGAL::Bbox_2> box;
  std::vector<const P2*> point;
  for (const Image& im : images) {
    box.push_back(im.box);
    point.push_back(&im.point);
  }
  const std::vector<std::int8_t> side = cap_sides(cc, cut, candidate, box, point);
  EXPECT_EQ(side, (std::vector<std::int8_t>{1, -1, 0, -1, 1, 0, 0, 0, -1, 1}));
}

// Many small triangles row by row across the same ring, its hole and outside
// it (most points then take the parity of the last one's: nothing parts them),
// and a second ring of another component interleaved: each side as the boxes
// and the point's place say, at 1, 2 and 3 threads (chunks of 4096 facets).
TEST(CapSides, NeighboursShareTheParityOfTheirRegionAtEveryThreadCount) {
  std::vector<CutSegment> cut;
  add_ring(cut, 0, {{-4, -4}, {4, -4}, {4, 4}, {-4, 4}});
  add_ring(cut, 0, {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}});
  add_ring(cut, 1, {{-2.5, -2.5}, {-1.5, -2.5}, {-1.5, -1.5}, {-2.5, -1.5}});
  std::vector<Image> images;
  ClosedComponents cc;
  const int m = 130;
  for (int row = 0; row < m; ++row)
    for (int col = 0; col < m; ++col) {
      const double x = -5.01 + 10.0 * col / m, y = -5.01 + 10.0 * row / m;
      images.push_back(triangle(x, y, x + 0.05, y, x, y + 0.05));
      cc.component.push_back((row + col) % 7 == 0 ? 1 : 0);
    }
  const std::size_t n = images.size();
  cc.side.assign(n, 1);
  std::vector<char> candidate(n, 1);
  std::vector<CGAL::Bbox_2> box;
  std::vector<const P2*> point;
  for (const Image& im : images) {
    box.push_back(im.box);
    point.push_back(&im.point);
  }
  auto apart = [](const CGAL::Bbox_2& a, const CGAL::Bbox_2& b) {
    return a.xmax() < b.xmin() || b.xmax() < a.xmin() || a.ymax() < b.ymin() || b.ymax() < a.ymin();
  };
  auto in_square = [](const Image& im, double lo, double hi) {
    const double x = CGAL::to_double(im.point.x()), y = CGAL::to_double(im.point.y());
    return lo < x && x < hi && lo < y && y < hi;
  };
  std::vector<std::int8_t> expected(n, 0);
  int inside = 0, outside = 0;
  for (std::size_t f = 0; f < n; ++f) {
    const int c = cc.component[f];
    if (std::any_of(cut.begin(), cut.end(), [&](const CutSegment& s) { return s.component == c && !apart(s.box, box[f]); }))
      continue;
    const bool in_cap = c == 0 ? in_square(images[f], -4, 4) && !in_square(images[f], -1, 1)
                               : CGAL::to_double(images[f].point.x()) > -2.5 && CGAL::to_double(images[f].point.x()) < -1.5 &&
                                     CGAL::to_double(images[f].point.y()) > -2.5 && CGAL::to_double(images[f].point.y()) < -1.5;
    expected[f] = in_cap ? 1 : -1;
    (in_cap ? inside : outside)++;
  }
  ASSERT_GT(inside, 1000);
  ASSERT_GT(outside, 1000);
  for (const int threads : {1, 2, 3})
    EXPECT_EQ(cap_sides(cc, cut, candidate, box, point, threads), expected) << threads << " threads";
}

// A scene of triangles (each a face) over the given corners.
Scene triangles(std::vector<Vec3> corners, std::vector<IndexRing> faces) {
  Scene s;
  s.file = "test";
  s.vertices = std::move(corners);
  s.faces = std::move(faces);
  return s;
}

bool meets(const Scene& s) {
  const WorldFacets wf = make_world_facets(s);
  std::vector<int> all(wf.facets.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
  return meets_itself(s, wf, all);
}

TEST(SelfContact, ClosedTubesAndTouchingTriangles) {
  // The corpus tubes: the one whose last leg passes through its first meets itself.
  EXPECT_TRUE(meets(read_scene(std::string(VISMAP_DATA_DIR) + "/tube_through_itself.off")));
  EXPECT_FALSE(meets(read_scene(std::string(VISMAP_DATA_DIR) + "/tube_hook.off")));
  EXPECT_FALSE(meets(read_scene(std::string(VISMAP_DATA_DIR) + "/cube_near_cut.off")));
  // Two triangles along a shared edge: bent, they meet only there; folded flat
  // onto one side, they overlap; opened flat, they do not.
  const std::vector<Vec3> v = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5, 0.5, 1}, {0.2, 0.5, 0}, {1, 1, 0}};
  EXPECT_FALSE(meets(triangles(v, {{0, 1, 2}, {1, 0, 3}})));
  EXPECT_TRUE(meets(triangles(v, {{0, 1, 2}, {1, 0, 4}})));
  EXPECT_FALSE(meets(triangles(v, {{0, 1, 2}, {1, 5, 2}})));
  // Sharing one corner: apart elsewhere, or crossing (one's far side through the other).
  const std::vector<Vec3> w = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {-1, 0, 1}, {0, -1, 1},
                               {0.5, 0.5, -1}, {0.5, 0.5, 1}};
  EXPECT_FALSE(meets(triangles(w, {{0, 1, 2}, {0, 3, 4}})));
  EXPECT_TRUE(meets(triangles(w, {{0, 1, 2}, {0, 5, 6}})));   // ((0.5,0.5,0) on both)
  // Sharing nothing: a corner of one on the other (touching) meets it.
  const std::vector<Vec3> u = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0.5, 0.5, 0}, {0.5, 0.5, 1}, {1.5, 0.5, 1}};
  EXPECT_TRUE(meets(triangles(u, {{0, 1, 2}, {3, 4, 5}})));
}

TEST(SelfContact, StarsThatGoRoundTwiceAreTested) {
  // Six triangles around the origin, each turning 120 degrees about it seen
  // along z: their link is one cycle, but it goes round twice. The second
  // round's triangle (0, 4, 5) dips through the first round's (0, 1, 2) (its
  // far edge crosses z = 0 at (0.25, 0.433..)): they meet other than at their
  // one shared corner, which a star taken as flat would miss.
  const double c = std::cos(2 * M_PI / 3), s = std::sin(2 * M_PI / 3);
  const std::vector<Vec3> v = {{0, 0, 0},  {2, 0, 0},  {2 * c, 2 * s, 0}, {2 * c, -2 * s, 0},
                               {1, 0, 1},  {c, s, -1}, {c, -s, 1}};
  const std::vector<IndexRing> twice = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}, {0, 5, 6}, {0, 6, 1}};
  EXPECT_TRUE(meets(triangles(v, twice)));
  // Going round once (the first three), the star is flat and meets nothing;
  // nor does a closed pyramid, whose apex's star is flat along z.
  EXPECT_FALSE(meets(triangles(v, {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}})));
  const std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 1}};
  const std::vector<IndexRing> pyramid = {{0, 2, 1}, {0, 3, 2}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
  EXPECT_FALSE(meets(triangles(p, pyramid)));
}

TEST(SelfContact, ComponentsAnsweredTogetherAsAlone) {
  // Several components in one call: each answered as it would be alone (the
  // vertex numbering shared between them is left as found), on any threads.
  const Scene tube = read_scene(std::string(VISMAP_DATA_DIR) + "/tube_through_itself.off");
  const WorldFacets wf = make_world_facets(tube);
  std::vector<int> all(wf.facets.size()), half(wf.facets.size() / 2);
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
  for (std::size_t i = 0; i < half.size(); ++i) half[i] = static_cast<int>(i);
  const std::vector<std::vector<int>> parts = {half, all, {}, all, half};
  std::vector<char> alone;
  for (const auto& part : parts) alone.push_back(meets_itself(tube, wf, part));
  for (int threads : {1, 2, 3}) EXPECT_EQ(meets_itself(tube, wf, parts, threads), alone);
  EXPECT_EQ(alone[1], 1);
}

// A closed, consistently oriented surface of positive volume that crosses
// itself turns inside out where it does: a cube whose roof's apex is pushed down
// through its floor (tests/data/cube_dent_through.off), seen from below, shows
// the spike's faces from behind, and nothing of the solid hides them. It is not
// taken as closed (nothing culled); the same cube with its apex above the roof is.
TEST(ClosedComponents, SurfacesThatCrossThemselvesAreNotClosed) {
  auto cube_with_apex = [](double z) {
    Scene s;
    s.file = "cube";
    s.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}, {0.5, 0.5, z}};
    s.faces = {{0, 3, 2, 1}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7},
               {4, 5, 8},    {5, 6, 8},    {6, 7, 8},    {7, 4, 8}};
    return s;
  };
  for (const double z : {1.5, -0.5}) {
    const Scene s = cube_with_apex(z);
    const WorldFacets wf = make_world_facets(s);
    const ClosedComponents cc = closed_components(s, wf, match_edges(s, wf));
    ASSERT_EQ(cc.side.size(), wf.facets.size());
    for (const std::int8_t side : cc.side) EXPECT_EQ(side, z > 1 ? 1 : 0) << "apex at z = " << z;
  }
}

// Closed boxes that touch (tests/data/boxes_touching.off): an annex against the
// first box's wall, sharing parts of two of its edges (pieces of four sharers),
// a box meeting it along a whole upright edge, one standing on its roof, and
// one on the third box, its floor that box's roof (every edge of the two faces
// shared by four facets: the solids are told apart by their input vertices).
// Each box is a closed shell of its own, whatever touches it; all but the one
// on the roof are one connected component. A box left open (its roof taken
// away), or with a face turned the other way, is not closed, and the others
// still are.
TEST(ClosedComponents, SolidsThatTouchAreShellsOfTheirOwn) {
  auto boxes = [](int drop_face, int flip_face) {
    Scene s;
    s.file = "boxes";
    const std::array<std::array<double, 6>, 5> at = {{{0, 0, 0, 2, 1, 1},
                                                      {2, 0, 0, 3, 0.5, 0.5},
                                                      {-1, 1, 0, 0, 2, 1},
                                                      {0.5, 0.25, 1, 1.5, 0.75, 1.5},
                                                      {-1, 1, 1, 0, 2, 2}}};
    for (const auto& [x0, y0, z0, x1, y1, z1] : at) {
      const auto b = static_cast<std::uint32_t>(s.vertices.size());
      s.vertices.insert(s.vertices.end(), {{x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0},
                                           {x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}});
      for (const auto& q : std::vector<std::array<std::uint32_t, 4>>{
               {0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}}) {
        if (static_cast<int>(s.faces.size()) == drop_face) { drop_face = -2; continue; }
        IndexRing ring{b + q[0], b + q[1], b + q[2], b + q[3]};
        if (static_cast<int>(s.faces.size()) == flip_face) std::reverse(ring.begin(), ring.end());
        s.faces.push_back(ring);
      }
    }
    return s;
  };
  // Per facet: its box (the facets are the quads, in file order).
  auto box_of = [](const Scene& s, const WorldFacets& wf, std::size_t f) {
    return static_cast<int>(s.faces[static_cast<std::size_t>(wf.facets[f].face)][0] / 8);
  };
  for (const auto& [drop, flip, open_box] :
       std::vector<std::array<int, 3>>{{-1, -1, -1}, {7, -1, 1}, {-1, 15, 2}, {-1, 26, 4}}) {
    const Scene s = boxes(drop, flip);
    const WorldFacets wf = make_world_facets(s);
    for (int threads : {1, 2}) {
      const ClosedComponents cc = closed_components(s, wf, match_edges(s, wf, 20, threads), threads);
      ASSERT_EQ(cc.side.size(), wf.facets.size());
      for (std::size_t f = 0; f < wf.facets.size(); ++f) {
        const int b = box_of(s, wf, f);
        EXPECT_EQ(cc.side[f], b == open_box ? 0 : 1) << "facet " << f << " of box " << b << ", open box " << open_box;
        for (std::size_t g = 0; g < f; ++g) {
          const int c = box_of(s, wf, g);
          EXPECT_EQ(cc.component[f] == cc.component[g], b == c) << "facets " << g << ", " << f;
          EXPECT_EQ(cc.connected_components()[f] == cc.connected_components()[g], (b == 3) == (c == 3))
              << "facets " << g << ", " << f;
        }
      }
    }
  }
}

// Per facet: its height-field label (or -1), on `threads` threads.
std::vector<int> height_fields(const Scene& s, int threads = 1) {
  const WorldFacets wf = make_world_facets(s);
  const std::vector<WorldPiece> pieces = match_edges(s, wf);
  const ClosedComponents cc = closed_components(s, wf, pieces);
  return height_field_components(s, wf, pieces, cc.connected_components(), threads);
}

// Whether every facet is certified, and with one label (one component).
bool all_certified(const std::vector<int>& label) {
  return !label.empty() && label[0] >= 0 && std::all_of(label.begin(), label.end(), [&](int l) { return l == label[0]; });
}
bool none_certified(const std::vector<int>& label) {
  return std::all_of(label.begin(), label.end(), [](int l) { return l < 0; });
}

// An n x n grid of squares over [0, 1]^2, two triangles each, heights z(x, y)
// (`mirror`: every triangle wound the other way).
Scene grid(int n, double (*z)(double, double), bool mirror = false) {
  Scene s;
  s.file = "grid";
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = static_cast<double>(i) / n, y = static_cast<double>(j) / n;
      s.vertices.push_back({x, y, z(x, y)});
    }
  auto id = [&](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      IndexRing a{id(i, j), id(i + 1, j), id(i + 1, j + 1)}, b{id(i, j), id(i + 1, j + 1), id(i, j + 1)};
      if (mirror) {
        std::reverse(a.begin(), a.end());
        std::reverse(b.begin(), b.end());
      }
      s.faces.push_back(a);
      s.faces.push_back(b);
    }
  return s;
}

// A band of triangles round the z axis, radii 1 to 2 (`rings` rings of
// vertices), from angle 0 to `turns` turns, heights z(angle, radius).
Scene band(double turns, int rings, double (*z)(double, double)) {
  Scene s;
  s.file = "band";
  const int steps = static_cast<int>(48 * turns);
  for (int k = 0; k <= steps; ++k)
    for (int r = 0; r < rings; ++r) {
      const double t = 2 * M_PI * turns * k / steps, radius = 1 + static_cast<double>(r) / (rings - 1);
      s.vertices.push_back({radius * std::cos(t), radius * std::sin(t), z(t, radius)});
    }
  // (A whole turn closes: its last ray is its first.)
  auto id = [&](int k, int r) { return static_cast<std::uint32_t>((turns == 1.0 && k == steps ? 0 : k) * rings + r); };
  for (int k = 0; k < steps; ++k)
    for (int r = 0; r + 1 < rings; ++r) {
      s.faces.push_back({id(k, r), id(k, r + 1), id(k + 1, r + 1)});
      s.faces.push_back({id(k, r), id(k + 1, r + 1), id(k + 1, r)});
    }
  return s;
}

TEST(HeightFields, TerrainsAreCertifiedWhicheverWayTheyTurn) {
  auto hills = [](double x, double y) { return std::sin(7 * x) * std::cos(5 * y); };
  for (bool mirror : {false, true})
    for (int threads : {1, 2, 3}) EXPECT_TRUE(all_certified(height_fields(grid(12, hills, mirror), threads)));
  // Seen along x rather than z: a wall whose x is a function of y and z.
  Scene wall = grid(6, hills);
  for (Vec3& p : wall.vertices) p = {p.z, p.x, p.y};
  EXPECT_TRUE(all_certified(height_fields(wall)));
  // A band of less than one turn is a height field over its annulus sector.
  EXPECT_TRUE(all_certified(height_fields(band(0.75, 3, [](double t, double) { return t; }))));
}

TEST(HeightFields, SurfacesThatOverlapThemselvesAreNot) {
  // A band of one and a half turns whose two sheets cross (they swap heights
  // at radius 1.4, between the rings of vertices): it meets itself; every
  // triangle turns positively along z and every star is flat there, but the
  // boundary loop crosses itself.
  const Scene crossing = band(1.5, 3, [](double t, double r) { return (t - 1.5 * M_PI) * (r - 1.4); });
  EXPECT_TRUE(meets(crossing));
  EXPECT_TRUE(none_certified(height_fields(crossing)));
  // A ramp of one and a half turns meets itself nowhere, but its projection is
  // not one to one: not certified either (the certificate is about the projection).
  EXPECT_TRUE(none_certified(height_fields(band(1.5, 3, [](double t, double) { return t; }))));
  // A closed ring (an annulus: Euler characteristic 0).
  EXPECT_TRUE(none_certified(height_fields(band(1.0, 3, [](double, double) { return 0.0; }))));
  // A sheet folded back over itself: the fold's triangles turn the other way.
  Scene folded = grid(8, [](double, double) { return 0.0; });
  for (Vec3& p : folded.vertices)
    if (p.x > 0.5) p = {1.0 - p.x, p.y, 1.0 - 2 * (1.0 - p.x) + 0.5};
  EXPECT_TRUE(none_certified(height_fields(folded)));
}

TEST(HeightFields, ComponentsSharingAVertexAreNot) {
  // Two grids touching at one corner: each alone a terrain, together two
  // components through one vertex (conservatively refused).
  auto flat = [](double, double) { return 0.0; };
  Scene a = grid(3, flat), b = grid(3, flat);
  const auto base = static_cast<int>(a.vertices.size());
  for (Vec3 p : b.vertices) a.vertices.push_back({p.x + 1, p.y + 1, 0.5});
  a.vertices[static_cast<std::size_t>(base)] = a.vertices.back();   // (never used: b's (0, 0) is a's (1, 1) below)
  for (IndexRing f : b.faces) {
    for (auto& i : f) i = i == 0 ? 15 : i + base;
    a.faces.push_back(f);
  }
  a.vertices[15] = {1, 1, 0};
  const std::vector<int> label = height_fields(a);
  EXPECT_TRUE(none_certified(label));
  EXPECT_TRUE(all_certified(height_fields(grid(3, flat))));
}

}  // namespace

// The screen order's radix sort: positions by key, ties in position order, as a
// stable comparison sort gives them (keys with many ties, in each of its three
// 11-bit digits, and some keys of any 32 bits), whatever the thread count (each
// pass's parts counted and placed side by side).
TEST(ScreenOrder, RadixOrderIsTheStableSortsOrder) {
  std::mt19937 rng(5);
  for (std::size_t n : {0u, 1u, 7u, 100000u, 300001u}) {
    std::vector<std::uint32_t> key(n);
    for (auto& k : key) {
      const int shift[] = {3, 13, 24};
      k = rng() % 16 == 0 ? static_cast<std::uint32_t>(rng()) : (rng() % 50) << shift[rng() % 3] | (rng() % 3);
    }
    std::vector<std::uint32_t> want(n);
    std::iota(want.begin(), want.end(), 0u);
    std::stable_sort(want.begin(), want.end(), [&](std::uint32_t a, std::uint32_t b) { return key[a] < key[b]; });
    for (const int threads : {1, 2, 3, 8})
      EXPECT_EQ(vismap::engine::order_by_key(key, threads), want) << n << " keys, " << threads << " threads";
  }
}
