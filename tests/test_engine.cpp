// The Franklin engine against the independent brute-force checker, on the
// degenerate corpus (through the command line, end to end) and on seeded random
// scenes; plus the properties any correct engine has: the grid is scaffolding
// only (the map does not depend on c), and runs are reproducible byte for byte.
#include <gtest/gtest.h>
#include <gmpxx.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <numeric>
#include <atomic>
#include <stdexcept>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "arrangements/json_writer.h"
#include "bench/scene_gen.h"
#include "engine/franklin_grid.h"
#include "engine/lazy_leaves.h"
#include "engine/parallel.h"
#include "engine/screen_scene.h"
#include "engine/union_find.h"
#include "engine/world_exact.h"
#include "engine/world_facets.h"
#include "engine/visibility.h"
#include "tests/run_child.h"
#include "tests/test_support.h"

namespace {

namespace fs = std::filesystem;
using vismap::Vec3;
using vismap_test::Case;
using vismap_test::expect_checked;
using vismap_test::slurp;

// The map as JSON without the grid-dependent statistics.
std::string map_json(const vismap::Scene& scene, const vismap::View& view, const vismap::Options& opt) {
  vismap::VisibilityMap map = vismap::visibility_franklin(scene, view, opt);
  map.stats = {};
  return vismap::to_json(map);
}

// The "segments" list of a map's JSON text (up to the free-form stats).
std::string segments_of(const std::string& json) {
  const auto from = json.find("\"segments\""), to = json.find("\"stats\"");
  return from == std::string::npos ? "" : json.substr(from, to - from);
}

// A map's JSON text up to its stats, without its "hidden" list: the map as
// written without --hidden (whose counters differ).
std::string without_hidden(const std::string& json) {
  const auto from = json.find(",\n\"hidden\""), to = json.find(",\n\"stats\"");
  return json.substr(0, std::min(from, to));
}

// ---- the degenerate corpus, end to end ----------------------------------------

std::vector<Case> corpus() {
  std::vector<Case> cases;
  for (const std::string& line : vismap_test::case_lines(fs::path(VISMAP_DATA_DIR) / "cases.txt"))
    cases.push_back(vismap_test::split_case(line));
  return cases;
}

class Corpus : public ::testing::TestWithParam<Case> {};

TEST_P(Corpus, CheckerAcceptsTheMapAndRunsAreReproducible) {
  const Case& c = GetParam();
  const fs::path scene = fs::path(VISMAP_DATA_DIR) / c.file;
  const fs::path dir = fs::temp_directory_path() / ("vismap_corpus_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path out1 = dir / (c.file + ".1.json"), out2 = dir / (c.file + ".2.json");
  for (const auto& [out, threads] : {std::pair{out1, " --threads 1"}, std::pair{out2, " --threads 3"}}) {
    std::string cmd =
        std::string(VISMAP_BIN) + " '" + scene.string() + "' " + c.args + threads + " --json '" + out.string() + "'";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  }
  const std::string json = slurp(out1);
  EXPECT_EQ(json, slurp(out2)) << "two runs differ (one thread, three threads)";
  // The lines alone (--no-regions; a lines-only SVG): the same segments, byte for
  // byte, computed without the regions; the SVG as drawn from the whole map.
  const fs::path lines = dir / (c.file + ".lines.json"), svg_whole = dir / (c.file + ".whole.svg"),
                 svg_lines = dir / (c.file + ".lines.svg");
  for (const std::string& extra : {" --no-regions --json '" + lines.string() + "'",
                                   " --lines-only -o '" + svg_lines.string() + "'",
                                   " --lines-only -o '" + svg_whole.string() + "' --json '" + out2.string() + "'"}) {
    std::string cmd = std::string(VISMAP_BIN) + " '" + scene.string() + "' " + c.args + extra;
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  }
  EXPECT_EQ(segments_of(slurp(lines)), segments_of(json)) << "--no-regions changed the segments";
  EXPECT_EQ(slurp(lines).find("\"regions\""), std::string::npos) << "--no-regions wrote regions";
  EXPECT_EQ(slurp(svg_lines), slurp(svg_whole)) << "a lines-only drawing differs from the whole map's";
  // With the hidden lines: the same map, plus its "hidden" list.
  const fs::path with_hidden = dir / (c.file + ".hidden.json");
  const std::string cmd = std::string(VISMAP_BIN) + " '" + scene.string() + "' " + c.args + " --hidden --json '" +
                          with_hidden.string() + "'";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  const std::string hidden_json = slurp(with_hidden);
  EXPECT_NE(hidden_json.find("\"hidden\""), std::string::npos) << "--hidden wrote no hidden lines";
  EXPECT_EQ(without_hidden(hidden_json), without_hidden(json)) << "--hidden changed the rest of the map";
  // The lines alone (--no-regions) with hidden lines: the same hidden list.
  const fs::path lines_hidden = dir / (c.file + ".lines_hidden.json");
  const std::string cmd2 = std::string(VISMAP_BIN) + " '" + scene.string() + "' " + c.args + " --hidden --no-regions --json '" +
                           lines_hidden.string() + "'";
  ASSERT_EQ(std::system(cmd2.c_str()), 0) << cmd2;
  auto hidden_of = [](const std::string& j) {
    const auto from = j.find("\"hidden\""), to = j.find("\"stats\"");
    return from == std::string::npos ? std::string() : j.substr(from, to - from);
  };
  EXPECT_EQ(hidden_of(slurp(lines_hidden)), hidden_of(hidden_json)) << "--no-regions changed the hidden lines";
  vismap_check::Options opt;
  opt.smooth = c.args.find("--smooth") != std::string::npos;
  if (auto k = c.args.find("--crease "); k != std::string::npos) opt.crease_deg = std::stod(c.args.substr(k + 9));
  expect_checked(vismap::read_scene(scene.string()), json, opt, c.file);
  expect_checked(vismap::read_scene(scene.string()), hidden_json, opt, c.file + " (hidden lines)");
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Degenerate, Corpus, ::testing::ValuesIn(corpus()),
                         [](const auto& info) { return vismap_test::case_name(info.param.file, info.index); });

// ---- seeded random scenes --------------------------------------------------------

struct RandomCase {
  std::string name;
  vismap::Scene (*make)(std::uint64_t seed);
  vismap::Camera camera;
};

vismap::Camera ortho(Vec3 d) { vismap::Camera c; c.dir = d; return c; }
vismap::Camera persp(Vec3 eye, Vec3 target, double fov) {
  vismap::Camera c;
  c.eye = eye;
  c.target = target;
  c.fov_deg = fov;
  return c;
}

std::vector<RandomCase> random_cases() {
  using namespace vismap::gen;
  return {
      {"squares_top", [](std::uint64_t s) { return random_squares_depth(40, 3, s); }, ortho({0, 0, -1})},
      {"squares_oblique", [](std::uint64_t s) { return random_squares_depth(30, 4, s); }, ortho({-0.3, -0.5, -1})},
      {"squares_perspective", [](std::uint64_t s) { return random_squares_depth(30, 3, s); },
       persp({0.5, 0.5, 3}, {0.45, 0.55, 0}, 50)},
      {"triangles", [](std::uint64_t s) { return random_triangles(30, 0.4, s); }, ortho({-1, -2, -1.5})},
      {"holed_plates", [](std::uint64_t s) { return holed_plates(5, s); }, ortho({-1, -2, -1.5})},
      {"holed_plates_perspective", [](std::uint64_t s) { return holed_plates(5, s); },
       persp({1.2, -0.6, 1.1}, {0.6, 0.5, 0.5}, 70)},
      {"triangles_perspective", [](std::uint64_t s) { return random_triangles(30, 0.4, s); },
       persp({1.5, 2.2, 1.7}, {0.5, 0.5, 0.5}, 60)},
      {"boxes", [](std::uint64_t s) { return interpenetrating_boxes(4, s); }, ortho({-1, -2, -1.5})},
      {"boxes_perspective", [](std::uint64_t s) { return interpenetrating_boxes(4, s); },
       persp({3, -4, 3.5}, {0, 0, 0}, 45)},
      {"terrain", [](std::uint64_t s) { return terrain(5, s); }, ortho({-1, -0.5, -0.7})},
      {"corner_fans", [](std::uint64_t s) { return corner_fans(14, 2, s); }, ortho({-1, -2, -1.5})},
      {"corner_fans_perspective", [](std::uint64_t s) { return corner_fans(14, 2, s); },
       persp({1.8, -1.2, 1.6}, {0.5, 0.5, 0.5}, 60)},
  };
}

class Random : public ::testing::TestWithParam<std::tuple<int, int>> {};

TEST_P(Random, CheckerAcceptsTheMap) {
  const auto cases = random_cases();
  const RandomCase& rc = cases[std::get<0>(GetParam())];
  const std::uint64_t seed = static_cast<std::uint64_t>(std::get<1>(GetParam()));
  vismap::Scene scene = rc.make(seed);
  scene.file = rc.name;
  vismap::View view = vismap::make_view(rc.camera, scene);
  vismap_check::Options opt;
  opt.samples = 1500;
  opt.seed = seed;
  const std::string json = map_json(scene, view, {});
  expect_checked(scene, json, opt, rc.name + " seed " + std::to_string(seed));
  vismap::Options hidden;
  hidden.hidden = true;
  const std::string hidden_json = map_json(scene, view, hidden);
  EXPECT_EQ(without_hidden(hidden_json), without_hidden(json)) << rc.name + " seed " + std::to_string(seed) << ": hidden lines changed the map";
  expect_checked(scene, hidden_json, opt, rc.name + " seed " + std::to_string(seed) + " (hidden lines)");
  vismap::Options lines_only;
  lines_only.regions = false;
  EXPECT_EQ(segments_of(map_json(scene, view, lines_only)), segments_of(json))
      << rc.name + " seed " + std::to_string(seed) << ": the lines alone differ from the whole map's";
}

INSTANTIATE_TEST_SUITE_P(Scenes, Random,
                         ::testing::Combine(::testing::Range(0, static_cast<int>(random_cases().size())),
                                            ::testing::Range(1, 5)),
                         [](const auto& info) {
                           return random_cases()[std::get<0>(info.param)].name + "_seed" +
                                  std::to_string(std::get<1>(info.param));
                         });

// ---- hidden lines: the checker refuses each way of getting them wrong ----------------

// Two interpenetrating boxes seen obliquely: hidden edges of back faces, hidden
// stretches of front ones, and hidden intersection lines.
TEST(HiddenLines, CheckerRefusesEachMutation) {
  const vismap::Scene scene = vismap::read_scene((fs::path(VISMAP_DATA_DIR) / "interpenetrating_boxes.off").string());
  vismap::Camera cam;
  cam.dir = Vec3{-1, -2, -4};
  const vismap::View view = vismap::make_view(cam, scene);
  vismap::Options opt;
  opt.hidden = true;
  const vismap::VisibilityMap map = vismap::visibility_franklin(scene, view, opt);
  ASSERT_GE(map.hidden.size(), 4u);
  vismap_check::Options check;
  expect_checked(scene, vismap::to_json(map), check, "the hidden lines as made");
  auto sorted = [](std::vector<vismap::HiddenSegment>& h) {
    std::sort(h.begin(), h.end(), [](const auto& a, const auto& b) {
      return a.from < b.from || (a.from == b.from && a.to < b.to);
    });
  };
  using Mutation = std::function<void(vismap::VisibilityMap&)>;
  const std::vector<std::pair<std::string, Mutation>> mutations = {
      {"a hidden segment dropped", [](vismap::VisibilityMap& m) { m.hidden.erase(m.hidden.begin() + 1); }},
      {"a visible segment added as hidden",
       [&](vismap::VisibilityMap& m) {
         const vismap::Segment& s = m.segments[0];
         m.hidden.push_back({m.at(s.from), m.at(s.to), s.kind, s.faces});
         sorted(m.hidden);
       }},
      {"a wrong kind",
       [](vismap::VisibilityMap& m) {
         vismap::HiddenSegment& h = m.hidden[0];
         h.kind = h.kind == vismap::EdgeKind::Border ? vismap::EdgeKind::Silhouette : vismap::EdgeKind::Border;
         h.faces.resize(h.kind == vismap::EdgeKind::Border ? 1 : 2, h.faces[0] + 1);
       }},
      {"two overlapping",
       [&](vismap::VisibilityMap& m) {
         vismap::HiddenSegment h = m.hidden[0];
         h.to = vismap::Point2{(h.from.x + h.to.x) / 2, (h.from.y + h.to.y) / 2};
         m.hidden.push_back(h);
         sorted(m.hidden);
       }},
      {"a segment split where nothing changes",
       [&](vismap::VisibilityMap& m) {
         vismap::HiddenSegment a = m.hidden[0], b = m.hidden[0];
         a.to = b.from = vismap::Point2{(a.from.x + a.to.x) / 2, (a.from.y + a.to.y) / 2};
         m.hidden[0] = a;
         m.hidden.push_back(b);
         sorted(m.hidden);
       }},
  };
  for (const auto& [what, mutate] : mutations) {
    vismap::VisibilityMap wrong = map;
    mutate(wrong);
    const vismap_check::Report r = vismap_check::check_map(scene, vismap::to_json(wrong), check);
    EXPECT_FALSE(r.ok) << what << ": accepted";
    bool named = false;
    for (const std::string& f : r.failures) named = named || f.find("hidden") != std::string::npos;
    EXPECT_TRUE(named) << what << ": refused, but not for its hidden lines";
  }
}

// ---- a lines-only drawing of one surface looks only near its drawn lines ------------

// A terrain alone (a height field: no two of its faces pierce each other): the
// lines-only drawing fills only the grid cells near its drawn lines (stat
// cells_for_drawn_lines, fewer than the grid's), and its segments are still the
// whole map's, on every thread count: in views where hills hide valleys, along a
// grazing direction, and from close by in perspective (near faces cover many
// cells and block them), at two grid sizes. Where the near plane cuts nothing, it
// makes whole only the faces those cells need (stat facets_made).
namespace {
// A height field over the unit square, n x n cells of two triangles.
vismap::Scene hills(int n) {
  vismap::Scene scene;
  scene.file = "hills";
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = static_cast<double>(i) / n, y = static_cast<double>(j) / n;
      scene.vertices.push_back({x, y, 0.15 * std::sin(9 * x) * std::cos(7 * y) + 0.04 * std::sin(23 * x * y)});
    }
  auto id = [&](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      scene.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      scene.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return scene;
}

// The scene with every coordinate times 2^e (exact: a power of two).
vismap::Scene scaled_by_power_of_two(vismap::Scene scene, int e) {
  for (vismap::Vec3& v : scene.vertices) v = {std::ldexp(v.x, e), std::ldexp(v.y, e), std::ldexp(v.z, e)};
  return scene;
}
}  // namespace

TEST(LinesOnly, OneSurfaceIsLookedAtOnlyNearItsDrawnLines) {
  const vismap::Scene scene = hills(40);
  const std::vector<vismap::Camera> cameras = {ortho({-1, -2, -3}), ortho({-1, -0.3, -0.18}),
                                               persp({1.8, -1.2, 0.9}, {0.5, 0.5, 0}, 35),
                                               persp({0.45, 0.2, 0.3}, {0.5, 0.6, 0}, 70)};
  for (std::size_t k = 0; k < cameras.size(); ++k)
    for (double c : {1.0, 4.0}) {
      const vismap::View view = vismap::make_view(cameras[k], scene);
      vismap::Options whole;
      whole.grid_c = c;
      whole.threads = 1;
      vismap::Options lines = whole;
      lines.regions = false;
      const std::string what = "camera " + std::to_string(k) + ", c " + std::to_string(c);
      const vismap::VisibilityMap m = vismap::visibility_franklin(scene, view, lines);
      EXPECT_GT(m.stats.counted("cells_for_drawn_lines"), 0) << what;
      EXPECT_LT(m.stats.counted("cells_for_drawn_lines"), m.stats.counted("grid_cells")) << what;
      // Nothing cut at the near plane: faces made only where needed; obliquely,
      // those far from the lines stay briefs (grazing, the lines reach everywhere).
      if (k < 3) {
        EXPECT_GT(m.stats.counted("facets_made"), 0) << what;
      }
      if (k == 0) {
        EXPECT_LT(m.stats.counted("facets_made"), m.stats.counted("facets")) << what;
      }
      EXPECT_GT(m.segments.size(), 20u) << what;
      const std::string drawn = segments_of(map_json(scene, view, lines));
      EXPECT_EQ(drawn, segments_of(map_json(scene, view, whole))) << what << ": the lines alone differ from the whole map's";
      lines.threads = 3;
      EXPECT_EQ(segments_of(map_json(scene, view, lines)), drawn) << what << ": three threads differ from one";
    }
}

// Where two drawn lines of one face meet collinearly (a polygon's border through
// a corner on a straight side), the map joins them into one segment unless
// something else visible ends there. Here two smooth edges end there: a wedge
// face between them, in a notch of a face that passes under the polygon, the
// same face on both sides of the wedge. A lines-only drawing skips the curves
// that are not drawn and only share an end with a drawn one, but not these:
// the side stays cut at that corner, as in the whole map.
TEST(LinesOnly, UndrawnEdgesEndingWhereTwoDrawnLinesCouldJoinAreKept) {
  vismap::Scene scene;
  // The plate, face 0: a square with a corner M = (1, 0, 0) on its bottom side.
  scene.vertices = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}};
  scene.faces = {{0, 1, 2, 3, 4}};
  // Faces 1 (notched round M) and 2 (the wedge in the notch), in one plane
  // through M: below the plate where they pass under it, above it outside.
  for (const auto& [x, y] : std::vector<std::pair<double, double>>{
           {0.9, -0.4}, {1.1, -0.4}, {1.5, -0.5}, {1.5, 0.5}, {0.5, 0.5}, {0.5, -0.5}})
    scene.vertices.push_back({x, y, -0.1 * y});
  const std::uint32_t corner = 1, g1 = 5, g2 = 6;
  scene.faces.push_back({corner, g2, 7, 8, 9, 10, g1});
  scene.faces.push_back({corner, g1, g2});
  const vismap::View view = vismap::make_view(ortho({0.1, 0.2, -1}), scene);
  vismap::Options whole;
  whole.threads = 1;
  vismap::Options lines = whole;
  lines.regions = false;
  // In the whole map, one vertex (M's image) joins exactly two segments, the
  // plate's, collinear: cut there only for the smooth edges.
  const vismap::VisibilityMap m = vismap::visibility_franklin(scene, view, whole);
  std::map<std::uint32_t, std::vector<std::size_t>> ending;   // vertex -> its segments
  for (std::size_t i = 0; i < m.segments.size(); ++i)
    for (const std::uint32_t v : {m.segments[i].from, m.segments[i].to}) ending[v].push_back(i);
  int kept_corners = 0;
  for (const auto& [v, at] : ending) {
    if (at.size() != 2) continue;
    const auto& s = m.segments[at[0]];
    const auto& t = m.segments[at[1]];
    if (s.faces != std::vector<int>{0} || t.faces != std::vector<int>{0}) continue;
    const vismap::Point2 &p = m.at(s.from == v ? s.to : s.from), &o = m.at(v), &q = m.at(t.from == v ? t.to : t.from);
    kept_corners += (o.x - p.x) * (q.y - p.y) == (o.y - p.y) * (q.x - p.x);
  }
  EXPECT_EQ(kept_corners, 1) << "the plate's side is not cut at M alone";
  const std::string drawn = segments_of(map_json(scene, view, lines));
  EXPECT_EQ(drawn, segments_of(map_json(scene, view, whole))) << "the lines alone differ from the whole map's";
}

