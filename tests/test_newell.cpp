// Newell's engine (depth sort with plane splitting) and the BSP engine (a tree
// built once, traversed per view, then Newell's overlay) against Franklin's and
// the independent checker: the engines must write the same map (regions,
// segments and hidden lines, byte for byte) on the degenerate corpus and on
// seeded random scenes, the checker
// must accept their maps, and the painter's fragments, painted back to front,
// must show the map's face at every pixel centre away from edges.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "arrangements/json_writer.h"
#include "bench/scene_gen.h"
#include "engine/bsp_forest.h"
#include "engine/part_edges.h"
#include "engine/visibility.h"
#include "tests/test_support.h"

namespace {

namespace fs = std::filesystem;
using vismap::Vec3;
using vismap_test::expect_checked;
using vismap_test::slurp;

// The JSON up to its statistics: the map itself (regions, segments, header).
std::string without_stats(const std::string& json) {
  auto k = json.find("\"stats\":");
  return k == std::string::npos ? json : json.substr(0, k);
}

std::string map_json(vismap::VisibilityMap map) {
  map.stats = {};
  return vismap::to_json(map);
}

std::int64_t counted(const vismap::VisibilityMap& m, const std::string& name) {
  for (const auto& [k, v] : m.stats.counts)
    if (k == name) return v;
  return -1;
}

// ---- scenes ----------------------------------------------------------------------

// Newell's three sticks, at random: three long thin rectangles along the sides of
// a triangle, each rising along its length so that at every crossing the one
// ahead lies over the next (a cycle no order of whole faces can paint), each
// rolled about its own axis at random, so that sometimes no stick crosses
// another's plane (only a cut along a screen line can break the cycle) and
// sometimes one does. Seen along -z. (`sticks` of them along the sides of a
// regular polygon: a longer cycle, each crossing only its neighbours.)
vismap::Scene cyclic_sticks(std::uint64_t seed, int sticks = 3) {
  vismap::gen::Rng rng(seed);
  vismap::Scene s;
  const double pi = std::acos(-1.0);
  const double phase = rng.uniform(0, 2 * pi);
  for (int i = 0; i < sticks; ++i) {
    const double th = phase + 2 * pi * i / sticks + rng.uniform(-0.1, 0.1);
    const Vec3 u{std::cos(th), std::sin(th), 0}, n{-std::sin(th), std::cos(th), 0};
    const double r = rng.uniform(0.25, 0.35);
    const double len = sticks == 3 ? rng.uniform(0.9, 1.2) : rng.uniform(1.5, 1.9) * r * std::tan(pi / sticks);
    const double width = rng.uniform(0.05, 0.12);
    const double rise = -rng.uniform(0.2, 0.5), roll = rng.uniform(-2.0, 2.0), z0 = rng.uniform(-0.05, 0.05);
    const std::uint32_t b = static_cast<std::uint32_t>(s.vertices.size());
    for (double a : {-len, len})
      for (double w : {-width, width})
        s.vertices.push_back(Vec3{r * n.x + a * u.x + w * n.x, r * n.y + a * u.y + w * n.y,
                                  z0 + rise * a + roll * w});
    s.faces.push_back({b, b + 2, b + 3, b + 1});
  }
  return s;
}

// Small integer scenes, degenerate on purpose: shared vertices and edges, faces
// in one plane, faces seen edge-on, vertices on other faces' planes.
//   kind 0: axis-aligned rectangles at three depth levels;
//   kind 1: triangles with vertices on the 5x5x5 integer lattice;
//   kind 2: parallelograms with integer corners, tilted.
vismap::Scene lattice(int kind, std::uint64_t seed) {
  vismap::gen::Rng rng(seed);
  vismap::Scene s;
  auto I = [&](int k) { return static_cast<double>(static_cast<int>(rng.uniform() * k)); };
  const int n = kind == 1 ? 8 : 10;
  for (int i = 0; i < n; ++i) {
    const auto b = static_cast<std::uint32_t>(s.vertices.size());
    if (kind == 0) {
      const double x = I(6), y = I(6), w = 1 + I(3), h = 1 + I(3), z = I(3);
      s.vertices.insert(s.vertices.end(), {{x, y, z}, {x + w, y, z}, {x + w, y + h, z}, {x, y + h, z}});
      s.faces.push_back({b, b + 1, b + 2, b + 3});
    } else if (kind == 1) {
      for (int k = 0; k < 3; ++k) s.vertices.push_back({I(5), I(5), I(5)});
      s.faces.push_back({b, b + 1, b + 2});
    } else {
      const double x = I(5), y = I(5), z = I(4);
      const double ax = 1 + I(3), ay = I(2), az = I(3) - 1, bx = I(2), by = 1 + I(3), bz = I(3) - 1;
      s.vertices.insert(s.vertices.end(), {{x, y, z}, {x + ax, y + ay, z + az},
                                           {x + ax + bx, y + ay + by, z + az + bz}, {x + bx, y + by, z + bz}});
      s.faces.push_back({b, b + 1, b + 2, b + 3});
    }
  }
  return s;
}

const Vec3 kLatticeViews[] = {{0, 0, -1}, {-1, -2, -1.5}, {-0.3, -0.5, -1}, {1, 0, -1}, {0, -1, 0}};

vismap::Camera ortho(Vec3 d) {
  vismap::Camera c;
  c.dir = d;
  return c;
}
vismap::Camera persp(Vec3 eye, Vec3 target, double fov) {
  vismap::Camera c;
  c.eye = eye;
  c.target = target;
  c.fov_deg = fov;
  return c;
}

struct RandomCase {
  std::string name;
  vismap::Scene (*make)(std::uint64_t seed);
  vismap::Camera camera;
};

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
      {"triangles_big", [](std::uint64_t s) { return random_triangles(12, 0.8, s); }, ortho({0.3, -0.2, -1})},
      {"triangles_perspective", [](std::uint64_t s) { return random_triangles(30, 0.4, s); },
       persp({1.5, 2.2, 1.7}, {0.5, 0.5, 0.5}, 60)},
      {"boxes", [](std::uint64_t s) { return interpenetrating_boxes(4, s); }, ortho({-1, -2, -1.5})},
      {"boxes_perspective", [](std::uint64_t s) { return interpenetrating_boxes(4, s); },
       persp({3, -4, 3.5}, {0, 0, 0}, 45)},
      {"cyclic_sticks", [](std::uint64_t s) { return cyclic_sticks(s); }, ortho({0, 0, -1})},
      {"sticks_and_squares",
       [](std::uint64_t s) {
         vismap::Scene sc = cyclic_sticks(s);
         vismap::Scene sq = random_squares_depth(20, 2, s);
         transform(sq, 1.2, {-0.6, -0.6, -0.3});
         append_scene(sc, sq);
         return sc;
       },
       ortho({0.1, 0.2, -1})},
      {"terrain", [](std::uint64_t s) { return terrain(5, s); }, ortho({-1, -0.5, -0.7})},
  };
}

