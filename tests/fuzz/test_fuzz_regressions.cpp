// Replays every seed and every finding of the fuzz targets through the same
// harness the fuzzers run (tests/fuzz/fuzz_harness.cpp), so the suite keeps
// each finding fixed without clang. A failure aborts with the reproducer.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/fuzz/fuzz_harness.h"
#include "tests/run_child.h"

namespace {

namespace fs = std::filesystem;
const fs::path kDir = VISMAP_FUZZ_DIR;

using vismap_test::slurp;

// The inputs of one target: its seed corpus and its regressions, sorted.
std::vector<fs::path> inputs(const std::string& target) {
  std::vector<fs::path> v;
  for (const char* where : {"corpus", "regressions"}) {
    const fs::path dir = kDir / where / target;
    if (!fs::is_directory(dir)) continue;
    for (const auto& e : fs::directory_iterator(dir))
      if (e.is_regular_file()) v.push_back(e.path());
  }
  std::sort(v.begin(), v.end());
  return v;
}

const std::uint8_t* bytes(const std::string& s) { return reinterpret_cast<const std::uint8_t*>(s.data()); }

class Reader : public ::testing::TestWithParam<std::string> {};

TEST_P(Reader, SeedsAndFindingsReadOrFailCleanly) {
  const std::string format = GetParam();
  const auto files = inputs("read_" + format);
  EXPECT_GE(files.size(), 3u);
  for (const fs::path& f : files) {
    SCOPED_TRACE(f.string());
    const std::string data = slurp(f);
    vismap_fuzz::check_reader(bytes(data), data.size(), format);
  }
}

INSTANTIATE_TEST_SUITE_P(Fuzz, Reader, ::testing::Values("off", "obj", "stl", "ply"));

// The three engines, whose maps must be verified and identical.
TEST(Pipeline, SeedsAndFindingsGiveVerifiedMaps) {
  const auto files = inputs("pipeline");
  EXPECT_GE(files.size(), 5u);
  for (const fs::path& f : files) {
    SCOPED_TRACE(f.string());
    const std::string data = slurp(f);
    vismap_fuzz::check_pipeline(bytes(data), data.size(), vismap_fuzz::Engines::All);
  }
}

TEST(Pipeline, TinyScenesAreTinyAndRoundTripThroughOff) {
  std::uint64_t seed = 3;
  for (int i = 0; i < 200; ++i) {
    std::string data;
    for (int k = 0; k < 80; ++k) {
      seed = seed * 6364136223846793005ull + 1442695040888963407ull;
      data += static_cast<char>(seed >> 56);
    }
    const vismap_fuzz::TinyCase t = vismap_fuzz::decode_tiny(bytes(data), data.size());
    EXPECT_LE(t.scene.faces.size(), 14u);      // with a seam's two squares
    EXPECT_LE(t.scene.vertices.size(), 22u);
    const vismap::Scene back = vismap::read_scene_bytes(vismap_fuzz::to_off(t.scene), "x.off", "off");
    EXPECT_EQ(back.faces, t.scene.faces);
    ASSERT_EQ(back.vertices.size(), t.scene.vertices.size());
    for (std::size_t v = 0; v < back.vertices.size(); ++v) {
      EXPECT_EQ(back.vertices[v].x, t.scene.vertices[v].x);
      EXPECT_EQ(back.vertices[v].y, t.scene.vertices[v].y);
      EXPECT_EQ(back.vertices[v].z, t.scene.vertices[v].z);
    }
  }
  // Every input decodes, the empty one included.
  EXPECT_FALSE(vismap_fuzz::decode_tiny(nullptr, 0).scene.faces.empty());
}

// ---- findings kept as OFF scenes with their command lines ------------------------------

struct SceneCase {
  std::string file, args, verify_args;
};

// "file<TAB>vismap options<TAB>vismap verify options" lines; '#' comments.
std::vector<SceneCase> scene_cases(const fs::path& list) {
  std::vector<SceneCase> v;
  for (const std::string& line : vismap_test::case_lines(list)) {
    SceneCase c;
    std::istringstream s(line);
    std::getline(s, c.file, '\t');
    std::getline(s, c.args, '\t');
    std::getline(s, c.verify_args, '\t');
    v.push_back(c);
  }
  return v;
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> v;
  std::istringstream in(s);
  for (std::string w; in >> w;) v.push_back(w);
  return v;
}

// vismap on the scene, then vismap verify (and verify --strict) on its map: all
// must succeed.
void expect_verified(const fs::path& dir, const SceneCase& c) {
  SCOPED_TRACE(c.file + " " + c.args);
  vismap_test::TempDir tmp("fuzz_case");
  const std::string scene = (dir / c.file).string(), map = tmp.file("m.json");
  std::vector<std::string> run = {VISMAP_BIN, scene, "--json", map};
  for (const std::string& w : split(c.args)) run.push_back(w);
  vismap_test::Result r = vismap_test::run(run, tmp.path());
  ASSERT_EQ(r.status, 0) << r.err;
  std::vector<std::string> check = {VISMAP_BIN, "verify", scene, map};
  for (const std::string& w : split(c.verify_args)) check.push_back(w);
  r = vismap_test::run(check, tmp.path());
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  check.push_back("--strict");   // and every stretch of every line
  r = vismap_test::run(check, tmp.path());
  EXPECT_EQ(r.status, 0) << "--strict\n" << r.out << r.err;
}

TEST(SceneFindings, FixedFindingsStayFixed) {
  for (const SceneCase& c : scene_cases(kDir / "regressions" / "cases.txt")) expect_verified(kDir / "regressions", c);
}

// Findings not fixed yet (see tests/fuzz/open/cases.txt): run with
// --gtest_also_run_disabled_tests; each fails until its engine is fixed.
TEST(SceneFindings, DISABLED_OpenFindings) {
  for (const SceneCase& c : scene_cases(kDir / "open" / "cases.txt")) expect_verified(kDir / "open", c);
}

}  // namespace