// A lines-only drawing leaves the pieces it does not draw latent (made later
// only where a drawn line is) while they are the more numerous; where most
// edges are drawn (a small crease angle on a dense mesh) it is made as a whole
// map, its segments alone written. Either way: the whole map's segments.
TEST(LinesOnly, PiecesLeftLatentOnlyWhereMostAreNotDrawn) {
  const vismap::Scene scene = hills(40);
  const vismap::View view = vismap::make_view(ortho({-1, -2, -3}), scene);
  for (const double crease : {30.0, 2.0}) {
    vismap::Options whole;
    whole.crease_deg = crease;
    vismap::Options lines = whole;
    lines.regions = false;
    const vismap::VisibilityMap m = vismap::visibility_franklin(scene, view, lines);
    const std::int64_t pieces = m.stats.counted("edge_pieces"), latent = m.stats.counted("curves_latent");
    const std::int64_t as_whole = m.stats.counted("lines_only_as_whole_map");
    if (crease == 30.0) {
      EXPECT_GT(2 * latent, pieces) << "most of a smooth surface's pieces are left latent";
      EXPECT_EQ(as_whole, 0);
    } else {
      EXPECT_EQ(as_whole, 1) << "most edges drawn: made as a whole map";
    }
    EXPECT_EQ(segments_of(map_json(scene, view, lines)), segments_of(map_json(scene, view, whole))) << "crease " << crease;
  }
}

// A lines-only drawing's screen scene leaves the vertex images for later where
// the near plane cuts nothing, projecting, culling and boxing the faces on the
// intervals it keeps for them: those must be the very intervals each image has
// once made (else boxes, cells and filters would differ from the whole map's).
// Oblique, along an axis (coordinates exact in doubles), in perspective from
// outside, at a scale that leaves the moderate range; and where the near plane
// cuts, every image is made at once.
TEST(LinesOnly, ImagesLeftForLaterKeepTheIntervalsTheyGet) {
  const vismap::Scene scene = hills(40);
  const vismap::Scene huge = scaled_by_power_of_two(scene, 600);
  struct Case {
    const vismap::Scene* scene;
    vismap::Camera camera;
    bool later;
  };
  const std::vector<Case> cases = {{&scene, ortho({-1, -2, -3}), true},
                                   {&scene, ortho({0, 0, -1}), true},
                                   {&scene, persp({1.8, -1.2, 0.9}, {0.5, 0.5, 0}, 35), true},
                                   {&huge, ortho({-1, -2, -3}), true},
                                   {&scene, persp({0.5, 0.5, 0.05}, {0.9, 0.9, 0}, 90), false}};
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const vismap::View view = vismap::make_view(cases[k].camera, *cases[k].scene);
    vismap::Options opt;
    opt.threads = 2;
    vismap::Stats stats;
    auto ss = vismap::engine::make_screen_scene(*cases[k].scene, view, opt, stats, /*latent=*/true);
    const std::size_t n = ss.images.size();
    ASSERT_EQ(!ss.image_bounds.empty(), cases[k].later) << "case " << k;
    if (!cases[k].later) continue;
    // (Kept, or where a sparse scene makes them only when asked, computed when read.)
    std::vector<vismap::engine::ImageBounds> kept(n);
    for (std::size_t u = 0; u < n; ++u) kept[u] = ss.kept_bounds(static_cast<std::ptrdiff_t>(u));
    std::size_t made = 0;
    for (std::size_t u = 0; u < n; ++u) made += ss.images.made(u);
    EXPECT_LT(made, n / 2) << "case " << k << ": most images are left for later (" << made << " of " << n << " made)";
    std::vector<std::uint32_t> all(n);
    for (std::size_t u = 0; u < n; ++u) all[u] = static_cast<std::uint32_t>(u);
    vismap::engine::make_images(ss, all, 2);
    auto same = [](const vismap::engine::Interval& a, const vismap::engine::Interval& b) {
      return a.inf() == b.inf() && a.sup() == b.sup();
    };
    for (std::size_t u = 0; u < n; ++u) {
      ASSERT_TRUE(ss.images.made(u)) << "case " << k << ", image " << u;
      const vismap::engine::P3& p = ss.images[u];
      EXPECT_TRUE(same(vismap::engine::approx_of(p.x), kept[u].x) && same(vismap::engine::approx_of(p.y), kept[u].y) &&
                  same(vismap::engine::approx_of(p.z), kept[u].z))
          << "case " << k << ", image " << u;
    }
  }
}

// An orthographic lines-only drawing of one solid (a height field, a closed
// solid seen from outside) is sparse: it makes the intervals of the vertex
// images and the boxes of the faces only near its drawn lines, finding those
// faces from runs of faces boxed in the world (stat image_bounds_made). Its
// segments are the whole map's, on one thread and three: obliquely, grazing,
// along an axis, at two grid sizes, and at a scale far from 1.
TEST(LinesOnly, SparseDrawingsBoxOnlyTheFacesNearTheirLines) {
  const vismap::Scene terrain = hills(40);
  const vismap::Scene huge = scaled_by_power_of_two(terrain, 100);
  struct Case {
    const vismap::Scene* scene;
    vismap::Camera camera;
    double crease;
  };
  const std::vector<Case> cases = {{&terrain, ortho({-1, -2, -3}), 30},     {&terrain, ortho({-1, -0.3, -0.18}), 30},
                                   {&terrain, ortho({0, 0, -1}), 30},        {&terrain, ortho({-1, -2, -3}), 10},
                                   {&huge, ortho({-1, -2, -3}), 30}};
  for (std::size_t k = 0; k < cases.size(); ++k)
    for (double c : {1.0, 4.0}) {
      const Case& t = cases[k];
      const vismap::View view = vismap::make_view(t.camera, *t.scene);
      vismap::Options whole;
      whole.grid_c = c;
      whole.crease_deg = t.crease;
      whole.threads = 1;
      vismap::Options lines = whole;
      lines.regions = false;
      const std::string what = "case " + std::to_string(k) + ", c " + std::to_string(c);
      const vismap::VisibilityMap m = vismap::visibility_franklin(*t.scene, view, lines);
      EXPECT_GT(m.stats.counted("image_bounds_made"), 0) << what << ": not sparse";
      EXPECT_GT(m.segments.size(), 5u) << what;
      const std::string drawn = segments_of(map_json(*t.scene, view, lines));
      EXPECT_EQ(drawn, segments_of(map_json(*t.scene, view, whole))) << what << ": the lines alone differ from the whole map's";
      lines.threads = 3;
      EXPECT_EQ(segments_of(map_json(*t.scene, view, lines)), drawn) << what << ": three threads differ from one";
    }
}

// ---- the grid is scaffolding: any c gives the same map ------------------------------

TEST(GridIndependence, SameMapForEveryGridConstant) {
  for (std::uint64_t seed : {1u, 2u}) {
    vismap::Scene scene = vismap::gen::random_squares_depth(300, 6, seed);
    vismap::gen::append_scene(scene, vismap::gen::interpenetrating_boxes(6, seed));
    vismap::View view = vismap::make_view(ortho({-0.2, -0.3, -1}), scene);
    vismap::Options opt;
    opt.grid_c = 4;
    const std::string reference = map_json(scene, view, opt);
    for (double c : {0.3, 1.0, 2.5, 9.0}) {
      opt.grid_c = c;
      EXPECT_EQ(map_json(scene, view, opt), reference) << "grid c = " << c << ", seed " << seed;
    }
  }
}