// ---- both engines, one map --------------------------------------------------------

class Corpus : public ::testing::TestWithParam<std::string> {};

// End to end through the program: --algorithm newell and franklin write the same
// regions and segments; the checker accepts Newell's; --painter writes a drawing.
TEST_P(Corpus, NewellWritesFranklinsMap) {
  const std::string line = GetParam();
  const auto tab = line.find('\t');
  const std::string file = line.substr(0, tab), args = tab == std::string::npos ? "" : line.substr(tab + 1);
  const fs::path scene = fs::path(VISMAP_DATA_DIR) / file;
  const fs::path dir = fs::temp_directory_path() / ("vismap_newell_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path franklin = dir / "franklin.json", newell = dir / "newell.json", painter = dir / "painter.svg";
  // (With the hidden lines: both engines write them, identically, and the checker checks them.)
  const std::string base = std::string(VISMAP_BIN) + " '" + scene.string() + "' " + args + " --hidden";
  const std::string run_f = base + " --algorithm franklin --json '" + franklin.string() + "'";
  const std::string run_n = base + " --algorithm newell --json '" + newell.string() + "' --painter '" + painter.string() + "'";
  ASSERT_EQ(std::system(run_f.c_str()), 0) << run_f;
  ASSERT_EQ(std::system(run_n.c_str()), 0) << run_n;
  const std::string jn = slurp(newell);
  EXPECT_EQ(without_stats(jn), without_stats(slurp(franklin))) << file << ": the engines' maps differ";
  vismap_check::Options opt;
  opt.smooth = args.find("--smooth") != std::string::npos;
  expect_checked(vismap::read_scene(scene.string()), jn, opt, file + " (newell)");
  // The BSP engine: the same map.
  const fs::path bsp = dir / "bsp.json";
  const std::string run_b = base + " --algorithm bsp --json '" + bsp.string() + "'";
  ASSERT_EQ(std::system(run_b.c_str()), 0) << run_b;
  const std::string jb = slurp(bsp);
  EXPECT_EQ(without_stats(jb), without_stats(jn)) << file << ": the BSP engine's map differs";
  expect_checked(vismap::read_scene(scene.string()), jb, opt, file + " (bsp)");
  const std::string svg = slurp(painter);
  EXPECT_EQ(svg.rfind("<svg", 0), 0u) << file;
  EXPECT_NE(svg.find("</svg>"), std::string::npos) << file;
  fs::remove_all(dir);
}

std::vector<std::string> corpus_lines() {
  return vismap_test::case_lines(fs::path(VISMAP_DATA_DIR) / "cases.txt");
}

INSTANTIATE_TEST_SUITE_P(Degenerate, Corpus, ::testing::ValuesIn(corpus_lines()), [](const auto& info) {
  return vismap_test::case_name(vismap_test::split_case(info.param).file, info.index);
});

class Random : public ::testing::TestWithParam<std::tuple<int, int>> {};

TEST_P(Random, SameMapAsFranklinAndCheckerAccepts) {
  const auto cases = random_cases();
  const RandomCase& rc = cases[std::get<0>(GetParam())];
  const auto seed = static_cast<std::uint64_t>(std::get<1>(GetParam()));
  vismap::Scene scene = rc.make(seed);
  scene.file = rc.name;
  const vismap::View view = vismap::make_view(rc.camera, scene);
  const std::string what = rc.name + " seed " + std::to_string(seed);
  vismap::Options hidden;
  hidden.hidden = true;
  const std::string jn = map_json(vismap::visibility_newell(scene, view, hidden));
  EXPECT_EQ(jn, map_json(vismap::visibility_franklin(scene, view, hidden))) << what << ": the engines' maps differ";
  EXPECT_EQ(map_json(vismap::visibility_bsp(scene, view, hidden)), jn) << what << ": the BSP engine's map differs";
  EXPECT_NE(jn.find("\"hidden\""), std::string::npos) << what;
  vismap_check::Options opt;
  opt.samples = 1000;
  opt.seed = seed;
  expect_checked(scene, jn, opt, what);
}

INSTANTIATE_TEST_SUITE_P(Scenes, Random,
                         ::testing::Combine(::testing::Range(0, static_cast<int>(random_cases().size())),
                                            ::testing::Range(1, 4)),
                         [](const auto& info) {
                           return random_cases()[std::get<0>(info.param)].name + "_seed" +
                                  std::to_string(std::get<1>(info.param));
                         });

// Many more scenes, both engines only (no checker): cheap, and the differences
// they could show are between two exact programs.
TEST(Differential, ManySeeds) {
  const auto cases = random_cases();
  for (std::size_t c = 0; c < cases.size(); ++c)
    for (std::uint64_t seed = 10; seed < 18; ++seed) {
      vismap::Scene scene = cases[c].make(seed);
      const vismap::View view = vismap::make_view(cases[c].camera, scene);
      vismap::Options hidden;
      hidden.hidden = true;
      const std::string jf = map_json(vismap::visibility_franklin(scene, view, hidden));
      EXPECT_EQ(map_json(vismap::visibility_newell(scene, view, hidden)), jf) << cases[c].name << " seed " << seed;
      EXPECT_EQ(map_json(vismap::visibility_bsp(scene, view, hidden)), jf) << cases[c].name << " seed " << seed << " (bsp)";
    }
}

// Boxes standing on a grid, of a few heights (their tops level with each
// other, their walls in common planes), seen from around them with the up axis
// vertical: their vertical edges are upright lines on the screen, on which many
// crossings and end points lie with exactly one x. Newell's and the BSP
// engine's maps are Franklin's byte for byte (the assembly then tells those
// points' x by the lines' and the vertices' own numbers: MapPiece::xa).
TEST(Differential, BoxesAroundUprightLines) {
  std::int64_t segments = 0;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    vismap::gen::Rng rng(seed);
    vismap::Scene scene;
    auto box = [&](double x, double y, double w, double d, double h) {
      const auto b = static_cast<std::uint32_t>(scene.vertices.size());
      for (const double z : {0.0, h})
        scene.vertices.insert(scene.vertices.end(), {{x, y, z}, {x + w, y, z}, {x + w, y + d, z}, {x, y + d, z}});
      scene.faces.push_back({b + 3, b + 2, b + 1, b});   // bottom, facing down
      scene.faces.push_back({b + 4, b + 5, b + 6, b + 7});   // top
      for (std::uint32_t k = 0; k < 4; ++k)
        scene.faces.push_back({b + k, b + (k + 1) % 4, b + 4 + (k + 1) % 4, b + 4 + k});
    };
    for (int i = 0; i < 5; ++i)
      for (int j = 0; j < 5; ++j)
        if (rng.uniform() < 0.7)
          box(3 * i + std::floor(rng.uniform() * 2), 3 * j, 1 + std::floor(rng.uniform() * 2), 2,
              1 + std::floor(rng.uniform() * 3));
    for (int k = 0; k < 6; ++k) {
      const double a = 2 * std::acos(-1.0) * k / 6 + 0.2 * static_cast<double>(seed), e = 0.5;
      const vismap::View view =
          vismap::make_view(ortho({std::cos(a) * std::cos(e), std::sin(a) * std::cos(e), -std::sin(e)}), scene);
      const vismap::VisibilityMap franklin = vismap::visibility_franklin(scene, view, {});
      segments += static_cast<std::int64_t>(franklin.segments.size());
      const std::string jf = map_json(franklin);
      EXPECT_EQ(map_json(vismap::visibility_newell(scene, view, {})), jf) << "seed " << seed << " view " << k;
      EXPECT_EQ(map_json(vismap::visibility_bsp(scene, view, {})), jf) << "seed " << seed << " view " << k << " (bsp)";
    }
  }
  EXPECT_GT(segments, 1000);
}

