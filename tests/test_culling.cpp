// Culling from inside a closed component (engine/cap_inside.h): which facets'
// images lie inside the near plane's cut, told by parity, and whether a
// component meets itself (engine/self_contact.h), where parity would be wrong.
// The corpus (tests/data/cases.txt: tube_hook.off, tube_through_itself.off)
// checks the maps; these check each step's answer where it is known by hand.
#include <gtest/gtest.h>
#include <cmath>

#include <vector>

#include "engine/cap_inside.h"
#include "engine/self_contact.h"
#include "engine/world_facets.h"

namespace {

using namespace vismap;
using namespace vismap::engine;

// A facet's image for inside_caps: its box and its first corner.
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

TEST(InsideCaps, ParityOfASquareRingTellsTheRingFromItsHole) {
  // The cap: the square [-4,4]^2 less [-1,1]^2 (a near plane through a frame).
  std::vector<CutSegment> cut;
  add_ring(cut, 0, {{-4, -4}, {4, -4}, {4, 4}, {-4, 4}});
  add_ring(cut, 0, {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}});
  const std::vector<Image> images = {
      triangle(2, 2, 3, 2, 2, 3),               // 0: in the ring
      triangle(-0.5, -0.5, 0.5, -0.5, 0, 0.5),  // 1: in the hole (within the cut's box)
      triangle(0.5, 0.5, 1.5, 0.5, 1, 1.5),     // 2: across the hole's border
      triangle(5, 5, 6, 5, 5, 6),               // 3: outside the cut's box
      triangle(-3, -1, -2, -1, -2.5, -0.5),     // 4: in the ring, its ray along the hole's side
      triangle(2, 2, 3, 2, 2, 3),               // 5: in the ring, not a candidate
      triangle(2, 2, 3, 2, 2, 3),               // 6: in the ring, of a component with no cut
      triangle(3.5, -0.5, 4.5, -0.5, 4, 0.5),   // 7: across the outer border
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
  const std::vector<char> inside = inside_caps(cc, cut, candidate, box, point);
  EXPECT_EQ(inside, (std::vector<char>{1, 0, 0, 0, 1, 0, 0, 0}));
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

}  // namespace
