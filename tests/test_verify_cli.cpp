// `vismap verify` through the command line, as a user runs it: it accepts the
// engine's maps of the whole degenerate corpus, and rejects each kind of wrong
// map (a relabelled region, a hidden line added, a visible line removed, a wrong
// kind, a non-canonical number) with exit status 1 and a located message; bad
// usage is 2, unreadable input 1. The old tool name still works.
#include <gtest/gtest.h>
#include <cctype>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/run_child.h"

namespace {

namespace fs = std::filesystem;
using vismap_test::Result;
using vismap_test::TempDir;

const std::string kBin = VISMAP_BIN;
const std::string kTool = VISMAP_CHECK_TOOL;
const fs::path kData = VISMAP_DATA_DIR;

std::vector<std::string> words(const std::string& s) {
  std::vector<std::string> v;
  std::size_t i = 0;
  while (i < s.size()) {
    const std::size_t j = s.find(' ', i);
    if (j != i) v.push_back(s.substr(i, j == std::string::npos ? std::string::npos : j - i));
    if (j == std::string::npos) break;
    i = j + 1;
  }
  return v;
}

Result vismap(const TempDir& dir, std::vector<std::string> args, const std::string& in = "") {
  args.insert(args.begin(), kBin);
  return vismap_test::run(args, dir.path(), in);
}

Result verify(const TempDir& dir, const std::string& scene, const std::string& map,
              const std::vector<std::string>& extra = {}) {
  std::vector<std::string> args = {"verify", scene, map};
  args.insert(args.end(), extra.begin(), extra.end());
  return vismap(dir, args);
}

std::string both(const Result& r) { return "stdout:\n" + r.out + "stderr:\n" + r.err; }

// ---- usage and unreadable input ------------------------------------------------------

TEST(VerifyCli, HelpAndUsage) {
  TempDir dir("verify_usage");
  Result r = vismap(dir, {"verify", "--help"});
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("usage: vismap verify SCENE MAP.json"), std::string::npos) << r.out;
  EXPECT_NE(vismap(dir, {"--help"}).out.find("vismap verify"), std::string::npos);
  r = vismap(dir, {"--version"});
  EXPECT_EQ(r.status, 0) << both(r);
  EXPECT_TRUE(r.out.rfind("vismap ", 0) == 0 && r.out.size() > 7 && std::isdigit(static_cast<unsigned char>(r.out[7])))
      << r.out;   // (CMakeLists.txt's project version)
  EXPECT_NE(r.out.find("GMP "), std::string::npos) << r.out;

  const std::string scene = (kData / "t_junction.off").string();
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"verify"}, {"verify", scene}, {"verify", scene, "m.json", "extra"},
        {"verify", "--bogus", scene, "m.json"}, {"verify", scene, "m.json", "--samples", "x"},
        {"verify", scene, "m.json", "--samples", "-1"}, {"verify", scene, "m.json", "--seed"},
        {"verify", scene, "m.json", "--crease", "200"}, {"verify", scene, "m.json", "--format", "gltf"},
        {"verify", scene, "m.json", "--max-memory", "lots"}, {"verify", "-", "-"}}) {
    r = vismap(dir, args);
    EXPECT_EQ(r.status, 2) << args.back() << "\n" << both(r);
    EXPECT_NE(r.err.find("vismap verify: "), std::string::npos) << both(r);
    EXPECT_NE(r.err.find("--help"), std::string::npos) << both(r);
  }
}

TEST(VerifyCli, UnreadableInputIsStatusOneNamingTheFile) {
  TempDir dir("verify_input");
  const std::string scene = (kData / "t_junction.off").string();
  const std::string map = dir.file("m.json");
  ASSERT_EQ(vismap(dir, {scene, "--dir", "0,0,-1", "--json", map}).status, 0);

  Result r = verify(dir, dir.file("missing.off"), map);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find(dir.file("missing.off") + ": cannot open file"), std::string::npos) << both(r);

  r = verify(dir, scene, dir.file("missing.json"));
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find(dir.file("missing.json") + ": cannot open file"), std::string::npos) << both(r);

  r = verify(dir, scene, dir.path().string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("is a directory"), std::string::npos) << both(r);

  const std::string bad_scene = dir.write("bad.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n");
  r = verify(dir, bad_scene, map);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find(bad_scene + ":"), std::string::npos) << both(r);

  for (const std::string& text : {std::string(""), std::string("{"), std::string("[]"), std::string("\x01\xff garbage")}) {
    r = verify(dir, scene, dir.write("junk.json", text));
    EXPECT_EQ(r.status, 1) << both(r);
    EXPECT_NE(r.out.find("FAIL format"), std::string::npos) << both(r);
    EXPECT_NE(r.out.find("FAILED: "), std::string::npos) << both(r);
  }
}