// Every cycle of three sticks is split (no order of whole faces paints it), and
// the runs end. Large crossing triangles also reach the third split, the cut of
// a face along a screen line where neither face crosses the other's plane: the
// maps stay Franklin's.
TEST(Differential, CyclesAreSplit) {
  std::int64_t by_plane = 0, by_cut = 0, reorders = 0;
  for (std::uint64_t seed = 1; seed <= 30; ++seed) {
    vismap::Scene scene = cyclic_sticks(seed);
    const vismap::View view = vismap::make_view(ortho({0, 0, -1}), scene);
    vismap::VisibilityMap n = vismap::visibility_newell(scene, view, {});
    by_plane += counted(n, "splits_by_plane") + counted(n, "splits_by_cut");
    reorders += counted(n, "reorders");
    EXPECT_GT(counted(n, "fragments_written"), 3) << "seed " << seed << ": a cycle was painted unsplit";
    EXPECT_EQ(map_json(n), map_json(vismap::visibility_franklin(scene, view, {}))) << "sticks seed " << seed;
    // The BSP engine breaks it too (Bsp.CyclesOfObjectsAreBroken says how).
    EXPECT_EQ(map_json(vismap::visibility_bsp(scene, view, {})), map_json(n)) << "sticks seed " << seed << " (bsp)";
  }
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    vismap::Scene scene = vismap::gen::random_triangles(12, 0.8, seed);
    const vismap::View view = vismap::make_view(ortho({-1, -2, -1.5}), scene);
    vismap::VisibilityMap n = vismap::visibility_newell(scene, view, {});
    by_cut += counted(n, "splits_by_cut");
    EXPECT_EQ(map_json(n), map_json(vismap::visibility_franklin(scene, view, {}))) << "triangles seed " << seed;
  }
  EXPECT_GT(by_plane, 0);
  EXPECT_GT(by_cut, 0);
  EXPECT_GT(reorders, 0);
}

