// The library's API (include/vismap/vismap.h) against the command line: the same
// map, byte for byte, on the corpus; vertices as the nearest doubles to their
// exact values; errors as exceptions whose messages name no command-line flag;
// files written by extension, whole or not at all.
#include <gmpxx.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "arrangements/rational.h"
#include "tests/test_support.h"
#include "vismap/vismap.h"

namespace {

namespace fs = std::filesystem;
using vismap_test::slurp;

// A case's camera and options from its command-line arguments (the corpus's
// lines use --dir, --eye, --target, --fov, --up, --smooth and --crease).
struct Call {
  vismap::Camera camera;
  vismap::Options options;
};

vismap::Vec3 vec(const std::string& text) {
  vismap::Vec3 v;
  char c1, c2;
  std::istringstream in(text);
  in >> v.x >> c1 >> v.y >> c2 >> v.z;
  return v;
}

Call call_of(const std::string& args) {
  Call c;
  std::istringstream in(args);
  std::string a, v;
  while (in >> a) {
    if (a == "--smooth") { c.options.smooth = true; continue; }
    in >> v;
    if (a == "--dir") c.camera.dir = vec(v);
    else if (a == "--eye") c.camera.eye = vec(v);
    else if (a == "--target") c.camera.target = vec(v);
    else if (a == "--up") c.camera.up = vec(v);
    else if (a == "--fov") c.camera.fov_deg = std::stod(v);
    else if (a == "--crease") c.options.crease_deg = std::stod(v);
    else ADD_FAILURE() << "the test does not know " << a;
  }
  return c;
}

fs::path temp_dir() {
  const fs::path d = fs::temp_directory_path() / ("vismap_api_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

// The command line's JSON for a scene and arguments.
std::string cli_json(const fs::path& scene, const std::string& args) {
  const fs::path out = temp_dir() / "cli.json";
  const std::string cmd = std::string(VISMAP_BIN) + " '" + scene.string() + "' " + args + " --json '" + out.string() + "'";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  return slurp(out);
}

class ApiCorpus : public ::testing::TestWithParam<vismap_test::Case> {};

TEST_P(ApiCorpus, JsonIsTheCommandLinesByteForByte) {
  const vismap_test::Case& c = GetParam();
  const fs::path scene = fs::path(VISMAP_DATA_DIR) / c.file;
  Call call = call_of(c.args);
  const vismap::Scene s = vismap::read_scene(scene.string());
  EXPECT_EQ(vismap::compute(s, call.camera, call.options).to_json(), cli_json(scene, c.args)) << c.file;
  call.options.hidden = true;
  call.options.algorithm = vismap::Algorithm::Newell;
  EXPECT_EQ(vismap::compute(s, call.camera, call.options).to_json(), cli_json(scene, c.args + " --hidden --algorithm newell"))
      << c.file << " with hidden lines, Newell's engine";
  call.options.regions = false;
  call.options.algorithm = vismap::Algorithm::Franklin;
  EXPECT_EQ(vismap::compute(s, call.camera, call.options).to_json(), cli_json(scene, c.args + " --hidden --no-regions"))
      << c.file << " without regions";
}

std::vector<vismap_test::Case> corpus() {
  std::vector<vismap_test::Case> cases;
  for (const std::string& line : vismap_test::case_lines(fs::path(VISMAP_DATA_DIR) / "cases.txt"))
    cases.push_back(vismap_test::split_case(line));
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Corpus, ApiCorpus, ::testing::ValuesIn(corpus()),
                         [](const ::testing::TestParamInfo<vismap_test::Case>& info) {
                           return vismap_test::case_name(info.param.file, info.index);
                         });

// |q - d| is no more than |q - d'| for the doubles d' on either side of d, and
// a tie goes to the even one.
void expect_nearest(const mpq_class& q, double d) {
  ASSERT_TRUE(std::isfinite(d)) << q.get_str();
  const mpq_class err = abs(q - mpq_class(d));
  for (double side : {std::nextafter(d, -INFINITY), std::nextafter(d, INFINITY)}) {
    if (!std::isfinite(side)) continue;
    const mpq_class other = abs(q - mpq_class(side));
    EXPECT_LE(err, other) << q.get_str() << " -> " << d;
    if (err == other) {
      std::int64_t bits;
      std::memcpy(&bits, &d, sizeof d);
      EXPECT_EQ(bits % 2, 0) << "a tie, not to even: " << q.get_str();
    }
  }
}

TEST(Api, NearestDoubleRoundsToNearestAndTiesToEven) {
  const double tiny = std::numeric_limits<double>::denorm_min(), big = std::numeric_limits<double>::max();
  std::vector<mpq_class> qs = {mpq_class(1, 3), mpq_class(-2, 3), mpq_class(1, 10), mpq_class(0)};
  // Exact ties: halfway between 1 and the next double, and between two subnormals.
  mpq_class half_ulp(1);
  half_ulp /= mpq_class(mpz_class(1) << 53);
  qs.push_back(1 + half_ulp);
  qs.push_back(1 + 3 * half_ulp);
  qs.push_back(-(1 + half_ulp));
  qs.push_back(mpq_class(tiny) * 3 / 2);
  qs.push_back(mpq_class(tiny) * 5 / 2);
  qs.push_back(mpq_class(tiny) / 3);
  qs.push_back(mpq_class(1, 7) * mpq_class(tiny));
  qs.push_back(mpq_class(big) - 1);
  for (const mpq_class& q : qs) expect_nearest(q, vismap::nearest_double(q));
  EXPECT_EQ(vismap::nearest_double(1 + half_ulp), 1.0);
  EXPECT_EQ(vismap::nearest_double(1 + 3 * half_ulp), std::nextafter(1.0, 2.0) + 2 * std::ldexp(1.0, -52) - std::ldexp(1.0, -52));
  EXPECT_EQ(vismap::nearest_double(mpq_class(tiny) * 3 / 2), 2 * tiny);
  EXPECT_EQ(vismap::nearest_double(mpq_class(tiny) / 3), 0.0);
  // Past the largest double by more than half its last unit: infinity, as IEEE rounds.
  EXPECT_EQ(vismap::nearest_double(mpq_class(big) * 2), INFINITY);
  EXPECT_EQ(vismap::nearest_double(mpq_class(big) + mpq_class(std::ldexp(1.0, 969))), big);
}

TEST(Api, VerticesAreTheNearestDoublesToTheExactValues) {
  for (const char* file : {"deep_rationals.off", "perspective_box_close.off", "tiny_coords.off", "huge_coords.off"}) {
    vismap::Camera camera;
    camera.dir = vismap::Vec3{-1, -2, -3};
    vismap::Options options;
    options.hidden = true;
    const vismap::Map m = vismap::compute(vismap::read_scene((fs::path(VISMAP_DATA_DIR) / file).string()), camera, options);
    ASSERT_FALSE(m.vertices().empty()) << file;
    for (std::uint32_t i = 0; i < m.vertices().size(); ++i) {
      const vismap::ExactPoint e = m.exact(i);
      expect_nearest(mpq_class(e.x), m.vertices()[i].x);
      expect_nearest(mpq_class(e.y), m.vertices()[i].y);
    }
    for (std::size_t i = 0; i < m.hidden().size(); ++i) {
      const auto ends = m.exact_hidden(i);
      expect_nearest(mpq_class(ends[0].x), m.hidden()[i].from.x);
      expect_nearest(mpq_class(ends[1].y), m.hidden()[i].to.y);
    }
  }
}

// Two unit squares, the second above the first and shifted by a half: the
// visible regions and segments follow from the picture.
TEST(Api, SceneBuiltInCode) {
  vismap::Scene s;
  s.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 1}, {1.5, 0.5, 1}, {1.5, 1.5, 1}, {0.5, 1.5, 1}};
  s.faces = {{0, 1, 2, 3}, {4, 5, 6, 7}};
  vismap::Camera camera;
  camera.dir = vismap::Vec3{0, 0, -1};
  vismap::Options options;
  options.hidden = true;
  const vismap::Map m = vismap::compute(s, camera, options);
  ASSERT_EQ(m.regions().size(), 2u);
  EXPECT_EQ(m.regions()[0].face + m.regions()[1].face, 1);   // one region of each square
  // The upper square (its left and lower sides split where the lower square's
  // sides end on them) and the lower one's visible L: 6 corners each.
  EXPECT_EQ(m.regions()[0].outer.size() + m.regions()[1].outer.size(), 6u + 6u);
  EXPECT_EQ(m.segments().size(), 6u + 4u);
  for (const vismap::Segment& seg : m.segments()) EXPECT_EQ(vismap::to_string(seg.kind), std::string("border"));
  ASSERT_EQ(m.hidden().size(), 2u);          // the lower square's corner under the upper one
  EXPECT_TRUE(m.has_hidden());
  EXPECT_FALSE(m.perspective());
  EXPECT_EQ(m.scene_faces(), 2u);
}

// A 4 x 4 square at z = 0 with a hole given by `hole` (vertex ids 4 on), seen from above.
vismap::Scene plate(std::vector<vismap::Vec3> hole_corners, std::vector<vismap::IndexRing> holes) {
  vismap::Scene s;
  s.file = "plate";
  s.vertices = {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}};
  s.vertices.insert(s.vertices.end(), hole_corners.begin(), hole_corners.end());
  s.faces = {{0, 1, 2, 3}};
  s.holes = {std::move(holes)};
  return s;
}