// An axis finds the cell of any coordinate (the last boundary at or below it,
// clamped to the first and last cell), on boundaries evenly spaced and on
// boundaries spread as a close-up's are (the quantiles of tan: a few outer
// cells reach a hundred times further than the rest, which a table of even
// bins over the whole span crowds into a few bins), in a few halving steps.
TEST(GridAxis, FindsEveryCellInFewStepsOnEvenAndSpreadBoundaries) {
  const double pi = std::acos(-1.0);
  for (const bool spread : {false, true}) {
    std::vector<double> bounds;
    const int cells = 223;
    for (int i = 0; i <= cells; ++i)
      bounds.push_back(spread ? std::tan(0.998 * pi * (static_cast<double>(i) / cells - 0.5)) : 0.25 * i - 7);
    const vismap::engine::Axis axis(bounds);
    ASSERT_EQ(axis.cells(), cells);
    auto expected = [&](double v) {
      const auto above = std::upper_bound(bounds.begin(), bounds.end(), v) - bounds.begin();
      return static_cast<int>(std::clamp<std::ptrdiff_t>(above - 1, 0, cells - 1));
    };
    std::vector<double> probes{-1e300, 1e300, bounds.front() - 1, bounds.back() + 1};
    for (std::size_t i = 0; i < bounds.size(); ++i) {
      probes.push_back(bounds[i]);
      probes.push_back(std::nextafter(bounds[i], -HUGE_VAL));
      probes.push_back(std::nextafter(bounds[i], HUGE_VAL));
      if (i + 1 < bounds.size()) probes.push_back(0.5 * (bounds[i] + bounds[i + 1]));
    }
    for (const double v : probes) EXPECT_EQ(axis.index(v), expected(v)) << "at " << v << (spread ? " (spread)" : "");
    // (On the spread boundaries a table over the whole span takes 2.6 steps a cell.)
    EXPECT_LT(axis.steps_per_cell(), 2.0) << (spread ? "spread" : "even");
  }
}

// ---- projected coordinates' intervals ------------------------------------------------

// The interval a projected coordinate's filter reads, made on doubles (Sum2
// and its last rounding's error), holds row . (p, 1) * 2^k and is exactly
// projected_mpzf's (the value rounded down and up) wherever it is made: on
// random rows and points over a wide range of magnitudes, with cancellation
// (points near the row's zero), and screen scales 2^k. (Wider intervals made
// the counted predicates depend on the thread count: see projected_bounds.)
TEST(ProjectedBounds, HoldTheExactValueAsTightlyAsMpzf) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::uniform_int_distribution<int> exponent(-60, 60), scale(-70, 70);
  int checked = 0, as_mpzf = 0;
  for (int n = 0; n < 200000; ++n) {
    std::array<double, 4> row{unit(rng), unit(rng), unit(rng), std::ldexp(unit(rng), exponent(rng))};
    const int e = exponent(rng);
    vismap::Vec3 p{std::ldexp(unit(rng), e), std::ldexp(unit(rng), e), std::ldexp(unit(rng), e)};
    if (n % 4 == 0) {   // near the plane row . (p, 1) = 0: the sum cancels
      const double t = -(row[0] * p.x + row[1] * p.y + row[3]) / row[2];
      if (std::isfinite(t)) p.z = t;
    }
    const int k = n % 3 == 0 ? 0 : scale(rng);
    double lo, hi;
    if (!vismap::exact::projected_bounds(row, p, k, lo, hi)) continue;
    mpq_class exact = mpq_class(row[0]) * p.x + mpq_class(row[1]) * p.y + mpq_class(row[2]) * p.z + row[3];
    if (k > 0) mpq_mul_2exp(exact.get_mpq_t(), exact.get_mpq_t(), static_cast<unsigned long>(k));
    if (k < 0) mpq_div_2exp(exact.get_mpq_t(), exact.get_mpq_t(), static_cast<unsigned long>(-k));
    ASSERT_LE(mpq_class(lo), exact) << n;
    ASSERT_GE(mpq_class(hi), exact) << n;
    const std::pair<double, double> want = vismap::exact::projected_mpzf(row, p, k).to_interval();
    as_mpzf += lo == want.first && hi == want.second;
    ++checked;
  }
  EXPECT_GT(checked, 140000);   // (the rest: cancelling too far, left to Mpzf)
  EXPECT_EQ(as_mpzf, checked);
}

// The orthographic view along d of the points `world`, and `source` (what lazy
// exact values come from) set to see them through it.
vismap::View look_along(const std::array<double, 3>& d, const std::vector<vismap::Vec3>& world,
                        vismap::exact::ExactSource& source) {
  vismap::Scene scene;
  scene.vertices = world;
  vismap::Camera cam;
  cam.dir = vismap::Vec3{d[0], d[1], d[2]};
  const vismap::View view = vismap::make_view(cam, scene);
  source.vertices = &world;
  source.m = view.m;
  return view;
}

// Images on one screen line, told by the world (ExactSource::same_screen_coordinate):
// wherever it says two vertices have one screen x (or y), their exact projected
// values are equal; and on views along an axis, whose rows read one or two world
// coordinates, it says so for every pair that shares them (vertices on a coarse
// lattice: many do), in front and side views and in orbit views at azimuths of
// multiples of 90 degrees, whose rows are not powers of two.
TEST(ScreenLines, ImagesToldOnOneLineByTheWorldAreSo) {
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<int> lattice(0, 3);
  std::vector<vismap::Vec3> world;
  for (int i = 0; i < 64; ++i)
    world.push_back({1.3 * lattice(rng), 0.7 * lattice(rng) + 0.1, 2.9 * lattice(rng) / 3});
  int told = 0, pairs_sharing = 0;
  for (const std::array<double, 3>& d : std::vector<std::array<double, 3>>{
           {0, -1, 0}, {-1, 0, 0}, {-0.866, 0, -0.5}, {0, 0.866, -0.5}, {-1, -2, -3}, {0.3, 0, -1}}) {
    vismap::exact::ExactSource source;
    const vismap::View view = look_along(d, world, source);
    for (std::uint32_t a = 0; a < world.size(); ++a)
      for (std::uint32_t b = 0; b < world.size(); ++b)
        for (int r : {0, 1}) {
          const bool same = source.same_screen_coordinate(a, b, r);
          const auto& row = view.m[static_cast<std::size_t>(r)];
          const vismap::Vec3 &p = world[a], &q = world[b];
          const bool shares = (row[0] == 0 || p.x == q.x) && (row[1] == 0 || p.y == q.y) && (row[2] == 0 || p.z == q.z);
          if (same) {
            ++told;
            EXPECT_EQ(source.row_at(r, a, false), source.row_at(r, b, false)) << a << " " << b << " row " << r;
          }
          if (shares && a != b && (row[0] == 0 || row[1] == 0 || row[2] == 0)) {
            ++pairs_sharing;
            EXPECT_TRUE(same) << a << " " << b << " row " << r;
          }
        }
  }
  EXPECT_GT(pairs_sharing, 1000);
  EXPECT_GT(told, pairs_sharing);
}

// One screen x (or y) told exactly from the world (ExactSource::
// screen_coordinates_equal, no image's rational made): the same answer as the
// images' exact values, N / W in perspective, for every pair of vertices of a
// coarse lattice, seen in perspective straight down an axis from above the
// lattice (its rows along y fall on screen verticals, whose ends no interval
// tells equal), in perspective obliquely, and orthographically.
TEST(ScreenLines, ScreenCoordinatesToldEqualFromTheWorldAreSo) {
  std::mt19937_64 rng(13);
  std::uniform_int_distribution<int> lattice(0, 3);
  std::vector<vismap::Vec3> world;
  for (int i = 0; i < 48; ++i) world.push_back({0.3 * lattice(rng), 0.7 * lattice(rng) + 0.1, 0.2 * lattice(rng) / 3});
  vismap::Scene scene;
  scene.vertices = world;
  int equal = 0, apart = 0;
  for (const vismap::Camera& cam : {persp({0.55, 1.2, 5}, {0.55, 1.2, 0}, 30), persp({-2, -3, 4}, {0.4, 1, 0}, 40),
                                    ortho({-1, -2, -3})}) {
    const vismap::View view = vismap::make_view(cam, scene);
    vismap::exact::ExactSource source;
    source.vertices = &world;
    source.m = view.m;
    source.perspective = view.perspective;
    auto image = [&](std::uint32_t v, int r) {
      const mpq_class n(source.row_at(r, v, false));
      return view.perspective ? mpq_class(n / mpq_class(source.row_at(3, v, false))) : n;
    };
    for (std::uint32_t a = 0; a < world.size(); ++a)
      for (std::uint32_t b = a + 1; b < world.size(); ++b)
        for (int r : {0, 1}) {
          const bool want = image(a, r) == image(b, r);
          ASSERT_EQ(source.screen_coordinates_equal(a, b, r), want) << a << " " << b << " row " << r;
          (want ? equal : apart) += 1;
        }
  }
  EXPECT_GT(equal, 200);
  EXPECT_GT(apart, 2000);
}

// A vertex image's exact coordinate (ExactSource::image_exact, perspective_exact:
// machine integers where the values fit, image_values.h) is the canonical
// rational of the row applied to the vertex, times 2^k, over row 3 in
// perspective, as GMP makes it from binary floats: for rows and points of
// doubles of every kind (negative, zero, subnormal, huge, exponents close
// together or far apart: both ways taken) and scales up and down.
TEST(ImageValues, ExactCoordinatesAreTheRowsOverW) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::uniform_int_distribution<int> spread(-40, 40), kind(0, 15);
  auto any = [&]() {
    switch (kind(rng)) {
      case 0: return 0.0;
      case 1: return 5e-324 * (1 + kind(rng));
      case 2: return std::ldexp(unit(rng), 900);
      case 3: return std::ldexp(unit(rng), -900);
      case 4: return 0.5;
      default: return std::ldexp(unit(rng), spread(rng));
    }
  };
  std::vector<vismap::Vec3> world;
  for (int i = 0; i < 400; ++i) world.push_back({any(), any(), any()});
  int fitted = 0, not_fitted = 0;
  for (int view = 0; view < 40; ++view) {
    vismap::exact::ExactSource source;
    source.vertices = &world;
    for (auto& row : source.m)
      for (double& x : row) x = any();
    source.k = std::vector<int>{0, 3, -5, 40, -70}[static_cast<std::size_t>(view % 5)];
    for (std::uint32_t v = 0; v < world.size(); ++v) {
      vismap::exact::Dyadic d;
      (vismap::exact::row_dyadic(source.m[0], world[v], d) ? fitted : not_fitted) += 1;
      for (int r : {0, 1}) {
        auto canonical = [](const mpq_class& q) {
          mpq_class c = q;
          c.canonicalize();
          return c.get_num() == q.get_num() && c.get_den() == q.get_den();
        };
        const mpq_class image = source.image_exact(r, v, view % 2 == 0);
        ASSERT_EQ(image, mpq_class(source.row_at(r, v, view % 2 == 0))) << "view " << view << " vertex " << v;
        ASSERT_TRUE(canonical(image));
        const mpq_class w(source.row_at(3, v, false));
        if (w == 0) continue;
        const mpq_class quotient = source.perspective_exact(r, v);
        ASSERT_EQ(quotient, mpq_class(mpq_class(source.row_at(r, v, true)) / w)) << "view " << view << " vertex " << v;
        ASSERT_TRUE(canonical(quotient));
      }
    }
  }
  EXPECT_GT(fitted, 1000);
  EXPECT_GT(not_fitted, 1000);
}

// The screen cross product's sign from the world (ExactSource::screen_cross_sign,
// orthographic views): the same as on the images' exact projected values, for
// pairs of segments between vertices of a coarse lattice (parallel ones by the
// hundred: the zeros it finds in the world) and of random doubles, in views
// along an axis, at 30 degrees above an axis and obliquely.
TEST(ScreenLines, CrossProductSignsFromTheWorldAreTheImages) {
  std::mt19937_64 rng(12);
  std::uniform_int_distribution<int> lattice(0, 2);
  std::uniform_real_distribution<double> any(-3, 3);
  std::vector<vismap::Vec3> world;
  for (int i = 0; i < 24; ++i) world.push_back({1.3 * lattice(rng), 0.7 * lattice(rng) + 0.1, 2.9 * lattice(rng) / 3});
  for (int i = 0; i < 8; ++i) world.push_back({any(rng), any(rng), any(rng)});
  const auto n = static_cast<std::uint32_t>(world.size());
  int zeros = 0, signs = 0;
  // (Along a diagonal, the isometric views: two of the sight's coordinates
  // equal or opposite, ExactSource::axis_cross's machine-integer case.)
  for (const std::array<double, 3>& d : std::vector<std::array<double, 3>>{
           {0, -1, 0}, {-0.866, 0, -0.5}, {-1, -2, -3}, {0.3, 0.1, -1}, {-1, -1, -1}, {1, -1, -1}, {-2, -2, -1}}) {
    vismap::exact::ExactSource source;
    look_along(d, world, source);
    source.k = 3;
    auto image = [&](std::uint32_t v, int r) { return mpq_class(source.row_at(r, v, true)); };
    for (std::uint32_t a = 0; a < n; a += 3)
      for (std::uint32_t b = 1; b < n; b += 2)
        for (std::uint32_t c = 0; c < n; c += 2)
          for (std::uint32_t e = 1; e < n; e += 3) {
            const mpq_class cross = (image(b, 0) - image(a, 0)) * (image(e, 1) - image(c, 1)) -
                                    (image(b, 1) - image(a, 1)) * (image(e, 0) - image(c, 0));
            const int want = sgn(cross), got = source.screen_cross_sign(a, b, c, e);
            ASSERT_EQ(got, want) << a << " " << b << " " << c << " " << e << " dir " << d[0] << "," << d[1] << "," << d[2];
            (want == 0 ? zeros : signs) += 1;
          }
  }
  EXPECT_GT(zeros, 500);
  EXPECT_GT(signs, 5000);
}

