// The image-precision baselines (bench/raster) against the exact engine and
// each other, and the error measures against an independent brute-force exact
// point location.
//
// Every baseline must give the exact label at every pixel centre that is not
// within 1e-7 of the window side of an exact region boundary (there, doubles may
// legitimately decide either way). The exact labels themselves are checked
// against a brute-force rational point-in-region test, boundary pixels
// included, on a scene whose edges run exactly through pixel centres.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "arrangements/json_writer.h"
#include "bench/raster/exact_error.h"
#include "bench/raster/raster.h"
#include "bench/scene_gen.h"
#include "engine/visibility.h"

namespace {

using vismap::Scene;
using vismap::Vec3;
using vismap::View;
namespace raster = vismap::raster;

View ortho(const Scene& scene, Vec3 dir) {
  vismap::Camera c;
  c.dir = dir;
  return vismap::make_view(c, scene);
}

View persp(const Scene& scene, Vec3 eye, Vec3 target, double fov, Vec3 up = {0, 0, 1}) {
  vismap::Camera c;
  c.eye = eye;
  c.target = target;
  c.fov_deg = fov;
  c.up = up;
  return vismap::make_view(c, scene);
}

// A counter-clockwise (seen from +z) axis-aligned rectangle at height z.
void rect(Scene& s, double x0, double y0, double x1, double y1, double z) {
  const auto b = static_cast<std::uint32_t>(s.vertices.size());
  s.vertices.push_back({x0, y0, z});
  s.vertices.push_back({x1, y0, z});
  s.vertices.push_back({x1, y1, z});
  s.vertices.push_back({x0, y1, z});
  s.faces.push_back({b, b + 1, b + 2, b + 3});
}

const Vec3 kDown{0, 0, -1};   // screen (x, y), depth -z: larger z is nearer

// Pixel centres within `rel` of the window side of an exact region boundary
// (distance in doubles to every ring edge: brute force, fine for small maps).
std::vector<char> near_boundary(const vismap::VisibilityMap& map, const raster::Window& w, double rel) {
  const double d = rel * w.pixel * w.R;
  std::vector<char> near(static_cast<std::size_t>(w.R) * w.R, 0);
  struct E {
    double ax, ay, bx, by;
  };
  std::vector<E> edges;
  auto add_ring = [&](const std::vector<vismap::Point2>& r) {
    for (std::size_t k = 0; k < r.size(); ++k) {
      const auto& a = r[k];
      const auto& b = r[(k + 1) % r.size()];
      edges.push_back({a.x.get_d(), a.y.get_d(), b.x.get_d(), b.y.get_d()});
    }
  };
  for (const auto& reg : map.regions) {
    add_ring(map.points(reg.outer));
    for (const auto& h : reg.holes) add_ring(map.points(h));
  }
  for (int j = 0; j < w.R; ++j)
    for (int i = 0; i < w.R; ++i) {
      const double px = w.cx(i), py = w.cy(j);
      for (const E& e : edges) {
        const double dx = e.bx - e.ax, dy = e.by - e.ay, l2 = dx * dx + dy * dy;
        double t = l2 > 0 ? ((px - e.ax) * dx + (py - e.ay) * dy) / l2 : 0;
        t = std::clamp(t, 0.0, 1.0);
        const double qx = e.ax + t * dx - px, qy = e.ay + t * dy - py;
        if (qx * qx + qy * qy <= d * d) {
          near[static_cast<std::size_t>(j) * w.R + i] = 1;
          break;
        }
      }
    }
  return near;
}

struct Checked {
  std::size_t far = 0;                 // pixel centres compared
  std::set<int> faces;                 // faces seen at them
};

// Every baseline equals the exact labels (and so each other) away from edges.
Checked expect_baselines_exact(const Scene& scene, const View& view, int R, const std::string& what) {
  const vismap::VisibilityMap map = vismap::visibility_franklin(scene, view, {});
  const raster::ScreenScene ss = raster::project(scene, view);
  const raster::Window w = raster::window_for(ss, R);
  const raster::ExactLabels ex = raster::exact_labels(map, w);
  const std::vector<char> near = near_boundary(map, w, 1e-7);
  Checked out;
  for (std::size_t k = 0; k < near.size(); ++k)
    if (!near[k]) {
      ++out.far;
      out.faces.insert(ex.image.label[k]);
      EXPECT_NE(ex.image.label[k], raster::kOnBoundary) << what << ": a boundary pixel far from every edge";
    }
  const raster::Image z = raster::zbuffer(ss, w);
  for (raster::Method m : raster::kMethods) {
    const raster::Image img = raster::render(m, ss, w);
    EXPECT_EQ(img.label.size(), ex.image.label.size());
    if (img.label.size() != ex.image.label.size()) continue;
    std::size_t wrong = 0, differ = 0;
    std::string first;
    for (std::size_t k = 0; k < near.size(); ++k) {
      if (near[k]) continue;
      if (img.label[k] != ex.image.label[k]) {
        if (wrong++ == 0)
          first = "pixel (" + std::to_string(k % R) + ", " + std::to_string(k / R) + "): " +
                  std::to_string(img.label[k]) + " instead of " + std::to_string(ex.image.label[k]);
      }
      if (img.label[k] != z.label[k]) ++differ;
    }
    EXPECT_EQ(wrong, 0u) << what << ", " << raster::name(m) << ": " << wrong << " wrong pixels, first " << first;
    EXPECT_EQ(differ, 0u) << what << ", " << raster::name(m) << " against the z-buffer";
  }
  return out;
}

TEST(Raster, TwoOverlappingSquares) {
  Scene s;
  rect(s, 0.1, 0.1, 0.6, 0.6, 0.2);    // face 0, behind
  rect(s, 0.35, 0.3, 0.9, 0.8, 0.7);   // face 1, in front
  const Checked c = expect_baselines_exact(s, ortho(s, kDown), 64, "two squares");
  EXPECT_GT(c.far, 3000u);
  EXPECT_EQ(c.faces, (std::set<int>{-1, 0, 1}));
  // The overlap shows the front square in every method.
  const raster::ScreenScene ss = raster::project(s, ortho(s, kDown));
  const raster::Window w = raster::window_for(ss, 64);
  const int i = static_cast<int>((0.5 - w.x0) / w.pixel), j = static_cast<int>((0.5 - w.y0) / w.pixel);
  for (raster::Method m : raster::kMethods) EXPECT_EQ(raster::render(m, ss, w).at(i, j), 1) << raster::name(m);
}

TEST(Raster, CoplanarOverlapGoesToTheLowestIndex) {
  for (bool swap : {false, true}) {
    Scene s;
    rect(s, 0.0, 0.0, 1.0, 1.0, 0.1);   // face 0: far background
    if (!swap) {
      rect(s, 0.3, 0.3, 0.9, 0.9, 0.5);   // face 1
      rect(s, 0.1, 0.1, 0.7, 0.7, 0.5);   // face 2, same plane
    } else {
      rect(s, 0.1, 0.1, 0.7, 0.7, 0.5);
      rect(s, 0.3, 0.3, 0.9, 0.9, 0.5);
    }
    const View v = ortho(s, kDown);
    const Checked c = expect_baselines_exact(s, v, 64, swap ? "coplanar, swapped" : "coplanar");
    EXPECT_EQ(c.faces, (std::set<int>{0, 1, 2}));
    const raster::ScreenScene ss = raster::project(s, v);
    const raster::Window w = raster::window_for(ss, 64);
    const int i = static_cast<int>((0.5 - w.x0) / w.pixel), j = static_cast<int>((0.5 - w.y0) / w.pixel);
    for (raster::Method m : raster::kMethods) EXPECT_EQ(raster::render(m, ss, w).at(i, j), 1) << raster::name(m);
  }
}

TEST(Raster, InterpenetratingBoxes) {
  const Scene s = vismap::gen::interpenetrating_boxes(3, 7);
  const Checked c = expect_baselines_exact(s, ortho(s, {-1, -2, -4}), 96, "interpenetrating boxes");
  EXPECT_GE(c.faces.size(), 7u);
}

TEST(Raster, RandomTrianglesCrossingEachOther) {
  const Scene s = vismap::gen::random_triangles(40, 0.5, 11);
  const Checked c = expect_baselines_exact(s, vismap::make_view({}, s), 96, "random triangles");
  EXPECT_GE(c.faces.size(), 20u);
}

TEST(Raster, NonConvexPolygon) {
  Scene s;
  rect(s, 0.0, 0.0, 1.0, 1.0, 0.1);
  // An L-shape (non-convex, planar, tilted), in front of the square.
  const auto b = static_cast<std::uint32_t>(s.vertices.size());
  for (auto [x, y] : std::vector<std::pair<double, double>>{
           {0.1, 0.1}, {0.9, 0.1}, {0.9, 0.4}, {0.4, 0.4}, {0.4, 0.9}, {0.1, 0.9}})
    s.vertices.push_back({x, y, 0.5 + 0.2 * x - 0.1 * y});
  s.faces.push_back({b, b + 1, b + 2, b + 3, b + 4, b + 5});
  const Checked c = expect_baselines_exact(s, ortho(s, kDown), 64, "non-convex");
  EXPECT_EQ(c.faces, (std::set<int>{0, 1}));
}

TEST(Raster, CubesInPerspective) {
  const Scene s = vismap::gen::cube_array(2, 0.5);
  const View v = persp(s, {6, -5, 4}, {1.25, 1.25, 1.25}, 50);
  const Checked c = expect_baselines_exact(s, v, 96, "cubes, perspective");
  EXPECT_GE(c.faces.size(), 10u);
}

TEST(Raster, PerspectiveNearPlaneClip) {
  // tests/data/perspective_near_clip.off: the eye stands above the ground, so
  // the ground is cut by the near plane; a wall faces the eye.
  Scene s;
  rect(s, -10, -10, 10, 10, 0);
  const auto b = static_cast<std::uint32_t>(s.vertices.size());
  for (Vec3 p : {Vec3{-1, 5, 0}, Vec3{1, 5, 0}, Vec3{1, 5, 2}, Vec3{-1, 5, 2}}) s.vertices.push_back(p);
  s.faces.push_back({b, b + 1, b + 2, b + 3});
  const View v = persp(s, {0, 0, 1}, {0, 5, 1}, 90);
  const Checked c = expect_baselines_exact(s, v, 128, "near-plane clip");
  // The cut's image reaches far out (screen y = -200), so the wall is far
  // smaller than a pixel in this window.
  EXPECT_EQ(c.faces, (std::set<int>{-1, 0}));
  // A larger wall seen from outside the ground: no clipping, both faces seen.
  Scene t;
  rect(t, -10, -10, 10, 10, 0);
  const auto c0 = static_cast<std::uint32_t>(t.vertices.size());
  for (Vec3 p : {Vec3{-5, 5, 0}, Vec3{5, 5, 0}, Vec3{5, 5, 6}, Vec3{-5, 5, 6}}) t.vertices.push_back(p);
  t.faces.push_back({c0, c0 + 1, c0 + 2, c0 + 3});
  const Checked c2 = expect_baselines_exact(t, persp(t, {0, -14, 3}, {0, 5, 1}, 60), 128, "ground and wall");
  EXPECT_EQ(c2.faces, (std::set<int>{-1, 0, 1}));
}

// ---- exact labels: brute-force rational point location ------------------------

// Sign of (b - a) x (p - a).
int orient(const vismap::Point2& a, const vismap::Point2& b, const mpq_class& px, const mpq_class& py) {
  return sgn((b.x - a.x) * (py - a.y) - (b.y - a.y) * (px - a.x));
}

bool on_ring(const std::vector<vismap::Point2>& r, const mpq_class& px, const mpq_class& py) {
  for (std::size_t k = 0; k < r.size(); ++k) {
    const auto& a = r[k];
    const auto& b = r[(k + 1) % r.size()];
    if (orient(a, b, px, py) != 0) continue;
    if (std::min(a.x, b.x) <= px && px <= std::max(a.x, b.x) && std::min(a.y, b.y) <= py &&
        py <= std::max(a.y, b.y))
      return true;
  }
  return false;
}

bool in_ring(const std::vector<vismap::Point2>& r, const mpq_class& px, const mpq_class& py) {   // off the ring
  bool in = false;
  for (std::size_t k = 0; k < r.size(); ++k) {
    const auto& a = r[k];
    const auto& b = r[(k + 1) % r.size()];
    if ((a.y > py) != (b.y > py)) {
      const mpq_class x = a.x + (py - a.y) * (b.x - a.x) / (b.y - a.y);
      if (x > px) in = !in;
    }
  }
  return in;
}

std::vector<std::int32_t> brute_labels(const vismap::VisibilityMap& map, const raster::Window& w) {
  // Exact boxes of the outer rings, to skip regions quickly.
  struct Box {
    mpq_class x0, x1, y0, y1;
  };
  std::vector<Box> boxes;
  struct Rings {
    int face;
    std::vector<vismap::Point2> outer;
    std::vector<std::vector<vismap::Point2>> holes;
  };
  std::vector<Rings> regions;
  for (const auto& reg : map.regions) {
    regions.push_back({reg.face, map.points(reg.outer), {}});
    for (const auto& h : reg.holes) regions.back().holes.push_back(map.points(h));
  }
  for (const auto& reg : regions) {
    Box b{reg.outer[0].x, reg.outer[0].x, reg.outer[0].y, reg.outer[0].y};
    for (const auto& p : reg.outer) {
      if (p.x < b.x0) b.x0 = p.x;
      if (p.x > b.x1) b.x1 = p.x;
      if (p.y < b.y0) b.y0 = p.y;
      if (p.y > b.y1) b.y1 = p.y;
    }
    boxes.push_back(b);
  }
  std::vector<std::int32_t> out;
  for (int j = 0; j < w.R; ++j)
    for (int i = 0; i < w.R; ++i) {
      const mpq_class px(w.cx(i)), py(w.cy(j));
      std::int32_t label = -1;
      for (std::size_t r = 0; r < regions.size(); ++r) {
        const auto& reg = regions[r];
        if (px < boxes[r].x0 || px > boxes[r].x1 || py < boxes[r].y0 || py > boxes[r].y1) continue;
        bool on = on_ring(reg.outer, px, py);
        for (const auto& h : reg.holes) on = on || on_ring(h, px, py);
        if (on) {
          label = raster::kOnBoundary;
          break;
        }
        bool in = in_ring(reg.outer, px, py);
        for (const auto& h : reg.holes) in = in && !in_ring(h, px, py);
        if (in) label = reg.face;
      }
      out.push_back(label);
    }
  return out;
}

TEST(ExactLabels, MatchBruteForceWithCentresOnEdges) {
  // Window [0,1]^2 at R = 8: centres at (k + 1/2) / 8. Face 1's edges x = 5/16,
  // y = 9/16 run through centres, and its corner (5/16, 9/16) is one; face 2's
  // corners lie between centres; face 3 is a tilted triangle.
  Scene s;
  rect(s, 0, 0, 1, 1, 0);                          // 0
  rect(s, 0.3125, 0.5625, 0.8125, 0.9375, 0.5);   // 1
  rect(s, 0.05, 0.05, 0.45, 0.3, 0.6);            // 2
  const auto b = static_cast<std::uint32_t>(s.vertices.size());
  s.vertices.push_back({0.55, 0.1, 0.3});
  s.vertices.push_back({0.95, 0.2, 0.9});
  s.vertices.push_back({0.6, 0.7, 0.4});
  s.faces.push_back({b, b + 1, b + 2});            // 3, crosses face 1 (an intersection line)
  const View v = ortho(s, kDown);
  const vismap::VisibilityMap map = vismap::visibility_franklin(s, v, {});
  for (int R : {8, 16, 37}) {
    const raster::Window w = raster::window_for_box(0, 1, 0, 1, R);
    const raster::ExactLabels ex = raster::exact_labels(map, w);
    const std::vector<std::int32_t> brute = brute_labels(map, w);
    EXPECT_EQ(ex.image.label, brute) << "R = " << R;
    if (R == 8) {
      EXPECT_GT(ex.boundary, 0u);   // centres on face 1's edges
      EXPECT_EQ(ex.image.at(2, 4), raster::kOnBoundary);   // the corner (5/16, 9/16)
      EXPECT_EQ(ex.image.at(4, 4), raster::kOnBoundary);   // on the edge y = 9/16
      EXPECT_EQ(ex.image.at(2, 6), raster::kOnBoundary);   // on the edge x = 5/16
      EXPECT_EQ(ex.image.at(4, 6), 1);
    }
  }
  // And on a general scene, where crossings are mostly placed in doubles.
  const Scene t = vismap::gen::random_triangles(30, 0.5, 5);
  const View vt = vismap::make_view({}, t);
  const vismap::VisibilityMap mt = vismap::visibility_franklin(t, vt, {});
  const raster::Window wt = raster::window_for(raster::project(t, vt), 48);
  const raster::ExactLabels et = raster::exact_labels(mt, wt);
  EXPECT_EQ(et.image.label, brute_labels(mt, wt));
  EXPECT_GT(et.crossings, 0u);
}

// ---- error measures --------------------------------------------------------------

TEST(ErrorMeasures, ZeroAgainstItselfPositiveAgainstAWrongImage) {
  Scene s;
  rect(s, 0.1, 0.1, 0.6, 0.6, 0.2);
  rect(s, 0.35, 0.3, 0.9, 0.8, 0.7);
  const View v = ortho(s, kDown);
  const vismap::VisibilityMap map = vismap::visibility_franklin(s, v, {});
  const raster::ScreenScene ss = raster::project(s, v);
  const raster::Window w = raster::window_for(ss, 64);
  const raster::ExactLabels ex = raster::exact_labels(map, w);
  const raster::LineRule smooth = raster::line_rule(s, v, ss);

  const raster::PixelError self = raster::pixel_error(ex.image, ex.image);
  EXPECT_EQ(self.wrong, 0u);
  EXPECT_EQ(self.fraction(), 0.0);
  EXPECT_EQ(self.compared, 64u * 64u);
  const raster::LineError lself = raster::line_error(map, ex.image, w, smooth);
  EXPECT_GT(lself.exact_length, 0.0);
  EXPECT_EQ(lself.missed, 0.0);
  EXPECT_EQ(lself.false_drawn, 0.0);

  // Every baseline gets every centre of this scene right, so its drawing too.
  for (raster::Method m : raster::kMethods) {
    const raster::Image img = raster::render(m, ss, w);
    EXPECT_EQ(raster::pixel_error(ex.image, img).wrong, 0u) << raster::name(m);
    const raster::LineError le = raster::line_error(map, img, w, smooth);
    EXPECT_EQ(le.missed, 0.0) << raster::name(m);
    EXPECT_EQ(le.false_drawn, 0.0) << raster::name(m);
  }

  // Wrong: the front square drawn as the back one (its edge inside the back
  // square disappears), and a phantom block of face 1 in the background.
  raster::Image bad = ex.image;
  for (auto& l : bad.label)
    if (l == 1) l = 0;
  for (int j = 2; j < 6; ++j)
    for (int i = 2; i < 6; ++i) bad.label[static_cast<std::size_t>(j) * 64 + i] = 1;
  const raster::PixelError pe = raster::pixel_error(ex.image, bad);
  EXPECT_GT(pe.fraction(), 0.1);
  const raster::LineError le = raster::line_error(map, bad, w, smooth);
  EXPECT_GT(le.missed_fraction(), 0.05);   // the front square's two inner sides
  EXPECT_GT(le.false_fraction(), 0.01);    // the phantom block's outline
  EXPECT_LT(le.missed_fraction(), 0.5);    // its outer sides are still drawn
}

TEST(ErrorMeasures, AreaErrorIsTheResolutionError) {
  // Edges on pixel sides: every pixel lies in one region, no area is wrong.
  Scene a;
  rect(a, 0, 0, 1, 1, 0);
  rect(a, 0.25, 0.125, 0.75, 0.5, 0.5);
  const View va = ortho(a, kDown);
  const vismap::VisibilityMap ma = vismap::visibility_franklin(a, va, {});
  const raster::Window wa = raster::window_for_box(0, 1, 0, 1, 8);
  const raster::ExactLabels ea = raster::exact_labels(ma, wa);
  const raster::Image za = raster::zbuffer(raster::project(a, va), wa);
  for (const auto& e : raster::area_error(ma, {&ea.image, &za}, wa, 4)) {
    EXPECT_EQ(e.samples, 32u * 32u);
    EXPECT_EQ(e.wrong, 0u);
  }

  // Edges across pixels (a slightly oblique view, so that no edge runs along a
  // pixel row or column): the area error of the exact centre labels is about
  // (boundary length in pixels) x 1/4 pixel / R^2, and halves when R doubles.
  Scene s;
  rect(s, 0.1, 0.1, 0.6, 0.6, 0.2);
  rect(s, 0.35, 0.3, 0.9, 0.8, 0.7);
  const View v = ortho(s, {0.13, 0.07, -1});
  const vismap::VisibilityMap map = vismap::visibility_franklin(s, v, {});
  const raster::ScreenScene ss = raster::project(s, v);
  double last = 0;
  for (int R : {32, 64, 128}) {
    const raster::Window w = raster::window_for(ss, R);
    const raster::ExactLabels ex = raster::exact_labels(map, w);
    const raster::Image z = raster::zbuffer(ss, w);
    raster::Image bad = z;
    for (auto& l : bad.label)
      if (l == 1) l = 0;
    const auto e = raster::area_error(map, {&ex.image, &z, &bad}, w, 4);
    EXPECT_GT(e[0].fraction(), 0.0) << R;
    EXPECT_EQ(e[1].wrong, e[0].wrong) << R;   // the z-buffer's labels are the exact ones
    EXPECT_GT(e[2].fraction(), 0.2) << R;     // face 1's square (~0.4 of the window) wrong
    const double length = raster::line_error(map, z, w, raster::all_changes()).exact_length;   // all drawn
    const double expect = length / (w.pixel * R) / R / 4;
    EXPECT_GT(e[0].fraction(), 0.6 * expect) << R;
    EXPECT_LT(e[0].fraction(), 1.6 * expect) << R;
    if (last > 0) {
      EXPECT_GT(last / e[0].fraction(), 1.6) << R;
      EXPECT_LT(last / e[0].fraction(), 2.5) << R;
    }
    last = e[0].fraction();
  }
}

TEST(ErrorMeasures, SmoothEdgesAreNotLines) {
  const Scene s = vismap::gen::sphere(32, 16);
  const View v = vismap::make_view({}, s);
  const vismap::VisibilityMap map = vismap::visibility_franklin(s, v, {});
  const raster::ScreenScene ss = raster::project(s, v);
  const raster::Window w = raster::window_for(ss, 128);
  const raster::Image img = raster::zbuffer(ss, w);
  const raster::LineRule smooth = raster::line_rule(s, v, ss);
  EXPECT_LT(std::set<std::int32_t>(smooth.patch.begin(), smooth.patch.end()).size(), 40u);   // few patches
  const raster::LineError with = raster::line_error(map, img, w, smooth);
  const raster::LineError without = raster::line_error(map, img, w, raster::all_changes());
  EXPECT_LT(with.false_fraction(), 0.05);     // only the silhouette is drawn
  EXPECT_GT(without.false_fraction(), 1.0);   // every facet outline would be
  EXPECT_LT(with.missed_fraction(), 0.05);
}

TEST(ErrorMeasures, JsonRoundTrip) {
  const Scene s = vismap::gen::cube_array(2, 0.5);
  const View v = persp(s, {6, -5, 4}, {1.25, 1.25, 1.25}, 50);
  vismap::VisibilityMap map = vismap::visibility_franklin(s, v, {});
  const vismap::VisibilityMap back = raster::read_map_json(vismap::to_json(map));
  ASSERT_EQ(back.regions.size(), map.regions.size());
  ASSERT_EQ(back.segments.size(), map.segments.size());
  EXPECT_TRUE(back.perspective);
  const View bv = raster::view_of(back);
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) EXPECT_EQ(bv.m[r][c], v.m[r][c]);
  EXPECT_NEAR(bv.eye.x, 6, 1e-9);
  EXPECT_NEAR(bv.eye.y, -5, 1e-9);
  EXPECT_NEAR(bv.eye.z, 4, 1e-9);
  const raster::Window w = raster::window_for(raster::project(s, bv), 64);
  EXPECT_EQ(raster::exact_labels(back, w).image.label, raster::exact_labels(map, w).image.label);
  EXPECT_THROW(raster::read_map_json("{\"regions\": []}"), std::runtime_error);
}

}  // namespace