// Degenerate integer scenes: the checker accepts Newell's maps, from above, along
// axes (faces edge-on) and obliquely, and Franklin writes the same map.
TEST(Lattice, CheckerAcceptsNewellsMaps) {
  for (int kind = 0; kind < 3; ++kind)
    for (std::uint64_t seed = 1; seed <= 12; ++seed)
      for (const Vec3& dir : kLatticeViews) {
        vismap::Scene scene = lattice(kind, seed);
        scene.file = "lattice";
        const vismap::View view = vismap::make_view(ortho(dir), scene);
        const std::string what = "lattice kind " + std::to_string(kind) + " seed " + std::to_string(seed) +
                                 " dir " + std::to_string(dir.x) + "," + std::to_string(dir.y) + "," +
                                 std::to_string(dir.z);
        const std::string jn = map_json(vismap::visibility_newell(scene, view, {}));
        vismap_check::Options opt;
        opt.samples = 400;
        expect_checked(scene, jn, opt, what);
        EXPECT_EQ(jn, map_json(vismap::visibility_franklin(scene, view, {}))) << what;
        EXPECT_EQ(map_json(vismap::visibility_bsp(scene, view, {})), jn) << what << " (bsp)";
      }
}

// One tree for many views: 8 directions around each scene (above, below and
// level with it, faces seen edge-on among them) and 8 eyes (inside the scene:
// the near plane cuts fragments), the tree built once; each
// view's map is the one-view run's, and Franklin's.
TEST(Bsp, OneTreeServesEveryView) {
  for (const auto& rc : random_cases()) {
    const vismap::Scene scene = rc.make(5);
    vismap::engine::BspForest forest = vismap::engine::build_bsp_forest(scene);
    std::size_t facets = 0;
    for (std::size_t g = 0; g < forest.groups.size(); ++g) {
      facets += forest.groups[g].size();
      const auto& t = forest.trees[g];
      EXPECT_EQ(static_cast<std::int64_t>(t.fragments.size() - forest.groups[g].size()), t.splits) << rc.name;
    }
    EXPECT_EQ(facets, forest.facets->facets.size()) << rc.name << ": every facet in one group";
    for (int k = 0; k < 16; ++k) {
      const double a = 2 * std::acos(-1.0) * (k % 8) / 8 + 0.1 * k, elevation = k % 3 == 0 ? 0 : k % 3 == 1 ? 0.6 : -0.8;
      const Vec3 d{std::cos(a), std::sin(a), elevation};
      // Eyes 0.3 from the middle of the unit cube the scenes fill.
      const double r = 0.3;
      const vismap::Camera cam = k < 8 ? ortho(d) : persp({0.5 - r * d.x, 0.5 - r * d.y, 0.5 - r * d.z}, {0.5, 0.5, 0.5}, 70);
      const vismap::View view = vismap::make_view(cam, scene);
      const std::string shared = map_json(vismap::visibility_bsp(scene, view, {}, nullptr, &forest));
      EXPECT_EQ(shared, map_json(vismap::visibility_bsp(scene, view, {}))) << rc.name << " view " << k;
      EXPECT_EQ(shared, map_json(vismap::visibility_franklin(scene, view, {}))) << rc.name << " view " << k;
    }
  }
}