// Order on lazy points without exceptions (exact_kernel.h): between_on_line,
// compare_xy_exactly and compare_coordinate_exactly answer as CGAL's predicates on the exact points, on a
// vertical line whose x is no double (1/3), a horizontal one, and a slanted
// one, each with a point repeated as a second object of the same value; and on
// the vertical line, whose points' y set them apart or are equal doubles, no
// exact value is needed, where CGAL's own predicate (which decides x first)
// needs one.
TEST(PointOrder, AsCGALsOnExactPointsAndWithoutExactValuesOnAVerticalLine) {
  using vismap::exact::FT;
  using vismap::exact::P2;
  const FT third = FT(1) / FT(3), seventh = FT(2) / FT(7);
  auto vertical = [&](double y) { return P2(FT(1) / FT(3), FT(y)); };
  auto horizontal = [&](double x) { return P2(FT(x), FT(2) / FT(7)); };
  auto slanted = [&](double t) { return P2(third + FT(t) / FT(5), seventh - FT(t) / FT(9)); };
  const std::vector<double> at{-2, 0.5, 3, 0.5, 7.25};   // (0.5 twice: equal points, two objects)
  for (int line = 0; line < 3; ++line) {
    std::vector<P2> pts;
    for (double t : at) pts.push_back(line == 0 ? vertical(t) : line == 1 ? horizontal(t) : slanted(t));
    for (const P2& a : pts)
      for (const P2& b : pts) {
        EXPECT_EQ(vismap::exact::compare_xy_exactly(a, b), CGAL::compare_xy(CGAL::exact(a), CGAL::exact(b)));
        EXPECT_EQ(vismap::exact::compare_coordinate_exactly(a, b, true), CGAL::compare_x(CGAL::exact(a), CGAL::exact(b)));
        EXPECT_EQ(vismap::exact::compare_coordinate_exactly(a, b, false), CGAL::compare_y(CGAL::exact(a), CGAL::exact(b)));
        for (const P2& c : pts)
          for (bool strictly : {false, true}) {
            const auto &ea = CGAL::exact(a), &eb = CGAL::exact(b), &ec = CGAL::exact(c);
            const bool want = strictly ? CGAL::collinear_are_strictly_ordered_along_line(ea, eb, ec)
                                       : CGAL::collinear_are_ordered_along_line(ea, eb, ec);
            EXPECT_EQ(vismap::exact::between_on_line(a, b, c, strictly), want) << "line " << line;
          }
      }
  }
  const P2 p = vertical(1), q = vertical(2), r = vertical(4);
  const std::int64_t before = vismap::exact::filter_counts.exact;
  EXPECT_TRUE(vismap::exact::between_on_line(p, q, r, true));
  EXPECT_FALSE(vismap::exact::between_on_line(q, p, r, true));
  // (At an end, as a second object of its value: the ends' y are doubles, unequal.)
  const P2 q2 = vertical(2);
  EXPECT_TRUE(vismap::exact::between_on_line(q, q2, r, false));
  EXPECT_FALSE(vismap::exact::between_on_line(q, q2, r, true));
  EXPECT_FALSE(vismap::exact::between_on_line(p, q2, q, true));
  EXPECT_TRUE(vismap::exact::between_on_line(p, q2, q, false));
  EXPECT_EQ(vismap::exact::filter_counts.exact, before);
  EXPECT_TRUE(CGAL::collinear_are_strictly_ordered_along_line(p, q, r));
  EXPECT_EQ(vismap::exact::filter_counts.exact, before + 1);
}

// ---- the interval filter -----------------------------------------------------------

// An interval holds the exact value: [0, 0] proves an exact zero (differences
// of equal doubles, products with them) as [1, 2] proves a positive sign, with
// no exact stage; an interval that reaches 0 from one side or across it does
// not, and the exact value decides (and is counted).
TEST(FilteredSign, ExactZerosOnDoublesNeedNoExactStage) {
  using vismap::exact::Interval;
  int exact_calls = 0;
  auto sign = [&](auto approx, int exact_value) {
    return vismap::exact::filtered_sign(approx, [&]() -> mpq_class { ++exact_calls; return exact_value; });
  };
  const std::int64_t before = vismap::exact::filter_counts.exact;
  const Interval x(0.1), y(0.30000000000000004);
  EXPECT_EQ(sign([&] { return (x - x) * (y - Interval(2.5, 3)) - (y - y) * x; }, 0), CGAL::ZERO);
  EXPECT_EQ(sign([&] { return Interval(-0.0, 0.0); }, 0), CGAL::ZERO);
  EXPECT_EQ(sign([&] { return Interval(1, 2); }, 1), CGAL::POSITIVE);
  EXPECT_EQ(exact_calls, 0);
  EXPECT_EQ(vismap::exact::filter_counts.exact, before);
  // (0.1 * 3 and 0.3 are not one double: their difference's interval is not a point.)
  EXPECT_EQ(sign([&] { return x * Interval(3) - Interval(0.3); }, 0), CGAL::ZERO);
  EXPECT_EQ(sign([&] { return Interval(0, 1e-300); }, 1), CGAL::POSITIVE);
  EXPECT_EQ(sign([&] { return Interval(-1e-300, 0); }, -1), CGAL::NEGATIVE);
  EXPECT_EQ(exact_calls, 3);
  EXPECT_EQ(vismap::exact::filter_counts.exact, before + 3);
}

// ---- a point's side of a facet's plane, in the world ------------------------------

// world::PlaneSide (one normal in doubles, a static bound, then the exact
// orientation) gives orientation()'s exact sign: on points nearly in the plane
// (made in doubles from the plane's own vectors, so off it by rounding only, or
// exactly in it on integer coordinates), far from the origin and at scales from
// 2^-200 to 2^200. With its bound taken away it fails here.
TEST(PlaneSide, SignAsTheExactOrientation) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::uniform_int_distribution<int> small(-8, 8), exponent(-200, 200);
  int zeros = 0, checked = 0;
  for (int n = 0; n < 100000; ++n) {
    const double scale = std::ldexp(1.0, exponent(rng)), offset = n % 2 ? 0 : 1e6 * scale;
    vismap::Vec3 o, a, b, p;
    if (n % 3 == 0) {   // integer coordinates: p exactly in the plane
      auto pt = [&](int x, int y, int z) { return vismap::Vec3{x * scale, y * scale, z * scale}; };
      const int ax = small(rng), ay = small(rng), az = small(rng), bx = small(rng), by = small(rng), bz = small(rng);
      const int s = small(rng), t = small(rng);
      o = pt(0, 0, 0);
      a = pt(ax, ay, az);
      b = pt(bx, by, bz);
      p = pt(s * ax + t * bx, s * ay + t * by, s * az + t * bz);
    } else {
      auto pt = [&] { return vismap::Vec3{offset + unit(rng) * scale, offset + unit(rng) * scale, unit(rng) * scale}; };
      o = pt();
      a = pt();
      b = pt();
      const double s = unit(rng), t = unit(rng);
      p = {o.x + s * (a.x - o.x) + t * (b.x - o.x), o.y + s * (a.y - o.y) + t * (b.y - o.y),
           o.z + s * (a.z - o.z) + t * (b.z - o.z)};
    }
    const int want = vismap::engine::world::det<CGAL::Mpzf>(o, a, b, p).sign();
    ASSERT_EQ(vismap::engine::world::PlaneSide(o, a, b)(p), want) << n;
    zeros += want == 0;
    ++checked;
  }
  EXPECT_GT(zeros, 10000);   // (the exact zeros are there)
}

// ---- vertex stars flat on the screen ----------------------------------------------

// A height field of random heights on a grid (jittered, or not: then an axis
// view has link vertices exactly level with their hub), with a double cover
// beside it: a vertex whose seven triangles (each turning the same way on the
// screen, each within pi at the vertex) go round it twice, so that they overlap
// and pierce each other on the screen.
vismap::Scene stars_scene(std::uint64_t seed, double relief, double jitter) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(-1, 1);
  vismap::Scene scene;
  const int n = 9;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      scene.vertices.push_back({x + jitter * unit(rng), y + jitter * unit(rng), relief * unit(rng)});
  auto at = [&](int x, int y) { return static_cast<std::uint32_t>(y * n + x); };
  for (int y = 0; y + 1 < n; ++y)
    for (int x = 0; x + 1 < n; ++x) {
      scene.faces.push_back({at(x, y), at(x + 1, y), at(x + 1, y + 1)});
      scene.faces.push_back({at(x, y), at(x + 1, y + 1), at(x, y + 1)});
    }
  const auto hub = static_cast<std::uint32_t>(scene.vertices.size());
  scene.vertices.push_back({n + 4.0, 4.0, 0.0});
  for (int k = 0; k < 7; ++k) {
    const double angle = 4 * M_PI * k / 7;
    scene.vertices.push_back({n + 4.0 + 3 * std::cos(angle), 4.0 + 3 * std::sin(angle), 2 * unit(rng)});
  }
  for (std::uint32_t k = 0; k < 7; ++k) scene.faces.push_back({hub, hub + 1 + k, hub + 1 + (k + 1) % 7});
  return scene;
}

// EmbeddedStars lets the pair searches skip facets that share one corner whose
// star it finds embedded on the screen. None of those pairs may cross: every
// such pair is tested here with intersection_segment, on rough and smooth
// height fields (folds on the screen, silhouettes) and the double cover, in
// oblique, axis and perspective views. Pairs around stars it does not find
// embedded do cross here (the double cover's), so skipping them would fail.
TEST(EmbeddedStars, NoPairSkippedCrosses) {
  std::int64_t skipped = 0, crossing_kept = 0, stars = 0, vertices = 0;
  const std::vector<vismap::Camera> cameras = {ortho({-1, -2, -3}), ortho({0, 0, -1}), ortho({0.3, -1, -0.2}),
                                                persp({4, -6, 5}, {5, 4, 0}, 50), persp({6, 3, 1.5}, {4, 4, 0}, 70)};
  for (std::uint64_t seed = 1; seed <= 6; ++seed)
    for (const double relief : {0.05, 0.5, 3.0})
      for (const vismap::Camera& camera : cameras) {
        const vismap::Scene scene = stars_scene(seed, relief, seed % 2 ? 0.3 : 0.0);
        const vismap::View view = vismap::make_view(camera, scene);
        vismap::Options opt;
        vismap::Stats stats;
        const auto ss = vismap::engine::make_screen_scene(scene, view, opt, stats);
        const vismap::engine::EmbeddedStars embedded(ss, 2);
        stars += embedded.count();
        vertices += static_cast<std::int64_t>(scene.vertices.size());
        for (std::size_t a = 0; a < ss.facets.size(); ++a)
          for (std::size_t b = a + 1; b < ss.facets.size(); ++b) {
            const auto &A = ss.facets[a], &B = ss.facets[b];
            auto shared = [&](long v) { return B.has_vertex(v); };
            if (!A.occluder || !B.occluder || std::count_if(A.id.begin(), A.id.end(), shared) != 1) continue;
            vismap::engine::P2 p, q;
            const bool cross = vismap::engine::intersection_segment(A, B, ss.world, p, q);
            if (vismap::engine::neighbours_apart(A, B, embedded)) {
              ++skipped;
              EXPECT_FALSE(cross) << "seed " << seed << " relief " << relief << " facets " << a << ", " << b;
            } else {
              crossing_kept += cross;
            }
          }
      }
  EXPECT_GT(skipped, 10000);
  EXPECT_GT(crossing_kept, 20);
  EXPECT_LT(stars, vertices * 3 / 4);   // (folds and silhouettes leave many stars untold)
}

// ---- crossings of covered lines apart in depth are not cut -----------------------

// A torus of nu x nv quads (each two triangles), outward, round the z axis.
vismap::Scene torus(int nu, int nv, double major, double minor) {
  vismap::Scene scene;
  scene.file = "torus";
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = 2 * M_PI * i / nu, v = 2 * M_PI * j / nv, rho = major + minor * std::cos(v);
      scene.vertices.push_back({rho * std::cos(u), rho * std::sin(u), minor * std::sin(v)});
    }
  auto id = [&](int i, int j) { return static_cast<std::uint32_t>((i % nu) * nv + j % nv); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      scene.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      scene.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return scene;
}

// A torus seen along its axis with the near plane through its tube: the plane
// cuts the tube in a ring whose two circles' images surround every face seen
// through the hole, so their boxes cull nothing. From the eye in the hole, the
// faces seen from behind whose images lie in the ring's hole (not within a cap:
// each ray towards them starts outside the solid) are culled all the same,
// exactly. From above the torus (the target far off, the near plane a thousandth
// of the way: through the tube), the tube's floor is seen from inside, through
// the cap: not culled (culling it fails the checker). Newell's engine writes
// the same maps, and the checker accepts them.
TEST(Culling, FacesSeenFromBehindOutsideTheNearPlanesCapsAreCulled) {
  const vismap::Scene t = torus(32, 16, 1.0, 0.3);
  const struct {
    const char* what;
    vismap::Camera camera;
    bool culls;
  } shots[] = {{"torus from its hole", persp({0, 0, 0}, {0, 0, -1}, 90), true},
               {"torus from above, through its tube", persp({0, 0, 0.9}, {0, 0, -1000}, 90), false}};
  for (const auto& shot : shots) {
    const vismap::View view = vismap::make_view(shot.camera, t);
    vismap::Options opt;
    opt.threads = 1;
    const vismap::VisibilityMap m = vismap::visibility_franklin(t, view, opt);
    EXPECT_GT(m.stats.counted("near_plane_caps"), 0) << shot.what;
    if (shot.culls) {
      EXPECT_GT(m.stats.counted("culled_back_faces"), 0) << shot.what;
    }
    const std::string json = map_json(t, view, opt);
    vismap::VisibilityMap n = vismap::visibility_newell(t, view, opt);
    n.stats = {};
    EXPECT_EQ(vismap::to_json(n), json) << shot.what << ": Newell's map differs";
    vismap_check::Options check;
    check.samples = 800;
    expect_checked(t, json, check, shot.what);
  }
}

