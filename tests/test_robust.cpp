// Robustness of the command line, measured from outside as a user meets it:
// malformed input of every kind is refused quickly and cheaply with a message
// naming the file, status 1 or 2, and no output file; scenes too big for the
// memory limit are refused up front; standard input works; outputs are atomic
// (a failed, killed or interrupted run leaves the old file and no temporary).
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <sstream>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "arrangements/atomic_file.h"
#include "engine/parallel.h"
#include "engine/scene.h"
#include "bench/scene_gen.h"
#include "tests/run_child.h"

namespace {

namespace fs = std::filesystem;
using vismap_test::Result;
using vismap_test::TempDir;

const std::string kBin = VISMAP_BIN;
const fs::path kData = VISMAP_DATA_DIR;

std::string both(const Result& r) { return "stdout:\n" + r.out.substr(0, 2000) + "\nstderr:\n" + r.err; }

// ---- building malformed files -----------------------------------------------------------

template <class T>
void put(std::string& s, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));  // little-endian machine (x86-64, arm64)
  s.append(b, sizeof(T));
}

std::string binary_stl(std::uint32_t count, int triangles, float poison = 0) {
  std::string s(80, '\0');
  put(s, count);
  for (int t = 0; t < triangles; ++t) {
    for (int k = 0; k < 12; ++k) put(s, k == 7 ? poison : static_cast<float>(k % 3));
    put(s, std::uint16_t{0});
  }
  return s;
}

std::string garbage(std::size_t n, std::uint64_t seed) {
  std::string s;
  for (std::size_t i = 0; i < n; ++i) {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    s += static_cast<char>(seed >> 56);
  }
  return s;
}

const std::string kOff = "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 1\n3 0 1 2\n3 0 2 3\n";
const std::string kObj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 1\nf 1 2 3\nf 1 3 4\n";
const std::string kStl =
    "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nendloop\nendfacet\n"
    "endsolid t\n";
const std::string kPlyHead =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
const std::string kPly = kPlyHead + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";

struct Bad {
  std::string name;   // file name, its extension choosing the reader
  std::string bytes;
};

std::vector<Bad> malformed() {
  std::vector<Bad> v = {
      {"empty.off", ""}, {"empty.obj", ""}, {"empty.stl", ""}, {"empty.ply", ""},
      {"garbage.off", garbage(4096, 1)}, {"garbage.obj", garbage(4096, 2)},
      {"garbage.stl", garbage(4096, 3)}, {"garbage.ply", garbage(4096, 4)},
      {"garbage_big.stl", garbage(1 << 20, 5)},
      {"truncated.off", kOff.substr(0, kOff.size() / 2)},
      {"truncated.stl", kStl.substr(0, kStl.size() / 2)},
      {"truncated.ply", kPly.substr(0, kPly.size() - 4)},
      {"truncated_binary.stl", binary_stl(2, 2).substr(0, 120)},
      {"nan.off", "OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n"},
      {"inf.off", "OFF\n3 1 0\n0 0 0\n1 inf 0\n0 1 0\n3 0 1 2\n"},
      {"overflow.obj", "v 0 0 0\nv 1e999 0 0\nv 0 1 0\nf 1 2 3\n"},
      {"nan.obj", "v 0 0 0\nv -nan 0 0\nv 0 1 0\nf 1 2 3\n"},
      {"nan.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 nan\nvertex 1 0 0\nvertex 1 1 0\n"
                  "endloop\nendfacet\nendsolid t\n"},
      {"nan_binary.stl", binary_stl(1, 1, std::numeric_limits<float>::quiet_NaN())},
      {"inf_binary.stl", binary_stl(1, 1, std::numeric_limits<float>::infinity())},
      {"nan.ply", kPlyHead + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n"},
      {"index_range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"},
      {"index_negative.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n"},
      {"index_range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n"},
      {"index_negative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n"},
      {"index_zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"},
      {"index_huge.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999\n"},
      {"index_range.ply", kPlyHead + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"},
      {"index_negative.ply", kPlyHead + "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n"},
      {"absurd_faces.off", "OFF\n3 1000000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"},
      {"absurd_both.off", "OFF\n18446744073709551615 18446744073709551615 0\n"},
      {"absurd_corners.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4000000000 0 1 2\n"},
      {"absurd_count.stl", binary_stl(0xFFFFFFFFu, 1)},
      {"absurd_count.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000000\nproperty float x\n"
                           "property float y\nproperty float z\nend_header\n" + std::string(12, '\0')},
      {"absurd_list.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                          "property float y\nproperty float z\nelement face 1\nproperty list uint int vertex_indices\n"
                          "end_header\n" + std::string(36, '\0') + "\xff\xff\xff\xff"},
      {"unknown.txt", kOff},
      {"no_extension", kOff},
  };
  return v;
}

// ---- malformed files through the command line -----------------------------------------------

// Each is refused with status 1 or 2 and a message naming it, writes nothing,
// and costs at most a few seconds of CPU and a few hundred MiB.
void expect_refused(const std::string& input, const std::string& name_in_message, const TempDir& out,
                    const TempDir& scratch, const std::string& stdin_file = "") {
  vismap_test::Limits lim;
  lim.address_space = 4ull << 30;   // what the program may reserve; the peak is checked below
  lim.cpu_seconds = 20;
  lim.kill_after_seconds = 60;
  const Result r = vismap_test::run({kBin, input, "--json", out.file("out.json"), "-o", out.file("out.svg")},
                                    scratch.path(), stdin_file, lim);
  EXPECT_TRUE(r.exited) << input << " died of signal " << r.status << "\n" << both(r);
  EXPECT_TRUE(r.status == 1 || r.status == 2) << input << ": status " << r.status << "\n" << both(r);
  EXPECT_NE(r.err.find("vismap: " + name_in_message), std::string::npos) << input << "\n" << both(r);
  EXPECT_TRUE(out.names().empty()) << input << " left " << out.names().front();
  for (const std::string& n : out.names()) fs::remove_all(out.path() / n);  // keep the cases independent
  EXPECT_LT(r.cpu_seconds, 5.0) << input;
  EXPECT_LT(r.max_rss, (vismap_test::kAsan ? 1024ull : 300ull) << 20) << input;
}

TEST(Malformed, EveryFileIsRefusedQuicklyNamingItAndWritingNothing) {
  TempDir in("robust_in"), out("robust_out"), scratch("robust_scratch");
  for (const Bad& b : malformed()) {
    SCOPED_TRACE(b.name);
    expect_refused(in.write(b.name, b.bytes), in.file(b.name), out, scratch);
  }
  fs::create_directory(in.path() / "folder.off");
  expect_refused(in.file("folder.off"), in.file("folder.off"), out, scratch);
  expect_refused(in.file("missing.off"), in.file("missing.off"), out, scratch);
  // Standard input: garbage and nothing at all.
  expect_refused("-", "<stdin>", out, scratch, in.write("stdin.bin", garbage(1000, 9)));
  expect_refused("-", "<stdin>", out, scratch, in.write("stdin.empty", ""));
}

TEST(Malformed, BadUsageIsStatusTwoAndWritesNothing) {
  TempDir in("robust_usage_in"), out("robust_usage_out"), scratch("robust_usage_scratch");
  const std::string scene = in.write("ok.off", kOff);
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{}, {scene, "--bogus"}, {scene, "--dir", "0,0"}, {scene, "--dir", "nan,0,1"},
        {scene, "--dir", "0,0,0"}, {scene, "--fov", "180", "--eye", "1,1,1"}, {scene, "--json"},
        {scene, "--format", "gltf"}, {scene, "--max-memory", "0"}, {scene, "--max-memory", "-5G"},
        {scene, "--max-memory", "8Q"}, {scene, scene}, {scene, "--style", "sketchy"}, {scene, "--line", "edges:width=1"},
        {scene, "--line", "hidden:dash=2"}, {scene, "--page", "a5"}, {scene, "--scale", "1:50"},
        {scene, "--scale", "1:0", "--page", "a4"}, {scene, "--margin", "-1"}, {scene, "--shading", "1,2"},
        {scene, "--light", "0,0,0"}}) {
    std::vector<std::string> argv = {kBin};
    argv.insert(argv.end(), args.begin(), args.end());
    argv.insert(argv.end(), {"-o", out.file("out.svg")});
    const Result r = vismap_test::run(argv, scratch.path());
    EXPECT_EQ(r.status, 2) << (args.empty() ? "" : args.back()) << "\n" << both(r);
    EXPECT_EQ(r.err.rfind("vismap: ", 0), 0u) << both(r);
    EXPECT_TRUE(out.names().empty());
  }
  // A drawing format that is not one, and drawing options with no drawing.
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{scene, "-o", out.file("out.gif")},
        {scene, "--style", "technical", "--json", out.file("out.json")},
        {scene, "--page", "a4", "--json", out.file("out.json")}}) {
    std::vector<std::string> argv = {kBin};
    argv.insert(argv.end(), args.begin(), args.end());
    const Result r = vismap_test::run(argv, scratch.path());
    EXPECT_EQ(r.status, 2) << args[1] << "\n" << both(r);
    EXPECT_TRUE(out.names().empty());
  }
}