// Tomlinson's priority over objects: rings of 3, 4 and 5 sticks, each stick an
// object, each over the next where they cross (a cycle of priorities no order
// of whole objects paints). The cycle is found, either in a view (a circuit:
// its objects drawn by one tree of their union, made once and kept for later
// views) or in preprocessing (no plane separates two of them: one group), and
// the map is Franklin's.
TEST(Bsp, CyclesOfObjectsAreBroken) {
  std::int64_t circuits = 0;
  for (int sticks : {3, 4, 5})
    for (std::uint64_t seed = 1; seed <= 8; ++seed) {
      const std::string what = std::to_string(sticks) + " sticks, seed " + std::to_string(seed);
      const vismap::Scene scene = cyclic_sticks(seed, sticks);
      const vismap::View view = vismap::make_view(ortho({0, 0, -1}), scene);
      vismap::engine::BspForest forest = vismap::engine::build_bsp_forest(scene);
      EXPECT_EQ(forest.objects, sticks) << what;
      const vismap::VisibilityMap m = vismap::visibility_bsp(scene, view, {}, nullptr, &forest);
      const std::int64_t found = counted(m, "priority_circuits");
      EXPECT_TRUE(found > 0 || counted(m, "bsp_groups") < sticks) << what << ": a cycle was drawn unbroken";
      EXPECT_EQ(map_json(m), map_json(vismap::visibility_franklin(scene, view, {}))) << what;
      circuits += found;
      // Another view of the same forest: the circuit's tree is not made again.
      const std::size_t trees = forest.circuits.size();
      const vismap::View tilted = vismap::make_view(ortho({0.05, -0.03, -1}), scene);
      EXPECT_EQ(map_json(vismap::visibility_bsp(scene, tilted, {}, nullptr, &forest)),
                map_json(vismap::visibility_franklin(scene, tilted, {})))
          << what << " (tilted)";
      if (found > 0) {
        EXPECT_EQ(forest.circuits.size(), trees) << what;
      }
    }
  EXPECT_GT(circuits, 0) << "no cycle was found by the priorities (all were groups)";
}