// The map's JSON up to its free-form stats (which count the triangles made).
std::string json_from_above(const vismap::Scene& s) {
  vismap::Camera camera;
  camera.dir = vismap::Vec3{-1, -2, -3};
  vismap::Options options;
  options.hidden = true;
  const std::string json = vismap::compute(s, camera, options).to_json();
  return json.substr(0, json.find("\"stats\""));
}

TEST(Holes, AHoleIsPartOfTheMapWhicheverWayItTurnsAndWhereverItStarts) {
  const std::vector<vismap::Vec3> square{{1, 1, 0}, {2, 1, 0}, {2, 2, 0}, {1, 2, 0}};
  const std::string ccw = json_from_above(plate(square, {{4, 5, 6, 7}}));
  EXPECT_EQ(json_from_above(plate(square, {{7, 6, 5, 4}})), ccw);
  EXPECT_EQ(json_from_above(plate(square, {{6, 7, 4, 5}})), ccw);
  // One region with one hole of four corners; the hole's four sides are border lines.
  vismap::Camera camera;
  camera.dir = vismap::Vec3{0, 0, -1};
  const vismap::Map m = vismap::compute(plate(square, {{4, 5, 6, 7}}), camera);
  ASSERT_EQ(m.regions().size(), 1u);
  ASSERT_EQ(m.regions()[0].holes.size(), 1u);
  EXPECT_EQ(m.regions()[0].holes[0].size(), 4u);
  EXPECT_EQ(m.segments().size(), 8u);
  // Without the hole, the square alone.
  EXPECT_NE(json_from_above(plate(square, {})), ccw);
}