// ---- drawings: the format by the file's extension ----------------------------------------

TEST(Drawings, EachFormatByItsExtension) {
  TempDir in("drawing_in"), out("drawing_out"), scratch("drawing_scratch");
  const std::string scene = in.write("ok.off", kOff);
  const std::vector<std::pair<std::string, std::string>> formats = {
      {"svg", "<svg"}, {"dxf", "0\nSECTION\n"}, {"pdf", "%PDF-"}, {"eps", "%!PS-Adobe-3.0 EPSF"}, {"png", "\x89PNG"}};
  for (const auto& [ext, magic] : formats) {
    const std::string file = out.file("drawing." + ext);
    const Result r = vismap_test::run({kBin, scene, "--hidden", "--style", "technical", "--page", "a4", "-o", file}, scratch.path());
    ASSERT_EQ(r.status, 0) << ext << "\n" << both(r);
    EXPECT_EQ(vismap_test::slurp(file).rfind(magic, 0), 0u) << ext << ": not the format its name says";
  }
}

// ---- memory limits -------------------------------------------------------------------------

TEST(Limits, AHeaderClaimingABillionFacesIsRefusedUpFront) {
  TempDir in("limits_in"), out("limits_out"), scratch("limits_scratch");
  const std::string huge = in.write("huge.off", "OFF\n3 1000000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  const Result r = vismap_test::run({kBin, huge, "--max-memory", "8G", "--json", out.file("m.json")}, scratch.path());
  EXPECT_EQ(r.status, 1) << both(r);
  // The size it would need and the limit, both in the message.
  EXPECT_NE(r.err.find(huge + ":2: the header's 3 vertices and 1000000000 faces would need about "),
            std::string::npos) << r.err;
  EXPECT_NE(r.err.find(" TiB of memory, more than the memory limit of 8.0 GiB\n(--max-memory sets the limit)"), std::string::npos)
      << r.err;
  EXPECT_LT(r.cpu_seconds, 1.0);
  EXPECT_TRUE(out.names().empty());
}

TEST(Limits, TheMemoryLimitAppliesToEveryFormatAndToTheFileSize) {
  TempDir in("limits2_in"), out("limits2_out"), scratch("limits2_scratch");
  auto refused = [&](const std::string& file, const std::string& limit, const std::string& text) {
    const Result r = vismap_test::run({kBin, file, "--max-memory", limit, "--json", out.file("m.json")},
                                      scratch.path());
    EXPECT_EQ(r.status, 1) << file << "\n" << both(r);
    EXPECT_NE(r.err.find(file + ":"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(text), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--max-memory"), std::string::npos) << r.err;
    EXPECT_TRUE(out.names().empty());
  };
  // A small scene fits in the default limit and in 1G, not in 1M (the engine's base need).
  const std::string off = in.write("ok.off", kOff);
  EXPECT_EQ(vismap_test::run({kBin, off, "--max-memory", "1G", "--json", out.file("m.json")}, scratch.path()).status, 0);
  fs::remove(out.file("m.json"));
  refused(off, "1M", "more than the memory limit of 1.0 MiB");
  refused(in.write("ok.obj", kObj), "1M", "more than the memory limit of 1.0 MiB");
  refused(in.write("ok.stl", kStl), "1M", "more than the memory limit of 1.0 MiB");
  refused(in.write("ok.ply", kPly), "1M", "more than the memory limit of 1.0 MiB");
  refused(in.write("b.stl", binary_stl(1, 1)), "1M", "more than the memory limit of 1.0 MiB");
  // A file bigger than the limit is not even read.
  refused(in.write("big.off", kOff + std::string(3 << 20, '#')), "2M", "more than the memory limit of 2.0 MiB");
}

TEST(Limits, SizesParseAndPrint) {
  std::uint64_t b = 0;
  EXPECT_TRUE(vismap::parse_memory_size("8G", b));
  EXPECT_EQ(b, 8ull << 30);
  EXPECT_TRUE(vismap::parse_memory_size("512MiB", b));
  EXPECT_EQ(b, 512ull << 20);
  EXPECT_TRUE(vismap::parse_memory_size("1.5g", b));
  EXPECT_EQ(b, 3ull << 29);
  EXPECT_TRUE(vismap::parse_memory_size("4096", b));
  EXPECT_EQ(b, 4096u);
  EXPECT_TRUE(vismap::parse_memory_size("64KB", b));
  EXPECT_EQ(b, 64u << 10);
  for (const char* bad : {"", "G", "0", "-1G", "8Q", "8GG", "1e3", " 8G", "99999999999T"})
    EXPECT_FALSE(vismap::parse_memory_size(bad, b)) << bad;
  EXPECT_EQ(vismap::format_bytes(812), "812 bytes");
  EXPECT_EQ(vismap::format_bytes(8ull << 30), "8.0 GiB");
  EXPECT_EQ(vismap::format_bytes(300ull << 20), "300 MiB");
  EXPECT_GT(vismap::default_max_memory(), 64ull << 20);
  // The estimate saturates instead of overflowing on absurd counts.
  EXPECT_EQ(vismap::estimate_memory(0, ~0ull, ~0ull, ~0ull), ~0ull);
  EXPECT_LT(vismap::estimate_memory(1000, 4, 2, 6), 100ull << 20);
}

// ---- standard input ----------------------------------------------------------------------------

TEST(Stdin, SceneFromStandardInputByContentOrFormat) {
  TempDir in("stdin_in"), scratch("stdin_scratch");
  const std::string file = in.write("s.off", kOff);
  const Result from_file = vismap_test::run({kBin, file, "--dir", "0,0,-1", "--json", "-"}, scratch.path());
  ASSERT_EQ(from_file.status, 0) << both(from_file);
  Result r = vismap_test::run({kBin, "-", "--dir", "0,0,-1", "--json", "-"}, scratch.path(), file);
  ASSERT_EQ(r.status, 0) << both(r);
  // The same map; only the scene's name differs.
  std::string expected = from_file.out;
  expected.replace(expected.find(file), file.size(), "<stdin>");
  EXPECT_EQ(r.out, expected);

  const std::string obj = in.write("s.obj", kObj), stl = in.write("s.stl", kStl), ply = in.write("s.ply", kPly);
  for (const std::string& f : {obj, stl, ply}) {
    r = vismap_test::run({kBin, "-", "--dir", "0,0,-1", "--json", "-"}, scratch.path(), f);
    EXPECT_EQ(r.status, 0) << f << "\n" << both(r);
    EXPECT_NE(r.out.find("\"file\":\"<stdin>\""), std::string::npos);
  }
  r = vismap_test::run({kBin, "-", "--dir", "0,0,-1", "--json", "-"}, scratch.path(), in.write("b.stl", binary_stl(1, 1)));
  EXPECT_EQ(r.status, 0) << both(r);
  // --format names it when the content cannot: OBJ with only a polygon record first.
  const std::string odd = in.write("odd", "# made by hand\nvertex_colors off\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  r = vismap_test::run({kBin, "-", "--json", "-"}, scratch.path(), odd);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("<stdin>: cannot tell the mesh format"), std::string::npos) << r.err;
  r = vismap_test::run({kBin, "-", "--format", "obj", "--json", "-"}, scratch.path(), odd);
  EXPECT_EQ(r.status, 0) << both(r);
  // --format also overrides a file's extension.
  r = vismap_test::run({kBin, odd, "--format", "obj", "--json", "-"}, scratch.path());
  EXPECT_EQ(r.status, 0) << both(r);
  r = vismap_test::run({kBin, file, "--format", "ply", "--json", "-"}, scratch.path());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find(file + ":1: not a PLY file"), std::string::npos) << r.err;
}

TEST(Stdin, SniffFormat) {
  EXPECT_EQ(vismap::sniff_format("OFF\n0 0 0\n"), "off");
  EXPECT_EQ(vismap::sniff_format("# comment\n\n  OFF 3 1 0\n"), "off");
  EXPECT_EQ(vismap::sniff_format("# colours\nCOFF\n3 1 0\n"), "off");
  EXPECT_EQ(vismap::sniff_format("STCNOFF 0 0 0\n"), "off");
  EXPECT_EQ(vismap::sniff_format("ply\r\nformat ascii 1.0\n"), "ply");
  EXPECT_EQ(vismap::sniff_format("solid x\n"), "stl");
  EXPECT_EQ(vismap::sniff_format(binary_stl(1, 1)), "stl");
  EXPECT_EQ(vismap::sniff_format("# blender\nmtllib a.mtl\no Cube\nv 1 1 1\n"), "obj");
  EXPECT_EQ(vismap::sniff_format("v 1 1 1\n"), "obj");
  EXPECT_EQ(vismap::sniff_format(""), "");
  EXPECT_EQ(vismap::sniff_format("hello world"), "");
  EXPECT_EQ(vismap::sniff_format("OFFICE\n"), "");
}

// ---- atomic output -------------------------------------------------------------------------------

std::string big_scene(int squares) {
  // Random unit-ish squares at random heights: a few seconds of work.
  std::string s = "OFF\n" + std::to_string(4 * squares) + " " + std::to_string(squares) + " 0\n";
  std::uint64_t seed = 7;
  auto rnd = [&] {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(seed >> 11) / 9007199254740992.0;
  };
  const double side = std::sqrt(3.0 / squares);
  for (int i = 0; i < squares; ++i) {
    const double x = rnd(), y = rnd(), z = rnd();
    for (auto [dx, dy] : {std::pair{0.0, 0.0}, {side, 0.0}, {side, side}, {0.0, side}})
      s += std::to_string(x + dx) + " " + std::to_string(y + dy) + " " + std::to_string(z) + "\n";
  }
  for (int i = 0; i < squares; ++i)
    s += "4 " + std::to_string(4 * i) + " " + std::to_string(4 * i + 1) + " " + std::to_string(4 * i + 2) + " " +
         std::to_string(4 * i + 3) + "\n";
  return s;
}

TEST(Atomic, AFailedRunLeavesTheOldFilesAndNoTemporary) {
  TempDir in("atomic_in"), out("atomic_out"), scratch("atomic_scratch");
  const std::string json = out.write("map.json", "old json"), svg = out.write("map.svg", "old svg");
  const std::string good = in.write("ok.off", kOff), bad = in.write("bad.off", "OFF\n3 1 0\n0 0 0\n");
  // Bad input.
  Result r = vismap_test::run({kBin, bad, "--json", json, "-o", svg}, scratch.path());
  EXPECT_EQ(r.status, 1);
  // One output that cannot be written: neither is replaced.
  r = vismap_test::run({kBin, good, "--json", json, "-o", (out.path() / "no" / "such" / "dir.svg").string()},
                       scratch.path());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("no/such/dir.svg: cannot write"), std::string::npos) << r.err;
  r = vismap_test::run({kBin, good, "--json", json, "-o", out.path().string()}, scratch.path());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find(out.path().string() + ": cannot write: is a directory"), std::string::npos) << r.err;
  EXPECT_EQ(vismap_test::slurp(json), "old json");
  EXPECT_EQ(vismap_test::slurp(svg), "old svg");
  EXPECT_EQ(out.names(), (std::vector<std::string>{"map.json", "map.svg"}));
  // A good run replaces both, with the usual permissions.
  r = vismap_test::run({kBin, good, "--json", json, "-o", svg}, scratch.path());
  EXPECT_EQ(r.status, 0) << both(r);
  EXPECT_EQ(vismap_test::slurp(json).rfind("{\"format\":\"vismap\"", 0), 0u);
  EXPECT_EQ(vismap_test::slurp(svg).rfind("<svg", 0), 0u);
  EXPECT_EQ(out.names(), (std::vector<std::string>{"map.json", "map.svg"}));
  struct stat st{};
  ASSERT_EQ(::stat(json.c_str(), &st), 0);
  const mode_t mask = ::umask(0);
  ::umask(mask);
  EXPECT_EQ(st.st_mode & 0777, 0666 & ~mask);
}

// A process killed while its temporary exists removes it, and leaves the old file.
// Streamed outputs (the JSON of a large map comes in pieces): written whole, in
// order; a render that fails midway leaves the old files and no temporary.
TEST(Atomic, StreamedOutputsAreWholeOrAbsent) {
  TempDir out("atomic_stream");
  const std::string a = out.write("a.json", "old a"), b = out.write("b.svg", "old b");
  auto pieces = [](int n) {
    return [n](const std::function<void(const std::string&)>& write) {
      for (int i = 0; i < n; ++i) write(std::to_string(i) + ",");
    };
  };
  vismap::write_outputs_atomically({{a, pieces(3)}, {b, pieces(2)}});
  EXPECT_EQ(vismap_test::slurp(a), "0,1,2,");
  EXPECT_EQ(vismap_test::slurp(b), "0,1,");
  auto failing = [](const std::function<void(const std::string&)>& write) {
    write("half");
    throw std::runtime_error("render failed");
  };
  EXPECT_THROW(vismap::write_outputs_atomically({{a, pieces(5)}, {b, failing}}), std::runtime_error);
  EXPECT_EQ(vismap_test::slurp(a), "0,1,2,");
  EXPECT_EQ(vismap_test::slurp(b), "0,1,");
  EXPECT_EQ(out.names(), (std::vector<std::string>{"a.json", "b.svg"}));
}

// Pieces handed over by the threads that made them (as the JSON's are), one at a
// time, in order: all of them, large and small, in the file in order; a piece
// that fails to be made leaves the old file and no temporary.
TEST(Atomic, PiecesWrittenFromSeveralThreadsAreWholeAndInOrder) {
  TempDir out("atomic_threads");
  const std::string a = out.write("a.json", "old a");
  auto piece = [](int i) { return std::string(static_cast<std::size_t>(i % 7) * 40000, static_cast<char>('a' + i % 26)) + ","; };
  std::string expected;
  for (int i = 0; i < 200; ++i) expected += piece(i);
  for (const int threads : {1, 2, 8}) {
    vismap::write_outputs_atomically({{a, [&](const std::function<void(std::string)>& write) {
                                         vismap::engine::parallel_in_order<std::string>(
                                             200, threads, piece, [&](int, std::string p) { write(std::move(p)); });
                                       }}});
    EXPECT_TRUE(vismap_test::slurp(a) == expected) << threads << " threads";
    auto failing = [&](int i) {
      if (i == 150) throw std::runtime_error("piece 150 failed");
      return piece(i);
    };
    EXPECT_THROW(vismap::write_outputs_atomically({{a, [&](const std::function<void(std::string)>& write) {
                                                      vismap::engine::parallel_in_order<std::string>(
                                                          200, threads, failing, [&](int, std::string p) { write(std::move(p)); });
                                                    }}}),
                 std::runtime_error);
    EXPECT_TRUE(vismap_test::slurp(a) == expected) << threads << " threads";
    EXPECT_EQ(out.names(), (std::vector<std::string>{"a.json"}));
  }
}

TEST(Atomic, ASignalDuringTheWriteRemovesTheTemporary) {
  for (int sig : {SIGTERM, SIGINT, SIGHUP}) {
    TempDir out("atomic_signal");
    const std::string path = out.write("map.json", "old");
    const pid_t pid = ::fork();
    if (pid == 0) {
      vismap::install_output_cleanup_handlers();
      vismap::AtomicFile f(path);
      f.write("new, half written");
      ::raise(sig);
      ::_exit(0);  // not reached
    }
    int status = 0;
    ::waitpid(pid, &status, 0);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << "signal " << sig << " status " << status;
    EXPECT_EQ(out.names(), std::vector<std::string>{"map.json"}) << "signal " << sig;
    EXPECT_EQ(vismap_test::slurp(path), "old");
  }
}

TEST(Atomic, AnInterruptedRunLeavesTheOldFileAndNoTemporary) {
  TempDir in("interrupt_in"), out("interrupt_out"), scratch("interrupt_scratch");
  const std::string scene = in.write("big.off", big_scene(6000));
  for (int sig : {SIGTERM, SIGINT}) {
    const std::string json = out.write("map.json", "old");
    const std::string o = scratch.file("o"), e = scratch.file("e");
    const pid_t pid = vismap_test::start({kBin, scene, "--json", json, "-o", out.file("map.svg")}, "", o, e);
    ::usleep(700'000);
    ::kill(pid, sig);
    const Result r = vismap_test::finish(pid, o, e);
    if (!r.exited) {
      EXPECT_EQ(r.status, sig);
      // Killed before the outputs were committed: the old file alone; or after
      // (while tearing down): both new files, whole. Never one new beside one old.
      const std::string now = vismap_test::slurp(json);
      if (now == "old") {
        EXPECT_EQ(out.names(), std::vector<std::string>{"map.json"});
      } else {
        EXPECT_EQ(out.names(), (std::vector<std::string>{"map.json", "map.svg"}));
        EXPECT_EQ(now.substr(now.size() - 3), "}}\n") << "a cut JSON";
      }
    } else {
      // Finished before the signal: the new files are whole.
      EXPECT_EQ(r.status, 0) << both(r);
      EXPECT_EQ(out.names(), (std::vector<std::string>{"map.json", "map.svg"}));
    }
    fs::remove(out.file("map.svg"));
  }
}

TEST(Atomic, AtomicFileDiscardsUnlessCommitted) {
  TempDir out("atomic_unit");
  const std::string path = out.file("a.txt");
  {
    vismap::AtomicFile f(path);
    f.write("x");
    EXPECT_TRUE(fs::exists(f.temp_path()));
    EXPECT_EQ(fs::path(f.temp_path()).parent_path(), out.path());
  }
  EXPECT_TRUE(out.names().empty());
  {
    vismap::AtomicFile f(path);
    f.write("hello");
    f.commit();
  }
  EXPECT_EQ(vismap_test::slurp(path), "hello");
  EXPECT_EQ(out.names(), std::vector<std::string>{"a.txt"});
  EXPECT_THROW(vismap::write_file_atomically((out.path() / "missing" / "b").string(), "x"), std::runtime_error);
}

// ---- a scene whose exact arithmetic grows very large numbers ------------------------------------

TEST(DeepRationals, NestedPerspectiveTunnelIsVerified) {
  TempDir out("deep"), scratch("deep_scratch");
  const std::string scene = (kData / "deep_rationals.off").string();
  for (const std::vector<std::string>& cam :
       {std::vector<std::string>{"--eye", "0.1000001,0.2000003,1.1", "--target", "0.1,0.2,0", "--fov", "73.3"},
        {"--eye", "0.10000000000000001,0.2,1.0500000001", "--target", "0.1,0.2,0.14285714285714285", "--fov", "170"},
        {"--dir", "0.1,-0.7,-3"}}) {
    std::vector<std::string> argv = {kBin, scene, "--json", out.file("m.json")};
    argv.insert(argv.end(), cam.begin(), cam.end());
    Result r = vismap_test::run(argv, scratch.path());
    ASSERT_EQ(r.status, 0) << both(r);
    // Numbers far beyond any machine type: hundreds of digits.
    const std::string map = vismap_test::slurp(out.file("m.json"));
    std::size_t longest = 0, at = 0;
    while ((at = map.find('"', at)) != std::string::npos) {
      const std::size_t end = map.find('"', at + 1);
      longest = std::max(longest, end - at - 1);
      at = end + 1;
    }
    EXPECT_GT(longest, 60u);
    r = vismap_test::run({kBin, "verify", scene, out.file("m.json")}, scratch.path());
    EXPECT_EQ(r.status, 0) << both(r);
  }
}

// ---- many views in one run ---------------------------------------------------------------

// The cameras --views ran, as the options its progress lines print.
std::vector<std::vector<std::string>> cameras_run(const std::string& err) {
  std::vector<std::vector<std::string>> out;
  for (std::size_t at = err.find("vismap: view "); at != std::string::npos; at = err.find("vismap: view ", at + 1)) {
    const std::size_t open = err.find('(', at), close = err.find(")\n", at);
    std::vector<std::string> words;
    std::string word;
    for (char c : err.substr(open + 1, close - open - 1) + " ") {
      if (c != ' ') word += c;
      else if (!word.empty()) { words.push_back(word); word.clear(); }
    }
    out.push_back(words);
  }
  return out;
}

// Each view's files are byte for byte what one run with its camera writes.
TEST(Views, EachViewIsASingleRunsMap) {
  TempDir dir("views");
  const std::string scene = (kData / "holes_block.vmscene.json").string();
  const std::string file = dir.write("views.txt",
                                     "# an oblique view and one from inside the tunnel\n--dir -1,-2,-4\n\n"
                                     "--eye 2,1.5,0.5 --target 2,4,0.5 --fov 100   # the near plane cuts\n");
  for (const std::string& spec : {std::string("orbit:3,20"), file}) {
    SCOPED_TRACE(spec);
    const Result r = vismap_test::run({kBin, scene, "--views", spec, "--hidden", "--json", dir.file("v%03d.json"),
                                       "-o", dir.file("v%d.svg")},
                                      dir.path());
    ASSERT_EQ(r.status, 0) << both(r);
    const auto cameras = cameras_run(r.err);
    ASSERT_EQ(cameras.size(), spec == file ? 2u : 3u) << both(r);
    for (std::size_t k = 0; k < cameras.size(); ++k) {
      std::vector<std::string> argv = {kBin, scene, "--hidden", "--json", dir.file("one.json"), "-o", dir.file("one.svg")};
      argv.insert(argv.end(), cameras[k].begin(), cameras[k].end());
      ASSERT_EQ(vismap_test::run(argv, dir.path()).status, 0);
      char name[32];
      std::snprintf(name, sizeof name, "v%03zu.json", k);
      EXPECT_EQ(vismap_test::slurp(dir.file(name)), vismap_test::slurp(dir.file("one.json"))) << k;
      EXPECT_EQ(vismap_test::slurp(dir.file("v" + std::to_string(k) + ".svg")), vismap_test::slurp(dir.file("one.svg"))) << k;
    }
  }
  // orbit:4 at elevation 0 looks exactly along the axes (quarter turns are exact).
  const Result r = vismap_test::run({kBin, scene, "--views", "orbit:4,0", "--json", dir.file("q%d.json")}, dir.path());
  ASSERT_EQ(r.status, 0) << both(r);
  EXPECT_EQ(cameras_run(r.err), (std::vector<std::vector<std::string>>{
                                    {"--dir", "-1,0,0"}, {"--dir", "0,-1,0"}, {"--dir", "1,0,0"}, {"--dir", "0,1,0"}}));
}

// A terrain, and the same with a vertex inside a neighbour's edge (a
// T-junction) and a triangle apart: a single run matches a terrain's edges by vertex pairs where
// its height field's certificate allows (engine/edge_pieces.h), the views of
// --views geometrically (for the world scene they share): the same maps, in
// oblique, perspective (the near plane cutting) and lines-only drawings.
TEST(Views, ATerrainMatchedByVertexPairsIsTheSameMap) {
  TempDir dir("views_terrain");
  vismap::Scene plain = vismap::gen::terrain(12, 3), split = plain;
  // (The square at (5, 5) of 12 x 12: its lower edge's midpoint joins the triangle below it.)
  const auto id = [](std::uint32_t i, std::uint32_t j) { return j * 13 + i; };
  const std::uint32_t a = id(5, 5), b = id(6, 5);
  split.vertices.push_back({(split.vertices[a].x + split.vertices[b].x) / 2, split.vertices[a].y,
                            (split.vertices[a].z + split.vertices[b].z) / 2});
  const auto m = static_cast<std::uint32_t>(split.vertices.size() - 1);
  std::size_t replaced = 0;
  for (std::size_t f = 0; f < split.faces.size() && replaced == 0; ++f) {
    auto v = split.faces[f];
    const bool has_edge = std::count(v.begin(), v.end(), a) && std::count(v.begin(), v.end(), b);
    if (!has_edge || !std::all_of(v.begin(), v.end(), [&](std::uint32_t w) { return split.vertices[w].y <= split.vertices[a].y; }))
      continue;
    // (Its corners turned so that the edge a -> b or b -> a comes first.)
    while (!((v[0] == a && v[1] == b) || (v[0] == b && v[1] == a))) std::rotate(v.begin(), v.begin() + 1, v.end());
    split.faces[f] = {v[0], m, v[2]};
    split.faces.push_back({m, v[1], v[2]});
    ++replaced;
  }
  ASSERT_EQ(replaced, 1u);
  // (And a triangle apart, so that V - E + F = 1 again: vertex pairs match the
  // scene, and only the certificate finds the T-junction.)
  const auto far = static_cast<std::uint32_t>(split.vertices.size());
  split.vertices.insert(split.vertices.end(), {{0.2, 1.5, 0}, {0.3, 1.5, 0}, {0.2, 1.6, 0.05}});
  split.faces.push_back({far, far + 1, far + 2});
  const std::string views = dir.write("views.txt", "--dir -1,-2,-3\n--eye 0.5,-0.2,0.12 --target 0.5,0.6,0 --fov 90\n");
  for (const auto& [name, scene] : {std::pair("plain", &plain), std::pair("split", &split)}) {
    SCOPED_TRACE(name);
    const std::string off = dir.write(std::string(name) + ".off", vismap::gen::to_off(*scene));
    for (const std::vector<std::string>& extra : {std::vector<std::string>{"--hidden"}, {"--crease", "10", "--no-regions"}}) {
      std::vector<std::string> argv = {kBin, off, "--views", views, "--json", dir.file("v%d.json")};
      argv.insert(argv.end(), extra.begin(), extra.end());
      const Result r = vismap_test::run(argv, dir.path());
      ASSERT_EQ(r.status, 0) << both(r);
      const auto cameras = cameras_run(r.err);
      ASSERT_EQ(cameras.size(), 2u) << both(r);
      for (std::size_t k = 0; k < cameras.size(); ++k) {
        std::vector<std::string> one = {kBin, off, "--json", dir.file("one.json")};
        one.insert(one.end(), extra.begin(), extra.end());
        one.insert(one.end(), cameras[k].begin(), cameras[k].end());
        const Result s = vismap_test::run(one, dir.path());
        ASSERT_EQ(s.status, 0) << both(s);
        const std::string single = vismap_test::slurp(dir.file("one.json"));
        EXPECT_NE(single.find("\"segments\""), std::string::npos);
        EXPECT_TRUE(vismap_test::slurp(dir.file("v" + std::to_string(k) + ".json")) == single) << k;   // (maps: long)
      }
    }
  }
}

// On several threads, the views of a small scene run side by side (one thread
// each here) and write what one view at a time writes, byte for byte, for
// every engine and output; progress in the views' order, each view's
// statistics named. A scene of 8192 faces or more: one view at a time.
TEST(Views, SideBySideWriteWhatOneAtATimeWrites) {
  TempDir dir("views_side");
  const std::string scene = (kData / "interpenetrating_boxes.off").string();
  for (const std::string engine : {"franklin", "newell", "bsp"}) {
    SCOPED_TRACE(engine);
    std::vector<std::string> outputs = {"--hidden", "--json", dir.file("s%d.json"), "-o", dir.file("s%d.svg")};
    if (engine != "franklin") outputs.insert(outputs.end(), {"--painter", dir.file("s%d.painter.svg")});
    auto run = [&](const std::string& threads, const std::string& prefix) {
      std::vector<std::string> argv = {kBin, scene, "--views", "orbit:7,25", "--algorithm", engine, "--threads", threads};
      for (std::string o : outputs) {
        if (o.find("s%d") != std::string::npos) o.replace(o.find("s%d"), 1, prefix);
        argv.push_back(o);
      }
      return vismap_test::run(argv, dir.path());
    };
    const Result side = run("3", "a"), alone = run("1", "b");
    ASSERT_EQ(side.status, 0) << both(side);
    ASSERT_EQ(alone.status, 0) << both(alone);
    EXPECT_NE(side.err.find("vismap: 3 views at a time, 1 thread each"), std::string::npos) << side.err;
    EXPECT_EQ(alone.err.find("at a time"), std::string::npos) << alone.err;
    EXPECT_EQ(cameras_run(side.err), cameras_run(alone.err));
    ASSERT_EQ(cameras_run(side.err).size(), 7u) << side.err;
    for (int k = 0; k < 7; ++k)
      for (const std::string ext : {".json", ".svg", ".painter.svg"}) {
        if (ext == ".painter.svg" && engine == "franklin") continue;
        const std::string a = vismap_test::slurp(dir.file("a" + std::to_string(k) + ext));
        EXPECT_FALSE(a.empty()) << k << ext;
        EXPECT_EQ(a, vismap_test::slurp(dir.file("b" + std::to_string(k) + ext))) << k << ext;
      }
  }
  // A scene of 8192 faces (a 64 x 64 terrain) is drawn one view at a time, on every thread.
  const std::string grid = vismap::gen::to_off(vismap::gen::terrain(64, 1));
  const Result big = vismap_test::run({kBin, dir.write("grid.off", grid), "--views", "orbit:3", "--threads", "2",
                                       "--json", dir.file("g%d.json")},
                                      dir.path());
  ASSERT_EQ(big.status, 0) << both(big);
  EXPECT_EQ(big.err.find("at a time"), std::string::npos) << big.err;
  EXPECT_EQ(cameras_run(big.err).size(), 3u) << big.err;
  const Result st = vismap_test::run({kBin, scene, "--views", "orbit:5", "--threads", "2", "--stats", "--json",
                                      dir.file("t%d.json")},
                                     dir.path());
  ASSERT_EQ(st.status, 0) << both(st);
  for (int k = 2; k <= 5; ++k)
    EXPECT_NE(st.err.find("vismap: statistics of view " + std::to_string(k) + ":\n  "), std::string::npos) << st.err;
}

// The least and greatest page x and y of the path points in group `id` of a sheet.
std::array<double, 4> group_box(const std::string& svg, const std::string& id) {
  const std::size_t begin = svg.find("<g id=\"" + id + "\">"), end = svg.find("<text", begin);
  std::array<double, 4> box{1e300, 1e300, -1e300, -1e300};
  for (std::size_t d = svg.find(" d=\"", begin); d < end; d = svg.find(" d=\"", d + 1)) {
    std::istringstream in(svg.substr(d + 4, svg.find('"', d + 4) - d - 4));
    std::string word;
    std::vector<double> xy;
    while (in >> word) {
      if (word[0] == 'M' || word[0] == 'L') word = word.substr(1);
      if (word == "Z" || word.empty()) continue;
      xy.push_back(std::stod(word));
      if (xy.size() == 2) {
        box = {std::min(box[0], xy[0]), std::min(box[1], xy[1]), std::max(box[2], xy[0]), std::max(box[3], xy[1])};
        xy.clear();
      }
    }
  }
  return box;
}

// --views sheet: four views on one SVG page, each map a single run's, the
// orthographic views at one scale and lined up as first- or third-angle wants.
// The BSP engine over many views builds its tree once (ViewSeries) and writes,
// for each view (orthographic or not), the single run's map with Franklin's
// engine (the stats aside: they name the engine's own work), and the BSP
// engine's single run byte for byte, counters included (what the shared tree's
// making ran is counted in every view, as a single run counts it).
TEST(Views, OneBspTreeForEveryView) {
  TempDir dir("views_bsp");
  const std::string scene = (kData / "interpenetrating_boxes.off").string();
  const Result r = vismap_test::run({kBin, scene, "--views", "orbit:5,25", "--algorithm", "bsp", "--hidden", "--json",
                                     dir.file("b%d.json")},
                                    dir.path());
  ASSERT_EQ(r.status, 0) << both(r);
  const auto cameras = cameras_run(r.err);
  ASSERT_EQ(cameras.size(), 5u) << both(r);
  auto map_of = [](const std::string& json) { return json.substr(0, json.find("\"stats\":")); };
  for (std::size_t k = 0; k < cameras.size(); ++k) {
    std::vector<std::string> argv = {kBin, scene, "--hidden", "--json", dir.file("one.json")};
    argv.insert(argv.end(), cameras[k].begin(), cameras[k].end());
    ASSERT_EQ(vismap_test::run(argv, dir.path()).status, 0);
    const std::string multi = vismap_test::slurp(dir.file("b" + std::to_string(k) + ".json"));
    EXPECT_NE(multi.find("\"bsp_fragments\""), std::string::npos) << k;
    EXPECT_EQ(map_of(multi), map_of(vismap_test::slurp(dir.file("one.json")))) << k;
    argv.insert(argv.end(), {"--algorithm", "bsp"});
    ASSERT_EQ(vismap_test::run(argv, dir.path()).status, 0);
    EXPECT_EQ(multi, vismap_test::slurp(dir.file("one.json"))) << k;
  }
  const std::string views = dir.write("views.txt", "--dir -1,-2,-4\n--eye 3,3,3\n--eye 0.1,0.2,0.3 --target 2,2,2 --fov 100\n");
  const Result p = vismap_test::run({kBin, scene, "--views", views, "--algorithm", "bsp", "--json", dir.file("p%d.json")},
                                    dir.path());
  ASSERT_EQ(p.status, 0) << both(p);
  const auto eyes = cameras_run(p.err);
  ASSERT_EQ(eyes.size(), 3u) << both(p);
  for (std::size_t k = 0; k < eyes.size(); ++k) {
    std::vector<std::string> argv = {kBin, scene, "--json", dir.file("one.json")};
    argv.insert(argv.end(), eyes[k].begin(), eyes[k].end());
    ASSERT_EQ(vismap_test::run(argv, dir.path()).status, 0);
    EXPECT_EQ(map_of(vismap_test::slurp(dir.file("p" + std::to_string(k) + ".json"))),
              map_of(vismap_test::slurp(dir.file("one.json"))))
        << k;
  }
}

TEST(Views, ASheetLinesUpFrontTopAndRight) {
  TempDir dir("views_sheet");
  const std::string scene = (kData / "holes_block.vmscene.json").string();
  for (const std::string angle : {"first", "third"}) {
    SCOPED_TRACE(angle);
    const Result r = vismap_test::run({kBin, scene, "--views", "sheet:" + angle, "--hidden", "--style", "technical",
                                       "--page", "a4", "-o", dir.file("sheet.svg"), "--json", dir.file("s%d.json")},
                                      dir.path());
    ASSERT_EQ(r.status, 0) << both(r);
    const auto cameras = cameras_run(r.err);
    ASSERT_EQ(cameras.size(), 4u);
    for (std::size_t k = 0; k < cameras.size(); ++k) {
      std::vector<std::string> argv = {kBin, scene, "--hidden", "--json", dir.file("one.json")};
      argv.insert(argv.end(), cameras[k].begin(), cameras[k].end());
      ASSERT_EQ(vismap_test::run(argv, dir.path()).status, 0);
      EXPECT_EQ(vismap_test::slurp(dir.file("s" + std::to_string(k) + ".json")), vismap_test::slurp(dir.file("one.json")));
    }
    const std::string svg = vismap_test::slurp(dir.file("sheet.svg"));
    EXPECT_NE(svg.find(angle == "first" ? "FIRST-ANGLE PROJECTION" : "THIRD-ANGLE PROJECTION"), std::string::npos);
    const auto front = group_box(svg, "front"), top = group_box(svg, "top"), right = group_box(svg, "right");
    ASSERT_LT(front[0], front[2]);
    // The block is 4 wide (x), 4 deep (y), 1 high (z): front and top share x, front and right share z.
    EXPECT_NEAR(front[0], top[0], 0.01);
    EXPECT_NEAR(front[2], top[2], 0.01);
    EXPECT_NEAR(front[1], right[1], 0.01);
    EXPECT_NEAR(front[3], right[3], 0.01);
    EXPECT_NEAR((front[2] - front[0]) / (front[3] - front[1]), 4.0, 0.01);   // one scale across and up
    EXPECT_NEAR(top[3] - top[1], front[2] - front[0], 0.01);                  // the top view is 4 deep
    // First angle: the top view under the front one, the right view left of it; third angle the other way.
    EXPECT_EQ(top[1] > front[3], angle == "first");
    EXPECT_EQ(right[2] < front[0], angle == "first");
  }
  const Result bad = vismap_test::run({kBin, scene, "--views", "sheet:second", "-o", dir.file("x.svg")}, dir.path());
  EXPECT_EQ(bad.status, 2) << both(bad);
  // The same page as PDF, EPS and PNG (cairo); DXF has no sheet.
  for (const auto& [ext, magic] : std::vector<std::pair<std::string, std::string>>{
           {"pdf", "%PDF-"}, {"eps", "%!PS-Adobe-3.0 EPSF"}, {"png", "\x89PNG"}}) {
    const Result r = vismap_test::run({kBin, scene, "--views", "sheet", "--page", "a4", "-o", dir.file("sheet." + ext)},
                                      dir.path());
    ASSERT_EQ(r.status, 0) << ext << "\n" << both(r);
    EXPECT_EQ(vismap_test::slurp(dir.file("sheet." + ext)).rfind(magic, 0), 0u) << ext;
  }
  // An A4 page in points, landscape or portrait.
  const std::string pdf = vismap_test::slurp(dir.file("sheet.pdf"));
  EXPECT_TRUE(pdf.find("/MediaBox [ 0 0 595.") != std::string::npos || pdf.find("/MediaBox [ 0 0 841.") != std::string::npos);
  const Result dxf = vismap_test::run({kBin, scene, "--views", "sheet", "-o", dir.file("x.dxf")}, dir.path());
  EXPECT_EQ(dxf.status, 2) << both(dxf);
  EXPECT_FALSE(std::filesystem::exists(dir.file("x.dxf")));
}

// A bad spec, a bad line of the file (named), an impossible camera in any view:
// refused before anything is written.
TEST(Views, BadViewsAreRefusedBeforeAnyOutput) {
  TempDir dir("views_bad"), out("views_bad_out");
  const std::string scene = (kData / "cube_axis.off").string();
  const std::string bad_line = dir.write("bad_line.txt", "--dir 0,0,-1\n--dir 0,0\n");
  const std::string bad_camera = dir.write("bad_camera.txt", "--dir 0,0,-1\n--eye 1,1,1 --target 1,1,1\n");
  struct Case {
    std::vector<std::string> args;
    int status;
    std::string message;
  };
  for (const Case& c : std::vector<Case>{
           {{"--views", "orbit:4", "--json", out.file("v.json")}, 2, "named with %d"},
           {{"--views", "orbit:4", "--json", "-"}, 2, "named with %d"},
           {{"--views", "orbit:4", "--dir", "0,0,-1", "--json", out.file("v%d.json")}, 2, "--views gives the cameras"},
           {{"--views", "orbit:0", "--json", out.file("v%d.json")}, 2, "orbit:N"},
           {{"--views", "orbit:4,90", "--json", out.file("v%d.json")}, 2, "orbit:N"},
           {{"--views", "orbit:4"}, 2, "needs an output"},
           {{"--views", bad_line, "--json", out.file("v%d.json")}, 1, bad_line + ":2: --dir expects X,Y,Z"},
           {{"--views", dir.file("none.txt"), "--json", out.file("v%d.json")}, 1, "cannot open the views file"},
           {{"--views", bad_camera, "--json", out.file("v%d.json")}, 2, "must differ"},
       }) {
    std::vector<std::string> argv = {kBin, scene};
    argv.insert(argv.end(), c.args.begin(), c.args.end());
    const Result r = vismap_test::run(argv, dir.path());
    EXPECT_EQ(r.status, c.status) << c.message << "\n" << both(r);
    EXPECT_NE(r.err.find(c.message), std::string::npos) << both(r);
    EXPECT_TRUE(out.names().empty()) << c.message;
  }
}

}  // namespace