// Views side by side (vismap --views on several threads) share one forest: the
// first view that meets a cycle makes its tree, the others wait and take it.
// Four threads draw the rings of sticks from eight directions at once, each
// map the one-view run's.
TEST(Bsp, ViewsSideBySideShareOneForest) {
  std::int64_t circuits = 0;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    const vismap::Scene scene = cyclic_sticks(seed, 3 + static_cast<int>(seed % 3));
    vismap::engine::BspForest forest = vismap::engine::build_bsp_forest(scene);
    std::vector<vismap::View> views;
    for (int k = 0; k < 8; ++k)
      views.push_back(vismap::make_view(ortho({0.02 * (k % 3), 0.015 * (k % 4), -1}), scene));
    std::vector<std::string> shared(views.size());
    std::vector<std::int64_t> found(views.size());
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
      threads.emplace_back([&, t] {
        for (std::size_t k = static_cast<std::size_t>(t); k < views.size(); k += 4) {
          const vismap::VisibilityMap m = vismap::visibility_bsp(scene, views[k], {}, nullptr, &forest);
          found[k] = counted(m, "priority_circuits");
          shared[k] = map_json(m);
        }
      });
    for (std::thread& t : threads) t.join();
    for (std::size_t k = 0; k < views.size(); ++k) {
      EXPECT_EQ(shared[k], map_json(vismap::visibility_bsp(scene, views[k], {}))) << "seed " << seed << " view " << k;
      circuits += found[k];
    }
  }
  EXPECT_GT(circuits, 0) << "no view met a cycle: the shared trees of cycles were not exercised";
}

bool has_segment(const vismap::VisibilityMap& m, const std::string& x0, const std::string& y0,
                 const std::string& x1, const std::string& y1) {
  for (const auto& s : m.segments) {
    const vismap::Point2 &from = m.at(s.from), &to = m.at(s.to);
    if (from.x == mpq_class(x0) && from.y == mpq_class(y0) && to.x == mpq_class(x1) && to.y == mpq_class(y1))
      return true;
  }
  return false;
}

// A line of a face seen edge-on passes through another face's plane inside it:
// no intersection line ends there (edge-on faces hide nothing), yet the line
// goes from hidden to visible. Worked by hand (view along -y: X = -x, Y = z,
// depth = -y): on the nearer edge of the edge-on face, at (-1 - 3t, t) for t in
// [0, 1], the edge's depth is -6 - t and the square's 3t - 7, so the edge is
// hidden up to t = 1/4, at (-7/4, 1/4), and visible after.
TEST(EdgeOn, LinePiercingAFaceIsCutWhereItComesOut) {
  vismap::Scene sq;
  sq.vertices = {{1, 4, 1}, {4, 4, 1}, {4, 7, 0}, {1, 7, 0}, {1, 4, 0}, {4, 5, 1}, {4, 7, 1}, {1, 6, 0}};
  sq.faces = {{0, 1, 2, 3}, {4, 5, 6, 7}};
  vismap::VisibilityMap m = vismap::visibility_newell(sq, vismap::make_view(ortho({0, -1, 0}), sq), {});
  EXPECT_TRUE(has_segment(m, "-4", "1", "-7/4", "1/4")) << vismap::to_json(m);
  EXPECT_FALSE(has_segment(m, "-4", "1", "-1", "0")) << "the hidden part is drawn";
  EXPECT_EQ(map_json(m), map_json(vismap::visibility_franklin(sq, vismap::make_view(ortho({0, -1, 0}), sq), {})));
  // The map with that segment drawn whole (what Franklin wrote before the fix) is
  // rejected by the checker: its segment check cuts where the line pierces a plane.
  m.vertices.push_back(vismap::Point2{-1, 0});
  for (auto& s : m.segments)
    if (m.at(s.from).x == -4 && m.at(s.from).y == 1 && m.at(s.to).x == mpq_class(-7, 4))
      s.to = static_cast<std::uint32_t>(m.vertices.size() - 1);
  sq.file = "pierce";
  EXPECT_FALSE(vismap_check::check_map(sq, vismap::to_json(m), {}).ok) << vismap::to_json(m);
  // Two triangles, the second seen edge-on: its nearer edge (depth -3t) is behind
  // the first (depth 14t - 14) until t = 14/17, at (-62/17, 42/17).
  vismap::Scene tri;
  tri.vertices = {{4, 4, 2}, {2, 2, 3}, {4, 0, 3}, {2, 0, 0}, {4, 3, 3}, {4, 2, 3}};
  tri.faces = {{0, 1, 2}, {3, 4, 5}};
  m = vismap::visibility_newell(tri, vismap::make_view(ortho({0, -1, 0}), tri), {});
  EXPECT_TRUE(has_segment(m, "-4", "3", "-62/17", "42/17")) << vismap::to_json(m);
  EXPECT_FALSE(has_segment(m, "-4", "3", "-7/2", "9/4")) << "the hidden part is drawn";
  EXPECT_EQ(map_json(m), map_json(vismap::visibility_franklin(tri, vismap::make_view(ortho({0, -1, 0}), tri), {})));
}