// A scene seen from one camera, named.
struct Shot {
  std::string what;
  vismap::Scene scene;
  vismap::Camera camera;
};

// Franklin's map of the shot (one thread) is Newell's, byte for byte, and the
// checker's; its lines alone (no regions) are the same segments. Returns the
// two runs' counts (whole map, lines only).
std::pair<vismap::Stats, vismap::Stats> expect_as_newell_and_checker(Shot& shot) {
  shot.scene.file = shot.what;
  const vismap::View view = vismap::make_view(shot.camera, shot.scene);
  vismap::Options opt;
  opt.threads = 1;
  vismap::VisibilityMap m = vismap::visibility_franklin(shot.scene, view, opt);
  const vismap::Stats whole = m.stats;
  m.stats = {};
  const std::string json = vismap::to_json(m);
  vismap::VisibilityMap n = vismap::visibility_newell(shot.scene, view, opt);
  n.stats = {};
  EXPECT_EQ(vismap::to_json(n), json) << shot.what << ": Newell's map differs";
  vismap_check::Options check;
  check.samples = 600;
  expect_checked(shot.scene, json, check, shot.what);
  vismap::Options lines = opt;
  lines.regions = false;
  vismap::VisibilityMap l = vismap::visibility_franklin(shot.scene, view, lines);
  const vismap::Stats drawn = l.stats;
  l.stats = {};
  EXPECT_EQ(segments_of(vismap::to_json(l)), segments_of(json)) << shot.what << ": the lines alone differ from the whole map's";
  return {whole, drawn};
}

// Boxes on a lattice seen from a direction in one of its planes: the edges of a
// column of boxes on common screen lines, and pieces' midpoints on the lines of
// other boxes' edges, where the images' x are doubles. Those zeros are the
// intervals' (on 20^3 such boxes the exact stage had 19.6 M of 153 M
// predicates before): few predicates reach the exact stage, and the map is
// Newell's and the checker's.
TEST(FilteredSign, ALatticeSeenAlongItsRowsNeedsFewExactPredicates) {
  Shot shot{"lattice of boxes seen along its rows", {}, ortho({-0.86602540378443871, 0, -0.49999999999999994})};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4; ++k)
        vismap::gen::add_box(shot.scene, {double(i), double(j), double(k)},
                             {i + 0.3 + 0.0625 * ((i + j + k) % 4), j + 0.5, k + 0.375 + 0.0625 * ((i * k) % 3)});
  const vismap::Stats whole = expect_as_newell_and_checker(shot).first;
  const std::int64_t predicates = whole.counted("predicates"), exact = whole.counted("predicates_exact");
  EXPECT_GT(predicates, 10000);
  EXPECT_LT(exact, predicates / 200) << exact << " of " << predicates << " predicates exact";
}

// The same lattice, corners on a grid of halves, seen along its diagonal (an
// isometric view, whose rows are rounded): images on each other's lines by
// the hundred, and near them everywhere, so that most pieces' sides and
// depths are told from their curves' ends (midpoint_probe.cpp) and the
// world's exact signs (ExactSource::axis_cross, whose sight has two equal
// coordinates here). Newell's engine writes the same map; the checker accepts it.
TEST(FilteredSign, ALatticeSeenAlongItsDiagonalAsNewellAndTheChecker) {
  for (const Vec3& dir : std::vector<Vec3>{{-1, -1, -1}, {1, -1, -1}, {-2, -2, -1}}) {
    Shot shot{"lattice of boxes seen along its diagonal", {}, ortho(dir)};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k)
          vismap::gen::add_box(shot.scene, {double(i), double(j), double(k)},
                               {i + 0.5 + 0.5 * ((i + k) % 2), j + 0.5, k + 0.5 + 0.5 * ((j * k) % 2)});
    const vismap::Stats whole = expect_as_newell_and_checker(shot).first;
    EXPECT_GT(whole.counted("visible_segments"), 100) << dir.x << "," << dir.y << "," << dir.z;
  }
}

// Where two lines each with a hiding facet on both sides (Curve::covered) cross
// on screen, one wholly nearer than the other and no face shared, the engine
// cuts neither (cut_curves: stat crossings_left_uncut). The map must not
// change: Newell's engine, which cuts every crossing, writes the same, and the
// checker accepts it. The cases where skipping would be wrong are here: hills
// hiding valleys (the skipped crossings), a line whose piece has its midpoint
// right under a nearer line (judged elsewhere on the piece), a fan that folds
// over its own edge behind another face (a face hides no edge of its own), a
// sphere right behind another on screen (a line right behind a covered one is
// visible: an overlap, never skipped), boxes that pierce each other.
TEST(CoveredCrossings, LeftUncutWithoutChangingTheMap) {
  std::vector<Shot> shots;
  const vismap::Scene h = hills(16);
  shots.push_back({"hills, perspective", h, persp({1.8, -1.2, 0.9}, {0.5, 0.5, 0}, 35)});
  shots.push_back({"hills, grazing", h, ortho({-1, -0.3, -0.18})});
  shots.push_back({"hills, close-up", h, persp({0.45, 0.2, 0.3}, {0.5, 0.6, 0}, 70)});
  vismap::Scene spheres = vismap::gen::sphere(10, 7, 1.0, {0, 0, 0});
  const vismap::Scene back = vismap::gen::sphere(10, 7, 1.0, {0, 0, -4});   // (the same x, y: the same screen)
  const auto first = static_cast<std::uint32_t>(spheres.vertices.size());
  spheres.vertices.insert(spheres.vertices.end(), back.vertices.begin(), back.vertices.end());
  for (auto f : back.faces) {
    for (auto& v : f) v += first;
    spheres.faces.push_back(f);
  }
  shots.push_back({"sphere behind a sphere, along z", spheres, ortho({0, 0, -1})});
  shots.push_back({"sphere behind a sphere, obliquely", spheres, ortho({-0.1, -0.2, -3})});
  // Two rectangles of two triangles, one right above the other, split along
  // the two diagonals: the lower diagonal's midpoint lies on the upper one.
  vismap::Scene stacked;
  stacked.vertices = {{0, 0, 1}, {2, 0, 1}, {2, 1, 1}, {0, 1, 1}, {0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}};
  stacked.faces = {{0, 1, 2}, {0, 2, 3}, {4, 5, 7}, {5, 6, 7}};
  shots.push_back({"a diagonal right under another's midpoint", stacked, ortho({0, 0, -1})});
  shots.push_back({"folded fans", vismap::read_scene((fs::path(VISMAP_DATA_DIR) / "stress_fold_818.off").string()),
                   ortho({-0.25, -0.5, -1})});
  shots.push_back({"piercing boxes", vismap::gen::interpenetrating_boxes(6, 3), ortho({-1, -2, -3})});
  std::int64_t uncut = 0, uncut_lines = 0;
  for (Shot& shot : shots) {
    const auto [whole, lines] = expect_as_newell_and_checker(shot);
    uncut += whole.counted("crossings_left_uncut");
    // A lines-only drawing leaves the same crossings uncut (and makes no curve
    // needed for them).
    uncut_lines += lines.counted("crossings_left_uncut");
  }
  EXPECT_GT(uncut, 1000) << "no crossing was left uncut";
  EXPECT_GT(uncut_lines, 100) << "no crossing was left uncut in a lines-only drawing";
}

// A flat grid of n x n cells of two triangles over [x0, x1] x [y0, y1] at height
// z, added to the scene (counter-clockwise seen from above).
void add_flat_grid(vismap::Scene& scene, double x0, double x1, double y0, double y1, double z, int n) {
  const auto first = static_cast<std::uint32_t>(scene.vertices.size());
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      scene.vertices.push_back({x0 + (x1 - x0) * i / n, y0 + (y1 - y0) * j / n, z});
  auto id = [&](int i, int j) { return first + static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      scene.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      scene.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
}

// Edges inside a plane seen edge-on, behind a facet of it that no facet of
// theirs hides or labels (orthographic: the facet on the eye's side; in
// perspective: two facets on either side), are not made into curves (stat
// edges_inside_edge_on_planes): nearer along each line of sight in the plane
// lies another piece of it, kept, that is visible wherever they are. The map
// must not change: the checker accepts it, Newell's engine writes it, the
// lines alone are its segments. The cases where dropping would be wrong are
// here: a plate's near border (the plate beyond it), a fin folded onto itself
// (its fold is the nearest piece there, a smooth seam over the fin's own
// borders: nothing is drawn), a plane through the eye that the near plane cuts
// (the nearest pieces are those of the facets it cuts), smooth edges drawn;
// and boxes seen along an axis (their far edges dropped).
TEST(EdgeOnPlanes, PiecesInsideAPlaneSeenEdgeOnAreDroppedWithoutChangingTheMap) {
  vismap::Scene plates;
  add_flat_grid(plates, 0, 1, 0, 1, 0, 6);
  add_flat_grid(plates, 0.5, 1.5, 2, 3, 0, 5);   // (behind the first, seen along y)
  vismap::gen::add_box(plates, {0.2, -0.5, -0.2}, {0.4, -0.3, 0.2});   // (before both, across their line)
  vismap::Scene fins;
  fins.vertices = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, 0.8, 0},     // a fin folded over its edge
                   {2, 0, 0}, {3, 0, 0}, {2.5, 1, 0}, {2.5, -1, 0}};   // a flat pair
  fins.faces = {{0, 1, 2}, {1, 0, 3}, {4, 5, 6}, {5, 4, 7}};
  vismap::Scene through_eye;
  add_flat_grid(through_eye, -1, 3, 0, 1, 0, 8);
  add_flat_grid(through_eye, -1, 3, 0, 1, 0.25, 3);   // (seen from below, not edge-on)
  vismap::Scene boxes;
  for (int i = 0; i < 2; ++i)
    for (int k = 0; k < 3; ++k)
      vismap::gen::add_box(boxes, {double(i), 0.25 * i, double(k)}, {i + 0.75, 1 + 0.25 * k, k + 0.5 + 0.25 * i});
  std::vector<Shot> shots;
  shots.push_back({"plates seen edge-on along y", plates, ortho({0, 1, 0})});
  shots.push_back({"plates seen edge-on obliquely", plates, ortho({0.3, 1, 0})});
  shots.push_back({"plates seen edge-on in perspective", plates, persp({0.5, -3, 0}, {0.7, 1, 0}, 40)});
  shots.push_back({"a folded fin and a flat pair seen edge-on", fins, ortho({0, 1, 0})});
  shots.push_back({"a plate through the eye", through_eye, persp({1, 0.5, 0}, {2, 0.5, 0}, 60)});
  shots.push_back({"boxes seen from above", boxes, ortho({0, 0, -1})});
  shots.push_back({"boxes seen from the front", boxes, ortho({0, 1, 0})});
  shots.push_back({"boxes seen along x at 30 degrees", boxes, ortho({-0.866, 0, -0.5})});
  std::int64_t dropped = 0;
  for (Shot& shot : shots) dropped += expect_as_newell_and_checker(shot).first.counted("edges_inside_edge_on_planes");
  EXPECT_GT(dropped, 150) << "no piece inside a plane seen edge-on was dropped";
  // Where smooth edges are drawn, those inside the planes are dropped too: they
  // are never the first line there either.
  for (const Shot& shot : shots) {
    vismap::Options opt;
    opt.threads = 1;
    opt.smooth = true;
    const vismap::VisibilityMap m = vismap::visibility_franklin(shot.scene, vismap::make_view(shot.camera, shot.scene), opt);
    vismap_check::Options check;
    check.smooth = true;
    check.samples = 600;
    expect_checked(shot.scene, vismap::to_json(m), check, shot.what + ", smooth edges drawn");
  }
}

// A curve whose part in a cell lies strictly inside a nearer facet listed
// there is hidden throughout the cell: its crossings there are not cut. The
// map must be the one Newell's engine writes (no grid, every crossing cut),
// and the checker's; the lines alone the same segments.
TEST(HiddenInCell, CrossingsOfCurvesHiddenInACellAreNotCutWithoutChangingTheMap) {
  std::vector<Shot> shots;
  const vismap::Scene squares = vismap::gen::random_squares_depth(300, 5, 11);
  shots.push_back({"squares, obliquely", squares, ortho({-0.3, -0.5, -1})});
  shots.push_back({"squares, along z", squares, ortho({0, 0, -1})});
  shots.push_back({"squares, perspective close-up", squares, persp({0.3, 0.4, 1.6}, {0.5, 0.5, 0.4}, 60)});
  shots.push_back({"piercing boxes", vismap::gen::interpenetrating_boxes(6, 5), ortho({-1, -2, -3})});
  shots.push_back({"hills, perspective", hills(16), persp({1.8, -1.2, 0.9}, {0.5, 0.5, 0}, 35)});
  std::int64_t behind = 0;
  for (Shot& shot : shots) behind += expect_as_newell_and_checker(shot).first.counted("curve_cells_behind_facet");
  EXPECT_GT(behind, 500) << "no curve was found hidden in a cell";
}

// ---- crease angles at the threshold ------------------------------------------------