// ---- the engine's maps of the corpus are accepted ---------------------------------------

TEST(VerifyCli, AcceptsTheEngineMapsOfTheCorpus) {
  TempDir dir("verify_corpus");
  int n = 0;
  for (const std::string& line : vismap_test::case_lines(kData / "cases.txt")) {
    const auto [file, rest] = vismap_test::split_case(line);
    const std::vector<std::string> args = words(rest);
    const std::string scene = (kData / file).string(), map = dir.file(file + ".json");
    std::vector<std::string> run = {scene, "--json", map};
    run.insert(run.end(), args.begin(), args.end());
    Result r = vismap(dir, run);
    ASSERT_EQ(r.status, 0) << file << "\n" << both(r);
    // The checker must be told the line options the map was made with.
    std::vector<std::string> extra = {"--samples", "500"};
    for (std::size_t i = 0; i < args.size(); ++i) {
      if (args[i] == "--smooth") extra.push_back("--smooth");
      if (args[i] == "--crease") extra.insert(extra.end(), {"--crease", args[i + 1]});
    }
    for (bool strict : {false, true}) {
      if (strict) extra.push_back("--strict");
      r = verify(dir, scene, map, extra);
      EXPECT_EQ(r.status, 0) << file << (strict ? " (--strict)" : "") << "\n" << both(r);
      EXPECT_EQ(r.out.rfind("OK: ", 0), 0u) << file << "\n" << both(r);
    }
    ++n;
  }
  EXPECT_GE(n, 20);
}

TEST(VerifyCli, MapOnStandardInputAndOldToolName) {
  TempDir dir("verify_stdin");
  const std::string scene = (kData / "shared_edge_crease.off").string(), map = dir.file("m.json");
  ASSERT_EQ(vismap(dir, {scene, "--dir", "0,0,-1", "--json", map}).status, 0);
  Result r = vismap(dir, {"verify", scene, "-"}, map);
  EXPECT_EQ(r.status, 0) << both(r);
  r = vismap_test::run({kTool, scene, map}, dir.path());
  EXPECT_EQ(r.status, 0) << both(r);
  EXPECT_EQ(r.out.rfind("OK: ", 0), 0u) << both(r);
}

// ---- each kind of wrong map is rejected ----------------------------------------------------

// Face 0, the square [0,2]^2 at z = 0, lies under face 1, [1,3]^2 at z = 1;
// seen from above, face 0's edges x = 2 and y = 2 are hidden for 1 < y, x <= 2.
const char* kTwoSquares = "OFF\n8 2 0\n0 0 0\n2 0 0\n2 2 0\n0 2 0\n1 1 1\n3 1 1\n3 3 1\n1 3 1\n4 0 1 2 3\n4 4 5 6 7\n";

struct Mutation {
  const char* name;
  std::string scene;        // "" = the two squares; else a corpus file
  std::string find, replace;
  std::string expect;       // a FAIL line starts with this
};

std::string replace_once(std::string s, const std::string& find, const std::string& with) {
  const auto at = s.find(find);
  if (at == std::string::npos) return "";
  return s.replace(at, find.size(), with);
}