// ---- the painter's drawing ---------------------------------------------------------

double seg_distance(double px, double py, double ax, double ay, double bx, double by) {
  const double dx = bx - ax, dy = by - ay, l2 = dx * dx + dy * dy;
  double t = l2 > 0 ? ((px - ax) * dx + (py - ay) * dy) / l2 : 0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(px - ax - t * dx, py - ay - t * dy);
}

using Ring = std::vector<std::pair<double, double>>;

Ring ring_of(const std::vector<vismap::Point2>& pts) {
  Ring r;
  for (const auto& p : pts) r.emplace_back(p.x.get_d(), p.y.get_d());
  return r;
}

bool in_ring(const Ring& r, double x, double y) {   // even-odd
  bool in = false;
  for (std::size_t i = 0, j = r.size() - 1; i < r.size(); j = i++)
    if ((r[i].second > y) != (r[j].second > y) &&
        x < (r[j].first - r[i].first) * (y - r[i].second) / (r[j].second - r[i].second) + r[i].first)
      in = !in;
  return in;
}

double ring_distance(const Ring& r, double x, double y) {
  double d = HUGE_VAL;
  for (std::size_t i = 0, j = r.size() - 1; i < r.size(); j = i++)
    d = std::min(d, seg_distance(x, y, r[j].first, r[j].second, r[i].first, r[i].second));
  return d;
}

// Paints the fragments back to front on a res x res raster over the map and
// compares, at every pixel centre farther than a small margin from any fragment
// side and any region boundary, the last-painted face with the map's region.
// (bsp: the BSP engine's fragments, in its tree's order.)
void expect_painter_matches_map(const vismap::Scene& scene, const vismap::Camera& cam, const std::string& what,
                                bool bsp = false) {
  const vismap::View view = vismap::make_view(cam, scene);
  std::vector<vismap::PaintedFragment> frags;
  const vismap::VisibilityMap map =
      bsp ? vismap::visibility_bsp(scene, view, {}, &frags) : vismap::visibility_newell(scene, view, {}, &frags);
  ASSERT_FALSE(frags.empty()) << what;
  std::vector<Ring> frag_rings;
  for (const auto& f : frags) frag_rings.push_back(ring_of(f.polygon));
  struct R { int face; Ring outer; std::vector<Ring> holes; };
  std::vector<R> regions;
  double x0 = HUGE_VAL, y0 = HUGE_VAL, x1 = -HUGE_VAL, y1 = -HUGE_VAL;
  for (const auto& g : map.regions) {
    R r{g.face, ring_of(map.points(g.outer)), {}};
    for (const auto& h : g.holes) r.holes.push_back(ring_of(map.points(h)));
    for (const auto& [x, y] : r.outer) { x0 = std::min(x0, x); x1 = std::max(x1, x); y0 = std::min(y0, y); y1 = std::max(y1, y); }
    regions.push_back(std::move(r));
  }
  const int res = 96;
  const double margin = 1e-7 * std::max(x1 - x0, y1 - y0);
  int compared = 0, wrong = 0;
  std::string first;
  for (int iy = 0; iy < res; ++iy)
    for (int ix = 0; ix < res; ++ix) {
      const double x = x0 + (x1 - x0) * (ix + 0.5) / res, y = y0 + (y1 - y0) * (iy + 0.5) / res;
      bool near_edge = false;
      int painted = -1;
      for (std::size_t k = 0; k < frags.size() && !near_edge; ++k) {
        near_edge = ring_distance(frag_rings[k], x, y) < margin;
        if (in_ring(frag_rings[k], x, y)) painted = frags[k].face;   // later fragments paint over
      }
      int label = -1;
      for (const R& r : regions) {
        if (near_edge) break;
        near_edge = ring_distance(r.outer, x, y) < margin;
        for (const Ring& h : r.holes) near_edge = near_edge || ring_distance(h, x, y) < margin;
        if (!near_edge && label < 0 && in_ring(r.outer, x, y)) {
          bool in_hole = false;
          for (const Ring& h : r.holes) in_hole = in_hole || in_ring(h, x, y);
          if (!in_hole) label = r.face;
        }
      }
      if (near_edge) continue;
      ++compared;
      if (painted != label) {
        if (!wrong++) first = "(" + std::to_string(x) + ", " + std::to_string(y) + "): painted face " +
                               std::to_string(painted) + ", map face " + std::to_string(label);
      }
    }
  EXPECT_EQ(wrong, 0) << what << ": " << wrong << " of " << compared << " pixels differ, first at " << first;
  EXPECT_GT(compared, res * res / 2) << what;
}