TEST(Holes, WhatAFaceWithHolesMayNotBeIsRefusedNamingTheFace) {
  auto refusal = [](const vismap::Scene& s) -> std::string {
    try {
      json_from_above(s);
    } catch (const vismap::InputError& e) {
      return e.what();
    }
    return "";
  };
  auto expect = [&](const vismap::Scene& s, const std::string& needle) {
    const std::string what = refusal(s);
    EXPECT_EQ(what.rfind("plate: face 0 ", 0), 0u) << what;
    EXPECT_NE(what.find(needle), std::string::npos) << what;
  };
  expect(plate({{1, 1, 0}, {2, 1, 0}, {2, 2, 0.5}, {1, 2, 0}}, {{4, 5, 6, 7}}), "must be planar");
  expect(plate({{1, 1, 0}, {2, 1, 0}, {3, 1, 0}}, {{4, 5, 6}}), "hole 0 with no area");
  expect(plate({{5, 1, 0}, {6, 1, 0}, {6, 2, 0}}, {{4, 5, 6}}), "not inside the outer ring");                 // outside
  expect(plate({{1, 1, 0}, {3, 1, 0}, {3, 3, 0}, {1.5, 1.5, 0}, {2.5, 1.5, 0}, {2.5, 2.5, 0}},
               {{4, 5, 6}, {7, 8, 9}}), "cross");                                                           // nested
  expect(plate({{1, 1, 0}, {5, 1, 0}, {5, 2, 0}}, {{4, 5, 6}}), "cross");                                   // crossing
  expect(plate({{1, 1, 0}, {2, 1, 0}, {1, 2, 0}, {2, 2, 0}}, {{4, 5, 6, 7}}), "crosses or touches itself");   // a bow tie
  expect(plate({{2, 0, 0}, {3, 1, 0}, {1, 1, 0}}, {{4, 5, 6}}), "touches");                                 // on an edge
  // Sharing a corner with the outer ring is allowed; so is a degenerate outer ring (dropped).
  EXPECT_EQ(refusal(plate({{3, 3, 0}, {3.5, 3, 0}}, {{2, 4, 5}})), "");
  vismap::Scene flat = plate({{1, 1, 0}, {2, 1, 0}, {2, 2, 0}}, {{4, 5, 6}});
  flat.vertices[2] = {2, 0, 0};
  flat.vertices[3] = {3, 0, 0};
  EXPECT_EQ(refusal(flat), "");
}