// Whether the edge o-p shared by triangles (o, p, q) and (p, o, r) is a crease at
// cosine c >= 0, from the spec's words on the exact input: the angle between the
// faces' normals exceeds the crease angle, n1.n2 < c |n1| |n2|, squared on rationals.
bool crease_exactly(const Vec3& o, const Vec3& p, const Vec3& q, const Vec3& r, double c) {
  using Q = mpq_class;
  auto normal = [](const Vec3& a, const Vec3& b, const Vec3& e) {
    const Q ux = Q(b.x) - Q(a.x), uy = Q(b.y) - Q(a.y), uz = Q(b.z) - Q(a.z);
    const Q vx = Q(e.x) - Q(a.x), vy = Q(e.y) - Q(a.y), vz = Q(e.z) - Q(a.z);
    return std::array<Q, 3>{uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx};
  };
  const auto n1 = normal(o, p, q), n2 = normal(p, o, r);
  const Q d = n1[0] * n2[0] + n1[1] * n2[1] + n1[2] * n2[2];
  const Q l = (n1[0] * n1[0] + n1[1] * n1[1] + n1[2] * n1[2]) * (n2[0] * n2[0] + n2[1] * n2[1] + n2[2] * n2[2]);
  return d < 0 || d * d < Q(c) * Q(c) * l;
}

// Two triangles hinged on a shared edge at about the crease angle, the far
// corner nudged by up to 300 ulps (on coordinates far from 1, and offset from 0
// where the edge vectors are rounded): some of these angles lie within rounding
// of the threshold: on doubles alone, d^2 - c^2 l comes out 0 for about 3 % of
// them, whose exact sign the engine must still find (with its error bounds
// taken away, 54 of these cases fail). The edge is drawn as a crease exactly
// when the exact test says so.
TEST(Crease, KindAtTheThresholdAsTheExactTest) {
  int creases = 0, smooth = 0;
  for (const double deg : {5.0, 30.0, 60.0})
    for (const double scale : {1.0, 0x1p40, 0x1p-40})
      for (const double offset : {0.0, 0.3, 1e6}) {
        const double theta = deg * M_PI / 180;
        double z = std::sin(theta);
        for (int k = 0; k < 300; ++k) z = std::nextafter(z, -1.0);
        for (int k = -300; k <= 300; k += 3) {
          auto at = [&](double x, double y, double h) {
            return Vec3{(x + offset) * scale, (y + offset) * scale, h * scale};
          };
          vismap::Scene scene;
          scene.vertices = {at(0, 0, 0), at(1, 0, 0), at(0.5, 1, 0), at(0.5, -std::cos(theta), z)};
          scene.faces = {{0, 1, 2}, {1, 0, 3}};
          vismap::Options opt;
          opt.crease_deg = deg;
          const vismap::View view = vismap::make_view(ortho({0.1, 0.2, -1}), scene);
          const vismap::VisibilityMap map = vismap::visibility_franklin(scene, view, opt);
          const bool drawn = std::any_of(map.segments.begin(), map.segments.end(),
                                         [](const vismap::Segment& g) { return g.kind == vismap::EdgeKind::Crease; });
          const bool want = crease_exactly(scene.vertices[0], scene.vertices[1], scene.vertices[2], scene.vertices[3],
                                           std::cos(deg * M_PI / 180));
          EXPECT_EQ(drawn, want) << deg << " degrees, scale " << scale << ", offset " << offset << ", nudge " << k;
          (want ? creases : smooth) += 1;
          for (int i = 0; i < 3; ++i) z = std::nextafter(z, 1.0);
        }
      }
  // (Both answers occur: the cases straddle the threshold.)
  EXPECT_GT(creases, 100);
  EXPECT_GT(smooth, 100);
}

// world::unit_normal's estimate lies within its error bound of the exact unit
// normal (|f - N / |N||^2 <= err^2, decided exactly: 2 f.N >= (|f|^2 + 1 -
// err^2) |N|), and crease_from_normals, where it answers, answers as the exact
// test (n1.n2 < c |n1||n2|) for c anywhere in [-1, 1], about the pair's own
// cosine, and within 3e-7 of it (inside the floats' uncertainty). With either
// bound cut to the floats' rounding alone, this fails. Triangles at scales from
// 2^-250 (products near underflow: no estimate) to 2^190, off the origin, some
// of them thin.
TEST(Crease, NormalEstimatesDecideAsTheExactTest) {
  using M = CGAL::Mpzf;
  namespace world = vismap::engine::world;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::uniform_int_distribution<int> exponent(-250, 190);
  auto exact_crease = [](const std::array<M, 3>& n1, const std::array<M, 3>& n2, double c) {
    const M d = n1[0] * n2[0] + n1[1] * n2[1] + n1[2] * n2[2];
    const M l = (n1[0] * n1[0] + n1[1] * n1[1] + n1[2] * n1[2]) * (n2[0] * n2[0] + n2[1] * n2[1] + n2[2] * n2[2]);
    const int e = (d * d - M(c) * M(c) * l).sign();
    return c >= 0 ? d.sign() < 0 || e < 0 : d.sign() < 0 && e > 0;
  };
  auto within_bound = [](const world::UnitNormal& f, const std::array<M, 3>& N) {
    if (!std::isfinite(f.err)) return true;   // (no estimate: nothing claimed)
    const M fx(static_cast<double>(f.n[0])), fy(static_cast<double>(f.n[1])), fz(static_cast<double>(f.n[2]));
    const M dot = fx * N[0] + fy * N[1] + fz * N[2], e(static_cast<double>(f.err));
    const M rhs = fx * fx + fy * fy + fz * fz + M(1.0) - e * e;
    if (rhs.sign() <= 0) return true;
    return dot.sign() > 0 && (M(4.0) * dot * dot - rhs * rhs * (N[0] * N[0] + N[1] * N[1] + N[2] * N[2])).sign() >= 0;
  };
  int settled = 0, unsettled_near = 0, asked = 0;
  for (int n = 0; n < 60000; ++n) {
    const double scale = std::ldexp(1.0, exponent(rng)), offset = n % 2 ? 0 : 1e6 * scale;
    auto pt = [&] { return Vec3{offset + unit(rng) * scale, unit(rng) * scale, offset + unit(rng) * scale}; };
    std::array<Vec3, 6> v{pt(), pt(), pt(), pt(), pt(), pt()};
    if (n % 5 == 0) v[2] = {v[0].x + 0.5 * (v[1].x - v[0].x), v[0].y + 0.5 * (v[1].y - v[0].y) + 1e-9 * scale, v[0].z};   // thin
    const world::UnitNormal f = world::unit_normal(v[0], v[1], v[2]), g = world::unit_normal(v[3], v[4], v[5]);
    const auto N1 = world::normal_of<M>(v[0], v[1], v[2]), N2 = world::normal_of<M>(v[3], v[4], v[5]);
    ASSERT_TRUE(within_bound(f, N1)) << n;
    ASSERT_TRUE(within_bound(g, N2)) << n;
    const double cos_here = static_cast<double>(f.n[0]) * g.n[0] + static_cast<double>(f.n[1]) * g.n[1] +
                            static_cast<double>(f.n[2]) * g.n[2];
    const double c = std::clamp(n % 3 == 0 ? unit(rng) : cos_here + (n % 3 == 1 ? 3e-7 * unit(rng) : 0.0), -1.0, 1.0);
    const std::optional<bool> told = world::crease_from_normals(f, g, c);
    ++asked;
    if (told) {
      ASSERT_EQ(*told, exact_crease(N1, N2, c)) << n;
      ++settled;
    } else if (n % 3 != 0) {
      ++unsettled_near;
    }
  }
  EXPECT_GT(settled, asked / 3);        // (random thresholds: nearly all settled)
  EXPECT_GT(unsettled_near, asked / 4);   // (the near ones: left to the exact test)
}

// Two faces at a right angle (the edges of every box): n1.n2 is exactly 0, which
// no filter settles. The angle between the normals is 90 degrees, so the edge is
// a crease under every crease angle below 90 and smooth above it (where the
// cosine is negative: n1.n2 < c |n1| |n2| is false for n1.n2 = 0).
TEST(Crease, RightAngleOnEitherSideOfNinetyDegrees) {
  for (const double deg : {1.0, 30.0, 89.0, 91.0, 120.0, 179.0})
    for (const double scale : {1.0, 0x1p40, 0x1p-40})
      for (const double offset : {0.0, 0.3, 1e6}) {
        auto at = [&](double x, double y, double h) { return Vec3{(x + offset) * scale, (y + offset) * scale, h * scale}; };
        vismap::Scene scene;
        scene.vertices = {at(0, 0, 0), at(1, 0, 0), at(0.5, 1, 0), at(0.5, 0, 1)};
        scene.faces = {{0, 1, 2}, {1, 0, 3}};   // normals +z and +y: both seen from the front
        vismap::Options opt;
        opt.crease_deg = deg;
        const vismap::View view = vismap::make_view(ortho({0.3, -1, -1}), scene);
        const vismap::VisibilityMap map = vismap::visibility_franklin(scene, view, opt);
        const bool drawn = std::any_of(map.segments.begin(), map.segments.end(),
                                       [](const vismap::Segment& g) { return g.kind == vismap::EdgeKind::Crease; });
        EXPECT_EQ(drawn, deg < 90) << deg << " degrees, scale " << scale << ", offset " << offset;
      }
}

// ---- threads change nothing -------------------------------------------------------------

// Franklin's engine runs its loops on several threads and joins their results in
// the serial order: the map, regions and segments and every counter but the
// timings, is the same byte for byte for every thread count. The scenes are big
// enough for every parallel loop to have many more chunks than threads.
TEST(Threads, SameMapForEveryThreadCount) {
  vismap::Scene squares = vismap::gen::random_squares_depth(3000, 5, 7);
  vismap::gen::append_scene(squares, vismap::gen::interpenetrating_boxes(8, 7));
  const vismap::Scene terrain = vismap::gen::terrain(40, 3);
  struct View {
    const vismap::Scene* scene;
    vismap::Camera camera;
  };
  const std::vector<View> views = {{&squares, ortho({-0.2, -0.3, -1})},
                                   {&squares, persp({0.2, 0.3, 2.5}, {0.5, 0.5, 0.5}, 50)},
                                   {&terrain, ortho({-1, -0.5, -0.7})}};
  auto json_of = [](const vismap::Scene& scene, const vismap::View& view, vismap::Options opt) {
    vismap::VisibilityMap map = vismap::visibility_franklin(scene, view, opt);
    map.stats.seconds.clear();
    return vismap::to_json(map);
  };
  for (std::size_t v = 0; v < views.size(); ++v) {
    const vismap::View view = vismap::make_view(views[v].camera, *views[v].scene);
    for (bool regions : {true, false}) {
      vismap::Options opt;
      opt.regions = regions;
      opt.hidden = !regions;   // (the hidden lines' pass has threads of its own)
      opt.threads = 1;
      const std::string reference = json_of(*views[v].scene, view, opt);
      ASSERT_NE(reference.find("\"segments\""), std::string::npos);
      for (int threads : {2, 3, 8}) {
        opt.threads = threads;
        EXPECT_EQ(json_of(*views[v].scene, view, opt), reference)
            << "view " << v << (regions ? "" : ", lines only") << ": " << threads << " threads differ from one";
      }
    }
  }
}

// ---- the screen order: the map does not depend on it ------------------------------------

// A map with its faces named anew (name[face]) and its regions and segments
// sorted, as JSON without counters: two scenes that list the same faces in
// other orders then give the same text.
std::string json_named(vismap::VisibilityMap map, const std::vector<std::uint32_t>& name) {
  for (vismap::Region& r : map.regions) r.face = static_cast<int>(name[static_cast<std::size_t>(r.face)]);
  for (vismap::Segment& g : map.segments) {
    for (int& f : g.faces) f = static_cast<int>(name[static_cast<std::size_t>(f)]);
    std::sort(g.faces.begin(), g.faces.end());
  }
  std::sort(map.regions.begin(), map.regions.end(), [](const vismap::Region& a, const vismap::Region& b) {
    return std::tie(a.outer, a.holes, a.face) < std::tie(b.outer, b.holes, b.face);
  });
  std::sort(map.segments.begin(), map.segments.end(), [](const vismap::Segment& a, const vismap::Segment& b) {
    return std::tie(a.from, a.to, a.kind, a.faces) < std::tie(b.from, b.to, b.kind, b.faces);
  });
  map.stats = {};
  return vismap::to_json(map);
}