TEST(Painter, BackToFrontShowsTheMap) {
  using namespace vismap::gen;
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const std::string s = " seed " + std::to_string(seed);
    expect_painter_matches_map(random_triangles(30, 0.5, seed), ortho({-1, -2, -1.5}), "triangles" + s);
    expect_painter_matches_map(random_triangles(25, 0.4, seed), persp({1.5, 2.2, 1.7}, {0.5, 0.5, 0.5}, 60),
                               "triangles perspective" + s);
    expect_painter_matches_map(interpenetrating_boxes(4, seed), ortho({-1, -2, -1.5}), "boxes" + s);
    expect_painter_matches_map(random_squares_depth(40, 4, seed), ortho({-0.3, -0.5, -1}), "squares" + s);
    expect_painter_matches_map(cyclic_sticks(seed), ortho({0, 0, -1}), "cyclic sticks" + s);
    expect_painter_matches_map(random_triangles(30, 0.5, seed), ortho({-1, -2, -1.5}), "bsp triangles" + s, true);
    expect_painter_matches_map(interpenetrating_boxes(4, seed), ortho({-1, -2, -1.5}), "bsp boxes" + s, true);
    expect_painter_matches_map(cyclic_sticks(seed), ortho({0, 0, -1}), "bsp cyclic sticks" + s, true);
    expect_painter_matches_map(random_triangles(25, 0.4, seed), persp({1.5, 2.2, 1.7}, {0.5, 0.5, 0.5}, 60),
                               "bsp triangles perspective" + s, true);
  }
}

}  // namespace

// A fragment's edges keep the facet edge each lies on through a cut and a
// reversal (engine/part_edges.h): the overlay then tells a curve on its own
// facet's edge by index.
TEST(PartEdges, CutAndReversedQuadKeepsItsEdgesLabels) {
  using namespace vismap::engine;
  // Quad c0 c1 c2 c3, its edges labelled 10..13, cut by a line through edges 1 and 3:
  // the part c0, c1, x1 (on edge 1), x3 (on edge 3).
  const std::vector<int> labels{10, 11, 12, 13};
  const std::vector<std::uint64_t> part{on_corner(0, 4), on_corner(1, 4), on_edge(1), on_edge(3)};
  const std::vector<int> edges = part_edges(part, labels);
  EXPECT_EQ(edges, (std::vector<int>{10, 11, -1, 13}));   // c0-c1 on 0, c1-x1 on 1, x1-x3 the cut, x3-c0 on 3
  // Reversed: x3, x1, c1, c0.
  EXPECT_EQ(reversed_edges(edges), (std::vector<int>{-1, 11, 10, 13}));
  // A corner kept for two equal on the screen (corners 1 and 2 of the quad) lies on edges 0, 1 and 2.
  const std::vector<std::uint64_t> merged{on_corner(0, 4), on_corner(1, 4) | on_corner(2, 4), on_corner(3, 4)};
  EXPECT_EQ(part_edges(merged, labels), (std::vector<int>{10, 12, 13}));
  // Edges from the 64th on have no bit: not known.
  EXPECT_EQ(part_edges({on_corner(64, 70), on_corner(65, 70)}, std::vector<int>(70, 7)), (std::vector<int>{-1, -1}));
}