TEST(Api, ErrorsAreExceptionsThatNameNoFlag) {
  auto expect_message = [](const std::string& what, const std::string& needle) {
    EXPECT_NE(what.find(needle), std::string::npos) << what;
    EXPECT_EQ(what.find("--"), std::string::npos) << "a flag in the library's message: " << what;
  };
  try {
    vismap::read_scene("/nonexistent/none.off");
    ADD_FAILURE() << "no error for a missing file";
  } catch (const vismap::InputError& e) {
    expect_message(e.what(), "none.off");
  }
  try {
    vismap::read_scene("scene.txt");
    ADD_FAILURE() << "no error for an unknown extension";
  } catch (const vismap::InputError& e) {
    expect_message(e.what(), "unknown file extension");
  }
  vismap::Scene s;
  s.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  s.faces = {{0, 1, 2}};
  vismap::Camera bad;
  bad.eye = bad.target = vismap::Vec3{1, 1, 1};
  try {
    vismap::compute(s, bad);
    ADD_FAILURE() << "no error for an eye on its target";
  } catch (const std::invalid_argument& e) {
    expect_message(e.what(), "eye and the target must differ");
  }
  bad = {};
  bad.dir = vismap::Vec3{0, 0, -1};
  bad.fov_deg = 30;
  EXPECT_THROW(vismap::compute(s, bad), std::invalid_argument);
  const vismap::Map m = vismap::compute(s);
  vismap::DrawingOptions d;
  d.style = "pastel";
  try {
    m.drawing(d);
    ADD_FAILURE() << "no error for an unknown style";
  } catch (const std::invalid_argument& e) {
    expect_message(e.what(), "pastel");
  }
  d = {};
  d.scale = "1:10";   // without a page
  EXPECT_THROW(m.drawing(d), std::invalid_argument);
  EXPECT_THROW(m.write((temp_dir() / "map.txt").string()), std::invalid_argument);
  const fs::path missing = temp_dir() / "no_such_folder" / "map.json";
  EXPECT_THROW(m.write(missing.string()), std::runtime_error);
  EXPECT_FALSE(fs::exists(missing.parent_path()));
}

TEST(Api, WritesByExtensionWhatItGives) {
  const vismap::Map m = vismap::compute(vismap::read_scene((fs::path(VISMAP_DATA_DIR) / "interpenetrating_boxes.off").string()));
  vismap::DrawingOptions d;
  d.style = "technical";
  d.page = "a4";
  for (const std::string ext : {"json", "svg", "dxf"}) {
    const fs::path out = temp_dir() / ("map." + ext);
    m.write(out.string(), d);
    EXPECT_EQ(slurp(out), ext == "json" ? m.to_json() : m.drawing(d, ext)) << ext;
  }
  EXPECT_NE(m.drawing(d).find("mm\" height=\""), std::string::npos) << "the page option did not reach the drawing";
}

}  // namespace