// Facets in a terrain's grid rows walk the screen, seen obliquely or from close
// by in perspective: a lines-only map keeps their order, where the same facets
// shuffled are sorted along a Morton curve (and a smaller terrain's always are). The two orders give one map: the shuffled
// scene's, its faces named back, is the rows' (the segments of a lines-only
// map; and a whole map's regions and segments, the rows sorted too).
TEST(ScreenOrder, FacetsThatWalkTheScreenKeepTheirOrderAndGiveTheSameMap) {
  const vismap::Scene rows = vismap::gen::terrain(182, 3);   // (2 x 182^2 triangles: over 2^16)
  ASSERT_GE(rows.faces.size(), std::size_t{1} << 16);
  std::vector<std::uint32_t> old_of(rows.faces.size()), same(rows.faces.size());
  std::iota(old_of.begin(), old_of.end(), 0u);
  std::iota(same.begin(), same.end(), 0u);
  std::shuffle(old_of.begin(), old_of.end(), std::mt19937(7));
  vismap::Scene shuffled = rows;
  for (std::size_t k = 0; k < old_of.size(); ++k) shuffled.faces[k] = rows.faces[old_of[k]];
  const vismap::View view = vismap::make_view(ortho({-1, -2, -3}), rows);
  EXPECT_TRUE(vismap::engine::walk_the_screen(vismap::engine::make_world_facets(rows), rows, view));
  EXPECT_FALSE(vismap::engine::walk_the_screen(vismap::engine::make_world_facets(shuffled), shuffled, view));
  // A close-up in perspective throws the facets near the eye's plane far over
  // the screen: the rows still walk it, the shuffled facets still do not.
  const vismap::View close = vismap::make_view(persp({0.5, 0.3, 0.25}, {0.5, 0.7, 0}, 60), rows);
  EXPECT_TRUE(vismap::engine::walk_the_screen(vismap::engine::make_world_facets(rows), rows, close));
  EXPECT_FALSE(vismap::engine::walk_the_screen(vismap::engine::make_world_facets(shuffled), shuffled, close));
  const vismap::Scene small = vismap::gen::terrain(100, 3);
  EXPECT_FALSE(vismap::engine::walk_the_screen(vismap::engine::make_world_facets(small), small,
                                               vismap::make_view(ortho({-1, -2, -3}), small)));
  for (const bool regions : {true, false}) {
    vismap::Options opt;
    opt.regions = regions;
    opt.crease_deg = 10;
    const std::string want = json_named(vismap::visibility_franklin(rows, view, opt), same);
    ASSERT_NE(want.find("\"segments\""), std::string::npos);
    EXPECT_EQ(json_named(vismap::visibility_franklin(shuffled, view, opt), old_of), want)
        << (regions ? "full map" : "lines only");
  }
}

// Sets joined from four threads at once: each element's root is the least member
// of its set (the components' numbers and lowest vertices rely on it), the sets
// those of the same joins made one by one.
TEST(Threads, ConcurrentUnionFindRootsAreTheLeastMembers) {
  constexpr int kN = 20000, kJoins = 15000, kThreads = 4;
  std::mt19937 rng(1129);
  std::vector<std::pair<int, int>> joins(kJoins);
  for (auto& [a, b] : joins) {
    a = static_cast<int>(rng() % kN);
    b = static_cast<int>(rng() % kN);
  }
  vismap::UnionFind one(kN);
  for (const auto& [a, b] : joins) one.join(a, b);
  std::vector<int> least(kN, kN);
  for (int x = 0; x < kN; ++x) {
    int& l = least[static_cast<std::size_t>(one.find(x))];
    l = std::min(l, x);
  }
  for (int round = 0; round < 5; ++round) {
    vismap::ConcurrentUnionFind many(kN);
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t)
      threads.emplace_back([&, t] {
        for (int i = t; i < kJoins; i += kThreads) {
          const auto& [a, b] = joins[static_cast<std::size_t>(i)];
          many.join(a, b);
        }
      });
    for (std::thread& t : threads) t.join();
    int wrong = 0;
    for (int x = 0; x < kN; ++x) wrong += many.find(x) != least[static_cast<std::size_t>(one.find(x))];
    EXPECT_EQ(wrong, 0) << "round " << round;
  }
}

// Where two segments cross, exactly (crossing_point's exact value), over any
// denominators: powers of two (an orthographic view's images), odd ones that
// differ from point to point and between x and y (a perspective view's, N / W
// normalised), and with segments parallel to an axis, whose shared coordinate
// the crossing keeps (one of them, or both: a vertical crossing a horizontal).
// Against the textbook formula on rationals.
TEST(Crossings, ExactValuesAreTheLinesCrossingOverAnyDenominators) {
  using vismap::exact::FT;
  using vismap::exact::P2;
  std::mt19937_64 rng(17);
  std::uniform_int_distribution<int> num(-4000, 4000), den(1, 999), bit(0, 20), wide(0, 160);
  std::uniform_int_distribution<std::int64_t> mantissa(-(std::int64_t{1} << 53), std::int64_t{1} << 53);
  int checked = 0, kept = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    // 0: odd and other denominators, 1: powers of two, 2: a segment parallel to
    // an axis, 3: a horizontal one and a vertical one, 4: projected doubles'
    // values (a sum of two products of doubles over a power of two: numbers of
    // several limbs)
    const int kind = trial % 5;
    auto coordinate = [&] {
      if (kind == 4) {
        mpz_class n = mpz_class(static_cast<double>(mantissa(rng))) * mpz_class(static_cast<double>(mantissa(rng))) +
                      mpz_class(static_cast<double>(mantissa(rng)));
        mpq_class q(n);
        mpz_mul_2exp(q.get_den_mpz_t(), q.get_den_mpz_t(), static_cast<mp_bitcnt_t>(wide(rng)));
        q.canonicalize();
        return q;
      }
      mpq_class q(num(rng), kind == 1 ? 1 << bit(rng) : den(rng));
      q.canonicalize();
      return q;
    };
    std::array<mpq_class, 8> v;
    for (mpq_class& q : v) q = coordinate();
    if (kind == 2) v[trial % 8 < 4 ? 6 : 7] = v[trial % 8 < 4 ? 4 : 5];   // (c, d share x or y)
    if (kind == 3) v[3] = v[1], v[6] = v[4];
    const mpq_class ux = v[2] - v[0], uy = v[3] - v[1], vx = v[6] - v[4], vy = v[7] - v[5];
    const mpq_class cross = ux * vy - uy * vx;
    if (cross == 0) continue;
    const mpq_class lambda = ((v[4] - v[0]) * vy - (v[5] - v[1]) * vx) / cross;
    const mpq_class want_x = v[0] + lambda * ux, want_y = v[1] + lambda * uy;
    auto point = [&](int i) { return P2(FT(v[static_cast<std::size_t>(i)]), FT(v[static_cast<std::size_t>(i) + 1])); };
    const P2 got = vismap::engine::crossing_point(point(0), point(2), point(4), point(6));
    ASSERT_EQ(vismap::exact::exact_x(got), want_x) << "trial " << trial;
    ASSERT_EQ(vismap::exact::exact_y(got), want_y) << "trial " << trial;
    ++checked;
    kept += kind == 2 || kind == 3;
  }
  EXPECT_GT(checked, 3900);
  EXPECT_GT(kept, 1500);
}

// The points the threads share keep the interval they were made with once their
// exact value is made (steady_point, crossing_point): a CGAL construction's
// narrows then, and which thread made it first would decide which later filters
// succeed, and so the predicate counts in the JSON (seen on a 10^6-triangle
// terrain in perspective on two threads: a few exact predicates more or less
// from run to run, which the scenes above are too small to show).
TEST(Threads, SharedPointsKeepTheirIntervalsOnceExact) {
  using vismap::exact::FT;
  using vismap::exact::P2;
  using vismap::exact::P3;
  // Sums of quotients, as a perspective image's coordinates: intervals a few
  // ulps wide, wider than their exact values' own (checked: the test can fail).
  auto x = [] { return FT(1) / FT(3) + FT(1) / FT(7); };
  auto y = [] { return FT(2) / FT(3) - FT(1) / FT(11); };
  auto wider = [](const vismap::exact::Interval& was, const mpq_class& exact) {
    const std::pair<double, double> tight = CGAL::to_interval(exact);
    return was.inf() < tight.first || was.sup() > tight.second;
  };
  auto unchanged = [](const vismap::exact::K::Approximate_kernel::Point_2& a, const vismap::exact::K::Approximate_kernel::Point_2& b) {
    return a.x().inf() == b.x().inf() && a.x().sup() == b.x().sup() && a.y().inf() == b.y().inf() &&
           a.y().sup() == b.y().sup();
  };
  const P3 image(x(), y(), FT(1) / FT(5));
  const auto image_was = image.xy().approx();
  ASSERT_TRUE(wider(image_was.x(), vismap::exact::to_mpq(x())));
  const mpq_class image_x = vismap::exact::exact_x(image.xy());
  EXPECT_EQ(image_x, mpq_class(10, 21));
  EXPECT_TRUE(unchanged(image.xy().approx(), image_was));

  const P2 a(x(), y()), b(FT(3), FT(1) / FT(3)), c(FT(1) / FT(9), FT(1)), d(FT(2), FT(-1) / FT(7));
  const P2 cross = vismap::engine::crossing_point(a, b, c, d);
  const auto cross_was = cross.approx();
  const P2 again = vismap::engine::crossing_point(P2(x(), y()), b, c, d);   // (its own DAG)
  ASSERT_TRUE(wider(cross_was.x(), vismap::exact::exact_x(again)) || wider(cross_was.y(), vismap::exact::exact_y(again)));
  EXPECT_EQ(vismap::exact::exact_x(cross), vismap::exact::exact_x(again));
  EXPECT_TRUE(unchanged(cross.approx(), cross_was));

  // The other points cut into curves: where a curve crosses a facet's depth
  // plane, and where two collinear curves' depths cross.
  using vismap::engine::Curve;
  const P3 s(x(), y(), FT(1) / FT(3)), t(FT(5) / FT(3), FT(7) / FT(9), FT(-2) / FT(3));
  Curve C;
  C.s = &s;
  C.t = &t;
  vismap::engine::Facet F;
  const auto plane = vismap::engine::DepthPlane::of_doubles(0.125, -0.25, 0.0625);   // (s above it, t below)
  F.plane = &plane;
  auto plane_crossing_again = [&] {   // (its own DAG: the same formula on fresh numbers)
    const P3 s2(x(), y(), FT(1) / FT(3)), t2(FT(5) / FT(3), FT(7) / FT(9), FT(-2) / FT(3));
    Curve C2;
    C2.s = &s2;
    C2.t = &t2;
    const P2 p = vismap::engine::plane_crossing(C2, F);
    return std::pair(vismap::exact::exact_x(p), vismap::exact::exact_y(p));
  };
  const P2 pierce = vismap::engine::plane_crossing(C, F);
  const auto pierce_was = pierce.approx();
  const auto [pierce_x, pierce_y] = plane_crossing_again();
  ASSERT_TRUE(wider(pierce_was.x(), pierce_x) || wider(pierce_was.y(), pierce_y));
  EXPECT_EQ(vismap::exact::exact_x(pierce), pierce_x);
  EXPECT_TRUE(unchanged(pierce.approx(), pierce_was));

  // Two curves on the line y = 2x / 3 (x from 0 to 3), one rising in depth, one falling.
  const P3 a0(FT(0), FT(0), FT(1) / FT(3)), a1(FT(3), FT(2), FT(-1) / FT(7));
  const P3 b0(FT(0), FT(0), FT(-2) / FT(9)), b1(FT(3), FT(2), FT(5) / FT(11));
  Curve A, B;
  A.s = &a0;
  A.t = &a1;
  B.s = &b0;
  B.t = &b1;
  P2 meet, meet_again;
  ASSERT_TRUE(vismap::engine::depth_crossing(A, B, a0.xy(), a1.xy(), meet));
  ASSERT_TRUE(vismap::engine::depth_crossing(A, B, a0.xy(), a1.xy(), meet_again));
  const auto meet_was = meet.approx();
  ASSERT_TRUE(wider(meet_was.x(), vismap::exact::exact_x(meet_again)) ||
              wider(meet_was.y(), vismap::exact::exact_y(meet_again)));
  EXPECT_EQ(vismap::exact::exact_x(meet), vismap::exact::exact_x(meet_again));
  EXPECT_TRUE(unchanged(meet.approx(), meet_was));
}

// The parallel sort gives std::sort's order for a strict total order on every
// thread count, and its merge (split across threads) keeps std::inplace_merge's
// stability: of equal keys, the first run's come first, each run's in order.
TEST(Threads, ParallelSortAndMergeAsTheSerialOnes) {
  std::mt19937 rng(11);
  for (const int n : {1000, 20000, 100003}) {
    std::vector<std::pair<int, int>> items(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) items[static_cast<std::size_t>(i)] = {static_cast<int>(rng() % 97), i};
    auto sorted = items;
    std::sort(sorted.begin(), sorted.end());
    for (const int threads : {1, 2, 3, 4, 8}) {
      auto mine = items;
      vismap::engine::parallel_sort(mine.begin(), mine.end(), std::less<>(), threads);
      EXPECT_TRUE(mine == sorted) << n << " items, " << threads << " threads";
    }
    // Two sorted runs of unequal length, merged on the key alone.
    for (const int cut : {n / 3, n / 2, n - n / 5}) {
      auto runs = items;
      auto by_key = [](const auto& a, const auto& b) { return a.first < b.first; };
      std::stable_sort(runs.begin(), runs.begin() + cut, by_key);
      std::stable_sort(runs.begin() + cut, runs.end(), by_key);
      auto serial = runs;
      std::inplace_merge(serial.begin(), serial.begin() + cut, serial.end(), by_key);
      for (const int parts : {2, 3, 4, 16}) {
        auto mine = runs;
        vismap::engine::parallel_inplace_merge(mine.begin(), mine.begin() + cut, mine.end(), by_key, parts);
        EXPECT_TRUE(mine == serial) << n << " items cut at " << cut << ", " << parts << " parts";
      }
    }
  }
}