TEST(VerifyCli, RejectsEachKindOfWrongMap) {
  TempDir dir("verify_mutations");
  const std::string two = dir.write("two.off", kTwoSquares);
  const std::string seg20 = R"({"from":["2","0"],"to":["2","1"],"kind":"border","faces":[0]})";
  const std::string seg10 = R"({"from":["1","0"],"to":["2","0"],"kind":"border","faces":[1]})";
  const std::vector<Mutation> mutations = {
      {"relabelled region", "", R"({"face":0,)", R"({"face":1,)", "FAIL regions: "},
      {"hidden line added", "", seg20, seg20 + ",\n" + R"({"from":["2","1"],"to":["2","2"],"kind":"border","faces":[0]})",
       "FAIL segment: "},
      {"visible line removed", "", R"({"from":["0","0"],"to":["0","2"],"kind":"border","faces":[0]},)" "\n", "",
       "FAIL coverage: "},
      {"wrong kind", "shared_edge_crease.off", R"("kind":"crease")", R"("kind":"silhouette")", "FAIL segment: "},
      {"non-canonical number", "", R"(["2","0"])", R"(["4/2","0"])", "FAIL format: "},
      {"negative zero", "", R"(["0","0"])", R"(["-0","0"])", "FAIL format: "},
      {"wrong faces", "shared_edge_crease.off", R"("faces":[0,1])", R"("faces":[0])", "FAIL "},
      // A farther border drawn where a nearer smooth seam (not drawn) is the first
      // visible line: what both engines wrote before issue 17.
      {"line under a smooth seam drawn", "seam_over_border.off", seg10,
       seg10 + ",\n" + R"({"from":["1","1/5"],"to":["1","4/5"],"kind":"border","faces":[2]})",
       "FAIL segment: "},
  };
  for (const Mutation& m : mutations) {
    SCOPED_TRACE(m.name);
    const std::string scene = m.scene.empty() ? two : (kData / m.scene).string();
    const std::string good = dir.file("good.json"), bad = dir.file("bad.json");
    ASSERT_EQ(vismap(dir, {scene, "--dir", "0,0,-1", "--json", good}).status, 0);
    ASSERT_EQ(verify(dir, scene, good).status, 0);
    const std::string text = replace_once(vismap_test::slurp(good), m.find, m.replace);
    ASSERT_FALSE(text.empty()) << "the engine's map no longer contains " << m.find;
    std::ofstream(bad, std::ios::binary) << text;
    const Result r = verify(dir, scene, bad);
    EXPECT_EQ(r.status, 1) << both(r);
    EXPECT_NE(r.out.find(m.expect), std::string::npos) << "wanted '" << m.expect << "'\n" << both(r);
    EXPECT_NE(r.out.find("FAILED: "), std::string::npos) << both(r);
    EXPECT_EQ(verify(dir, scene, bad, {"--strict"}).status, 1) << "--strict accepts it";
  }
}

// Holes are part of the scene the checker reads: the map of a face with its
// holes filled is refused against the scene with holes, and the map with holes
// against the scene without them (the same vertices; every hole's ring a face's).
TEST(VerifyCli, HolesMatter) {
  TempDir dir("verify_holes");
  const std::string with_holes = (kData / "holes_block.vmscene.json").string();
  std::string filled = vismap_test::slurp(with_holes);
  // {"outer": [..], "holes": [[..]]} -> [..]: the outer ring alone.
  for (std::size_t at; (at = filled.find("{\"outer\": ")) != std::string::npos;) {
    const std::size_t holes = filled.find(", \"holes\"", at), end = filled.find("]]}", at);
    filled = filled.substr(0, at) + filled.substr(at + 10, holes - at - 10) + filled.substr(end + 3);
  }
  const std::string without = dir.write("holes_block.vmscene.json", filled);
  const std::string map_with = dir.file("with.json"), map_without = dir.file("without.json");
  ASSERT_EQ(vismap(dir, {with_holes, "--dir", "-1,-2,-4", "--hidden", "--json", map_with}).status, 0);
  ASSERT_EQ(vismap(dir, {without, "--dir", "-1,-2,-4", "--hidden", "--json", map_without}).status, 0);
  ASSERT_EQ(verify(dir, with_holes, map_with).status, 0);
  ASSERT_EQ(verify(dir, without, map_without).status, 0);
  const Result r = verify(dir, with_holes, map_without), s = verify(dir, without, map_with);
  EXPECT_EQ(r.status, 1) << both(r);
  EXPECT_EQ(s.status, 1) << both(s);
}

// --strict recomputes, at every stretch of every line, which line the map must
// draw there: under the issue-17 seam it finds the border drawn where the seam
// (not drawn) is the first visible line, and says so.
TEST(VerifyCli, StrictModeNamesTheStretch) {
  TempDir dir("verify_strict");
  const std::string scene = (kData / "seam_over_border.off").string(), good = dir.file("good.json"),
                    bad = dir.file("bad.json");
  ASSERT_EQ(vismap(dir, {scene, "--dir", "0,0,-1", "--json", good}).status, 0);
  const std::string seg10 = R"({"from":["1","0"],"to":["2","0"],"kind":"border","faces":[1]})";
  const std::string text = replace_once(
      vismap_test::slurp(good), seg10, seg10 + ",\n" + R"({"from":["1","1/5"],"to":["1","4/5"],"kind":"border","faces":[2]})");
  ASSERT_FALSE(text.empty());
  std::ofstream(bad, std::ios::binary) << text;
  const Result r = verify(dir, scene, bad, {"--strict"});
  EXPECT_EQ(r.status, 1) << both(r);
  EXPECT_NE(r.out.find("FAIL strict: segments["), std::string::npos) << both(r);
  EXPECT_NE(r.out.find("the first visible line there is not drawn (smooth [0,1])"), std::string::npos) << both(r);
}

}  // namespace