// The pipeline that writes the JSON: every item made once, taken in order, one
// take at a time (none overlaps another), whatever the thread count; once a
// make throws, no take follows (those taken are the first ones, in order: no
// item past the failed one), and the error reaches the caller.
TEST(Threads, InOrderPipelineTakesEachItemOnceInOrder) {
  for (const int threads : {1, 2, 3, 8}) {
    const int n = 500;
    std::vector<int> taken;
    std::atomic<int> inside{0}, overlaps{0};
    auto make = [](int i) {
      std::vector<int> v(static_cast<std::size_t>(1 + i % 37), i);   // (work of uneven size)
      return v;
    };
    auto take = [&](int i, std::vector<int> v) {
      if (inside.fetch_add(1) != 0) ++overlaps;
      EXPECT_EQ(v.size(), static_cast<std::size_t>(1 + i % 37));
      taken.push_back(v.front());
      std::this_thread::sleep_for(std::chrono::microseconds(20));   // (a take that lasts: others make meanwhile)
      inside.fetch_sub(1);
    };
    vismap::engine::parallel_in_order<std::vector<int>>(n, threads, make, take);
    std::vector<int> all(static_cast<std::size_t>(n));
    std::iota(all.begin(), all.end(), 0);
    EXPECT_EQ(taken, all) << threads << " threads";
    EXPECT_EQ(overlaps.load(), 0) << threads << " threads";
    taken.clear();
    auto failing = [&](int i) {
      if (i == 123) throw std::runtime_error("make 123 failed");
      return make(i);
    };
    EXPECT_THROW(vismap::engine::parallel_in_order<std::vector<int>>(n, threads, failing, take), std::runtime_error);
    ASSERT_LE(taken.size(), 123u) << threads << " threads";
    all.resize(taken.size());
    EXPECT_EQ(taken, all) << threads << " threads";
  }
}

// A polygon soup (every face with its own copies of its corners, in shuffled
// order): vertices with equal coordinates get one id, the least index among
// them, whatever the thread count (the table is filled side by side).
TEST(Threads, CanonicalVertexIdsAreTheLeastEqualVertex) {
  const vismap::Scene mesh = vismap::gen::terrain(120, 5);
  vismap::Scene soup;
  for (const vismap::IndexRing& f : mesh.faces) {
    vismap::IndexRing ring;
    for (std::uint32_t v : f) {
      ring.push_back(static_cast<std::uint32_t>(soup.vertices.size()));
      soup.vertices.push_back(mesh.vertices[v]);
    }
    soup.faces.push_back(ring);
  }
  std::vector<std::uint32_t> place(soup.vertices.size());   // (shuffled: the least copy is not the first used)
  std::iota(place.begin(), place.end(), 0u);
  std::shuffle(place.begin(), place.end(), std::mt19937(7));
  std::vector<Vec3> shuffled(soup.vertices.size());
  for (std::size_t i = 0; i < place.size(); ++i) shuffled[place[i]] = soup.vertices[i];
  soup.vertices = shuffled;
  for (vismap::IndexRing& f : soup.faces)
    for (std::uint32_t& v : f) v = place[v];
  ASSERT_GT(soup.vertices.size(), 4u * 16384u);   // (many chunks per thread)
  std::map<std::tuple<double, double, double>, std::uint32_t> least;
  for (std::uint32_t i = 0; i < soup.vertices.size(); ++i) {
    const Vec3& p = soup.vertices[i];
    least.try_emplace({p.x, p.y, p.z}, i);
  }
  ASSERT_LT(least.size(), soup.vertices.size() / 4);
  for (const int threads : {1, 2, 8}) {
    const vismap::engine::WorldFacets wf = vismap::engine::make_world_facets(soup, threads);
    ASSERT_EQ(wf.facets.size(), soup.faces.size());
    std::size_t wrong = 0;
    for (std::size_t f = 0; f < wf.facets.size(); ++f)
      for (std::size_t k = 0; k < wf.facets[f].v.size(); ++k) {
        const Vec3& p = soup.vertices[soup.faces[f][k]];
        wrong += wf.facets[f].v[k] != least.at({p.x, p.y, p.z});
      }
    EXPECT_EQ(wrong, 0u) << threads << " threads";
  }
}

// A mesh of triangles only has its facets made in place (each face's one facet,
// its normal beside it; a degenerate triangle's slot dropped): the same facets,
// normals and counts, at every thread count, as the general path makes them for
// the same faces once one face is not a triangle (a quad after them).
TEST(WorldFacets, TrianglesAreMadeAsTheGeneralPathMakesThem) {
  const vismap::Scene mesh = vismap::gen::terrain(60, 3);   // (7 200 triangles: several chunks)
  vismap::Scene with_line = mesh;   // (a triangle whose corners are in a line, among the others)
  with_line.vertices.push_back({-7, -7, 0});
  with_line.vertices.push_back({-8, -8, 0});
  with_line.vertices.push_back({-9, -9, 0});
  const auto last = static_cast<std::uint32_t>(with_line.vertices.size() - 1);
  with_line.faces.insert(with_line.faces.begin() + 3000, {last - 2, last - 1, last});
  for (const vismap::Scene* triangles : {&mesh, static_cast<const vismap::Scene*>(&with_line)}) {
    vismap::Scene with_quad = *triangles;
    with_quad.faces.push_back({0, 1, 62, 61});
    for (const int threads : {1, 2}) {
      const vismap::engine::WorldFacets t = vismap::engine::make_world_facets(*triangles, threads);
      const vismap::engine::WorldFacets g = vismap::engine::make_world_facets(with_quad, threads);
      const std::size_t n = mesh.faces.size();
      ASSERT_EQ(t.facets.size(), n);
      ASSERT_EQ(t.normals.size(), n);
      ASSERT_GT(g.facets.size(), n);   // (the quad: one facet, or two where it folds)
      EXPECT_EQ(t.degenerate, triangles == &with_line ? 1 : 0);
      EXPECT_EQ(g.degenerate, t.degenerate);
      for (std::size_t f = 0; f < n; ++f) {
        const vismap::engine::WorldFacet &a = t.facets[f], &b = g.facets[f];
        ASSERT_EQ(std::tuple(a.face, a.planar, a.split), std::tuple(b.face, b.planar, b.split)) << f;
        ASSERT_EQ(std::vector<std::uint32_t>(a.v.begin(), a.v.end()), std::vector<std::uint32_t>(b.v.begin(), b.v.end())) << f;
        ASSERT_TRUE(std::equal(a.role.begin(), a.role.end(), b.role.begin(), b.role.end())) << f;
        ASSERT_EQ(t.normals[f].n, g.normals[f].n) << f;
        ASSERT_EQ(t.normals[f].err, g.normals[f].err) << f;
      }
    }
  }
}

// ---- the whole double range ----------------------------------------------------------

// The regions and segments of a map (what depends on the geometry, not the matrix).
std::string drawing_of(const std::string& json) {
  const auto from = json.find("\"regions\""), to = json.find("\"stats\"");
  return json.substr(from, to - from);
}

// A scene and its eye and target scaled by 2^k: a perspective view projects them
// to the same screen points (the view matrix's last column scales by 2^k, X, Y,
// Z and W with it), so the map is the same, down to every byte of its regions
// and segments, from k = -1000 to 1000. The camera must not overflow or underflow.
TEST(DoubleRange, PerspectiveMapIsTheSameAtEveryPowerOfTwoScale) {
  const vismap::Scene base = vismap::read_scene((fs::path(VISMAP_DATA_DIR) / "interpenetrating_boxes.off").string());
  auto scaled = [](Vec3 v, int k) { return Vec3{std::ldexp(v.x, k), std::ldexp(v.y, k), std::ldexp(v.z, k)}; };
  auto map_at = [&](int k) {
    vismap::Scene s = base;
    for (Vec3& v : s.vertices) v = scaled(v, k);
    vismap::Camera cam;
    cam.eye = scaled({-4, -6, 9}, k);
    cam.target = scaled({3, 3, 1}, k);
    cam.fov_deg = 50;
    return drawing_of(map_json(s, vismap::make_view(cam, s), {}));
  };
  const std::string reference = map_at(0);
  ASSERT_NE(reference.find("\"intersection\""), std::string::npos);
  for (int k : {-1000, -600, -300, 300, 600, 1000}) EXPECT_EQ(map_at(k), reference) << "scale 2^" << k;
}

// ---- the executables' threads ---------------------------------------------------------

#if VISMAP_IDLE_THREADS_SLEEP
// vismap's OpenMP threads spin briefly when idle, then sleep
// (cli/openmp_wait.cpp): its libgomp, asked to show its settings, spins 10 000
// rounds (the shared libgomp's default is 300 000); a policy or a spin count the
// user sets is kept.
TEST(Runtime, IdleOpenMPThreadsSpinBrieflyInTheExecutable) {
  auto settings = [](const std::string& env) {
    const std::string cmd = "env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT " + env + " OMP_DISPLAY_ENV=verbose " +
                            std::string(VISMAP_BIN) + " --help 2>&1 >/dev/null";
    std::string out;
    if (FILE* p = popen(cmd.c_str(), "r")) {
      char buf[4096];
      for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
      EXPECT_EQ(pclose(p), 0) << cmd;
    }
    return out;
  };
  const std::string chosen = settings(""), active = settings("OMP_WAIT_POLICY=active"),
                    passive = settings("OMP_WAIT_POLICY=passive"), count = settings("GOMP_SPINCOUNT=1234");
  EXPECT_NE(chosen.find("GOMP_SPINCOUNT = '10000'"), std::string::npos) << chosen;
  EXPECT_NE(active.find("OMP_WAIT_POLICY = 'ACTIVE'"), std::string::npos) << active;
  EXPECT_NE(passive.find("GOMP_SPINCOUNT = '0'"), std::string::npos) << passive;
  EXPECT_NE(count.find("GOMP_SPINCOUNT = '1234'"), std::string::npos) << count;
}
#endif
#if VISMAP_LARGE_PAGES
// vismap's allocator takes memory in 2 MiB pages where the kernel lends them
// (cli/large_pages.cpp): filling tens of MB then costs a few hundred page
// faults, not one per 4 KiB page; a choice the user made is kept. Measured
// from outside: the child's minor faults against its peak resident memory.
TEST(Runtime, MemoryComesInLargePagesInTheExecutable) {
  std::ifstream thp("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string mode((std::istreambuf_iterator<char>(thp)), std::istreambuf_iterator<char>());
  if (mode.find("[always]") == std::string::npos && mode.find("[madvise]") == std::string::npos)
    GTEST_SKIP() << "the kernel lends no transparent huge pages: " << mode;
  // A terrain of 2 x 159^2 triangles (~60 MB at the peak), seen obliquely.
  const vismap_test::TempDir dir("pages");
  const std::string off = dir.write("terrain.off", vismap::gen::to_off(vismap::gen::terrain(159, 5)));
  auto run = [&](std::vector<std::string> env) {   // (env execs vismap: its usage is vismap's)
    std::vector<std::string> argv = {"/usr/bin/env", "-u", "MIMALLOC_LARGE_OS_PAGES"};
    argv.insert(argv.end(), env.begin(), env.end());
    argv.insert(argv.end(), {VISMAP_BIN, off, "--dir", "-1,-2,-3", "--threads", "1", "--json", dir.file("map.json")});
    const vismap_test::Result r = vismap_test::run(argv, dir.path());
    EXPECT_EQ(r.status, 0) << r.err;
    return r;
  };
  const vismap_test::Result chosen = run({}), users = run({"MIMALLOC_LARGE_OS_PAGES=0"});
  const long chosen_kb = static_cast<long>(chosen.max_rss / 1024), users_kb = static_cast<long>(users.max_rss / 1024);
  ASSERT_GT(chosen_kb, 40 * 1024);
  // In 2 MiB pages: under one fault for every 32 KiB resident at the peak (the
  // loader's own pages included); in 4 KiB pages, the user's choice where the
  // kernel lends large pages only to those who ask (madvise): a fault for each.
  EXPECT_LT(chosen.minor_faults, chosen_kb / 32) << chosen_kb << " KB";
  if (mode.find("[madvise]") != std::string::npos) {
    EXPECT_GT(users.minor_faults, users_kb / 8) << users_kb << " KB";
  }
}

// Blocks the engine frees (vectors of 10^5-10^6 items, which mimalloc gives
// back to the kernel) are used again by the next ones, not asked for anew in
// fresh pages (cli/large_pages.cpp): the memory it touches in all is about its
// peak. Measured from outside in 4 KiB pages (a fault for each fresh page),
// against the user's choice of no reservation, where it touches 1.5x its peak.
TEST(Runtime, FreedMemoryIsReusedInTheExecutable) {
  std::ifstream overcommit("/proc/sys/vm/overcommit_memory");
  int mode = 0;
  if ((overcommit >> mode) && mode == 2) GTEST_SKIP() << "the kernel counts every mapping: no reservation made";
  // A terrain of 2 x 449^2 triangles (~200 MB at the peak), its lines-only
  // drawing, its faces shuffled: the drawing then sorts them along a Morton
  // curve (a terrain's rows it keeps), freeing the blocks the sorted ones replace.
  const vismap_test::TempDir dir("reuse");
  vismap::Scene terrain = vismap::gen::terrain(449, 5);
  std::shuffle(terrain.faces.begin(), terrain.faces.end(), std::mt19937(5));
  const std::string off = dir.write("terrain.off", vismap::gen::to_off(terrain));
  auto touched_per_peak = [&](std::vector<std::string> env) {
    std::vector<std::string> argv = {"/usr/bin/env", "-u", "MIMALLOC_RESERVE_OS_MEMORY", "MIMALLOC_LARGE_OS_PAGES=0"};
    argv.insert(argv.end(), env.begin(), env.end());
    argv.insert(argv.end(), {VISMAP_BIN, off, "--dir", "-1,-2,-3", "--threads", "1", "--lines-only", "-o",
                             dir.file("drawing.svg")});
    const vismap_test::Result r = vismap_test::run(argv, dir.path());
    EXPECT_EQ(r.status, 0) << r.err;
    return static_cast<double>(r.minor_faults) * 4096 / static_cast<double>(r.max_rss);
  };
  EXPECT_LT(touched_per_peak({}), 1.25);
  EXPECT_GT(touched_per_peak({"MIMALLOC_RESERVE_OS_MEMORY=0"}), 1.25);   // (the case is one where it matters)
}
#endif
}  // namespace
