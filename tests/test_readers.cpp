// Tests for the mesh readers (engine/io): every format from small inline
// files, exact number parsing, and a table of malformed inputs whose messages
// must name the file and the line (or byte offset).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "engine/scene.h"

namespace {

using vismap::InputError;
using vismap::ReadLimits;
using vismap::Scene;
using vismap::Vec3;
using Faces = std::vector<std::vector<std::uint32_t>>;

Scene read(std::string_view bytes, const std::string& format, const ReadLimits& limits = {}) {
  return vismap::read_scene_bytes(bytes, "t." + format, format, limits);
}

// The message of the InputError that reading throws ("" if none is thrown).
std::string error_of(std::string_view bytes, const std::string& name, const std::string& format,
                     const ReadLimits& limits = {}) {
  try {
    vismap::read_scene_bytes(bytes, name, format, limits);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

void expect_vertex(const Vec3& v, double x, double y, double z) {
  EXPECT_EQ(v.x, x);
  EXPECT_EQ(v.y, y);
  EXPECT_EQ(v.z, z);
}

// Little- or big-endian byte builder for binary STL and PLY.
struct Bytes {
  bool little = true;
  std::string s;

  template <class T>
  Bytes& put(T v) {
    unsigned char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    if (little != (std::endian::native == std::endian::little)) std::reverse(b, b + sizeof(T));
    s.append(reinterpret_cast<const char*>(b), sizeof(T));
    return *this;
  }
  Bytes& text(std::string_view t) {
    s += t;
    return *this;
  }
};

// A binary STL: 80-byte header (padded with NULs), count, triangles.
std::string binary_stl(std::string header, const std::vector<std::array<float, 9>>& tris,
                       std::uint32_t count) {
  header.resize(80, '\0');
  Bytes b;
  b.text(header).put(count);
  for (const auto& t : tris) {
    b.put(0.0f).put(0.0f).put(1.0f);  // normal
    for (float f : t) b.put(f);
    b.put(std::uint16_t{0});
  }
  return b.s;
}
std::string binary_stl(const std::string& header, const std::vector<std::array<float, 9>>& tris) {
  return binary_stl(header, tris, static_cast<std::uint32_t>(tris.size()));
}

// A fresh temporary directory per test, removed afterwards.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            (std::string("vismap_readers_") + info->test_suite_name() + "_" + info->name());
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  std::string write(const std::string& file, std::string_view bytes) const {
    const std::string p = (path_ / file).string();
    std::ofstream(p, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return p;
  }
  std::filesystem::path path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// --- OFF --------------------------------------------------------------------------

TEST(Off, ReadsVerticesAndFacesInOrder) {
  const Scene s = read(
      "# a comment line\n"
      "OFF\n"
      "\n"
      "4 3 0   # counts\n"
      "0 0 0\n"
      "1 0 0 0.5 0.5 0.5 1   # colour ignored\n"
      "1 1 0\n"
      "0 1 0\n"
      "4 0 1 2 3\n"
      "3 0 1 2 255 0 0\n"   // face colour ignored
      "3 1 1 2\n",          // degenerate: kept
      "off");
  EXPECT_EQ(s.file, "t.off");
  ASSERT_EQ(s.vertices.size(), 4u);
  expect_vertex(s.vertices[1], 1, 0, 0);
  expect_vertex(s.vertices[2], 1, 1, 0);
  EXPECT_EQ(s.faces, (Faces{{0, 1, 2, 3}, {0, 1, 2}, {1, 1, 2}}));
}

// Geomview's OFF variants whose vertex lines carry more values (a colour, a
// normal, texture coordinates), as CGAL's sample meshes and MeshLab write them:
// the same scene as plain OFF, the extra values ignored.
TEST(Off, VariantsWithMoreVertexValuesReadAsOff) {
  const Scene plain = read("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "off");
  const std::pair<const char*, const char*> variants[] = {
      {"COFF", " 192 192 192 255"}, {"NOFF", " 0 0 1"}, {"CNOFF", " 0 0 1 0.9 0 0"},
      {"STOFF", " 0.5 0.5"},        {"STCNOFF", " 0.5 0.5 0 0 1 0.9 0 0 1"}};
  for (const auto& [header, extra] : variants) {
    const std::string text = std::string("# a comment\n") + header + "\n3 1 0\n0 0 0" + extra + "\n1 0 0" + extra +
                             "\n0 1 0" + extra + "\n3 0 1 2\n";
    const Scene s = read(text, "off");
    ASSERT_EQ(s.vertices.size(), 3u) << header;
    for (std::size_t i = 0; i < 3; ++i) {
      EXPECT_EQ(s.vertices[i].x, plain.vertices[i].x) << header;
      EXPECT_EQ(s.vertices[i].y, plain.vertices[i].y) << header;
      EXPECT_EQ(s.vertices[i].z, plain.vertices[i].z) << header;
    }
    EXPECT_EQ(s.faces, plain.faces) << header;
  }
}

TEST(Off, CountsOnHeaderLineCrlfAndNoEdgeCount) {
  const Scene a = read("OFF 3 1 0\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\n3 0 1 2\r\n", "off");
  EXPECT_EQ(a.faces, (Faces{{0, 1, 2}}));
  const Scene b = read("OFF\n3 1\n0 0 0\n1 0 0\n0 1 0\n3 2 1 0", "off");  // no final newline
  EXPECT_EQ(b.faces, (Faces{{2, 1, 0}}));
  const Scene empty = read("OFF\n0 0 0\n", "off");
  EXPECT_TRUE(empty.vertices.empty());
  EXPECT_TRUE(empty.faces.empty());
}

TEST(Off, ParsesNearestDouble) {
  const Scene s = read(
      "OFF\n6 0 0\n"
      "0.1 1e-300 -0\n"
      "0.30000000000000004 0.3 +1.5\n"
      "4.9e-324 1e-400 -1e-400\n"       // subnormal; underflow rounds to +-0
      "1.7976931348623157e308 -2.5E+3 .5\n"
      "123456789012345678901234567890 1 5.\n"
      "0.1000000000000000055511151231257827 0.10000000000000001 1\n",
      "off");
  expect_vertex(s.vertices[0], 0.1, 1e-300, 0.0);
  EXPECT_TRUE(std::signbit(s.vertices[0].z));
  EXPECT_EQ(s.vertices[1].x, 0.30000000000000004);
  EXPECT_NE(s.vertices[1].x, s.vertices[1].y);
  EXPECT_EQ(s.vertices[1].z, 1.5);
  EXPECT_EQ(s.vertices[2].x, std::numeric_limits<double>::denorm_min());
  EXPECT_EQ(s.vertices[2].y, 0.0);
  EXPECT_TRUE(std::signbit(s.vertices[2].z));
  expect_vertex(s.vertices[3], std::numeric_limits<double>::max(), -2500, 0.5);
  EXPECT_EQ(s.vertices[4].x, 123456789012345678901234567890.0);
  EXPECT_EQ(s.vertices[4].z, 5.0);
  EXPECT_EQ(s.vertices[5].x, 0.1);
  EXPECT_EQ(s.vertices[5].y, 0.1);
}

// Numbers are parsed where they start (the common case) or from their whole
// token (the rest): both must end a number where its token ends.
TEST(Off, NumbersEndWhereTheirTokensDo) {
  const Scene s = read(
      "OFF\n3 1 0\n"
      "0 0 0#glued comment\n"
      "1e0\t+0 0\r\n"
      "0 1 0\n"
      "3 000 00000000000000000001 +2# 20 digits, a plus sign\n",
      "off");
  expect_vertex(s.vertices[1], 1, 0, 0);
  EXPECT_EQ(s.faces, (Faces{{0, 1, 2}}));
  EXPECT_TRUE(error_of("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2.\n", "t.off", "off").find("found '2.'") !=
              std::string::npos);
  EXPECT_TRUE(error_of("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0e\n3 0 1 2\n", "t.off", "off").find("found '0e'") !=
              std::string::npos);
}

// Short decimals (the usual mesh file's) are read by a fast path of their own:
// each must still be the nearest double, as std::from_chars gives it.
TEST(Off, ShortDecimalsAreNearestDoubles) {
  std::mt19937_64 rng(7);
  const int n = 30000;
  std::string text = "OFF\n" + std::to_string(n) + " 0 0\n";
  std::vector<std::string> tokens;
  for (int i = 0; i < 3 * n; ++i) {
    const int digits = 1 + static_cast<int>(rng() % 17);   // (past 15: the general path)
    std::string t = rng() % 2 ? "-" : "";
    for (int k = 0; k < digits; ++k) t += static_cast<char>('0' + rng() % 10);
    const int point = static_cast<int>(rng() % (digits + 2));   // (digits + 1: none)
    if (point <= digits) t.insert(t.size() - static_cast<std::size_t>(digits - point), ".");
    tokens.push_back(t);
    text += t + (i % 3 == 2 ? "\n" : " ");
  }
  const Scene s = read(text, "off");
  for (int i = 0; i < 3 * n; ++i) {
    double want;
    const std::string& t = tokens[static_cast<std::size_t>(i)];
    ASSERT_EQ(std::from_chars(t.data(), t.data() + t.size(), want).ec, std::errc()) << t;
    const Vec3& v = s.vertices[static_cast<std::size_t>(i / 3)];
    const double got = i % 3 == 0 ? v.x : i % 3 == 1 ? v.y : v.z;
    ASSERT_EQ(std::bit_cast<std::uint64_t>(got), std::bit_cast<std::uint64_t>(want)) << t;
  }
}

// A large OFF file (over 2 MB of records: read in pieces when threads are
// given), with comments, blank lines, CRLF lines, extra values and junk after
// the faces; `break_at` (a record number) spoils that record with text.
std::string large_off(std::size_t nv, std::size_t nf, long break_at = -1, bool truncate = false) {
  std::string s = "OFF\n# made by the test\n" + std::to_string(nv) + " " + std::to_string(nf) + " 0\n";
  std::size_t r = 0;
  auto end_line = [&](std::size_t k) { s += k % 7 == 0 ? "\r\n" : k % 11 == 0 ? "   # note\n\n" : "\n"; };
  for (std::size_t i = 0; i < nv; ++i, ++r) {
    if (static_cast<long>(r) == break_at) { s += "1 oops 3\n"; continue; }
    s += std::to_string(i * 0.25) + " " + std::to_string(i % 97) + " -" + std::to_string(i % 13) + ".5";
    if (i % 5 == 0) s += " 0.5 0.5 0.5";
    end_line(i);
  }
  for (std::size_t f = 0; f < nf; ++f, ++r) {
    if (static_cast<long>(r) == break_at) { s += "3 0 1\n"; continue; }
    const std::size_t a = f % nv, b = (f * 7 + 1) % nv, c = (f * 13 + 2) % nv;
    s += f % 9 == 0 ? "4 " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(c) + " " +
                          std::to_string((a + 5) % nv)
                    : "3 " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(c);
    end_line(f);
  }
  if (truncate) s.resize(s.rfind('\n', s.size() - 40 * 1000) + 1);   // (a thousand records or so short)
  else s += "junk after the faces is ignored\n";
  return s;
}

ReadLimits with_threads(int threads) {
  ReadLimits l;
  l.threads = threads;
  return l;
}

TEST(Off, ReadInPiecesAsInOne) {
  const std::string text = large_off(60000, 120000);
  ASSERT_GT(text.size(), 3u << 20);
  const Scene one = read(text, "off");
  ASSERT_EQ(one.vertices.size(), 60000u);
  ASSERT_EQ(one.faces.size(), 120000u);
  EXPECT_EQ(one.faces[9], (std::vector<std::uint32_t>{9, 64, 119, 14}));
  for (int threads : {2, 3, 8}) {
    const Scene many = read(text, "off", with_threads(threads));
    ASSERT_EQ(many.vertices.size(), one.vertices.size());
    for (std::size_t i = 0; i < one.vertices.size(); ++i) {
      ASSERT_EQ(many.vertices[i].x, one.vertices[i].x);
      ASSERT_EQ(many.vertices[i].y, one.vertices[i].y);
      ASSERT_EQ(many.vertices[i].z, one.vertices[i].z);
    }
    EXPECT_EQ(many.faces, one.faces);
  }
}

TEST(Off, ReadInPiecesFailsAsInOne) {
  // A spoilt record early, in the middle, near the end; a file cut short.
  for (long at : {3L, 61234L, 90000L, 179990L}) {
    const std::string text = large_off(60000, 120000, at);
    const std::string one = error_of(text, "big.off", "off");
    ASSERT_TRUE(starts_with(one, "big.off:")) << one;
    for (int threads : {2, 8}) EXPECT_EQ(error_of(text, "big.off", "off", with_threads(threads)), one) << at;
  }
  const std::string cut = large_off(60000, 120000, -1, true);
  const std::string one = error_of(cut, "big.off", "off");
  EXPECT_TRUE(one.find("unexpected end of file: expected 120000 faces") != std::string::npos) << one;
  for (int threads : {2, 8}) EXPECT_EQ(error_of(cut, "big.off", "off", with_threads(threads)), one);
}

// --- OBJ ----------------------------------------------------------------------------

TEST(Obj, CornerFormsIgnoredRecordsAndPolygons) {
  const Scene s = read(
      "# comment\n"
      "mtllib a.mtl\n"
      "o thing\n"
      "v 0 0 0\n"
      "v 1 0 0 1.0\n"         // w ignored
      "v 1 1 0 0.2 0.3 0.4\n" // vertex colour ignored
      "v 0 1 0\n"
      "v 0.5 2 0\n"
      "vt 0 0\nvt 1 0\nvn 0 0 1\n"
      "g group\ns off\nusemtl red\n"
      "f 1 2 3\n"
      "f 1/1 2/2 3/1\n"
      "f 1//1 2//1 3//1 4//1\n"
      "f 1/1/1 2/2/1 3/1/1 4/2/1 5/1/1   # pentagon\n"
      "l 1 2\np 3\nvp 0.1\nfoo bar\n"
      "f 3 3 3\n",  // degenerate: kept
      "obj");
  ASSERT_EQ(s.vertices.size(), 5u);
  expect_vertex(s.vertices[1], 1, 0, 0);
  expect_vertex(s.vertices[4], 0.5, 2, 0);
  EXPECT_EQ(s.faces, (Faces{{0, 1, 2}, {0, 1, 2}, {0, 1, 2, 3}, {0, 1, 2, 3, 4}, {2, 2, 2}}));
}

TEST(Obj, NegativeIndicesAreRelativeToVerticesSoFar) {
  const Scene s = read(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
      "f -3 -2 -1\n"
      "v 5 5 5\n"
      "f -1 -2/1 -4//2\n",
      "obj");
  EXPECT_EQ(s.faces, (Faces{{0, 1, 2}, {3, 2, 0}}));
}

TEST(Obj, ForwardReferencesAndLineContinuation) {
  const Scene s = read(
      "f 1 2 \\\n"
      "  3\n"
      "v 0 0 0\nv 1 0 0\nv 0 1 0\n",
      "obj");
  EXPECT_EQ(s.faces, (Faces{{0, 1, 2}}));
  // Line numbers after a continuation are still those of the file.
  EXPECT_TRUE(starts_with(error_of("v 0 0 \\\r\n 0\nv 1 0 0\nf 1 2 0\n", "c.obj", "obj"), "c.obj:4: "));
}

// --- STL ----------------------------------------------------------------------------

TEST(Stl, AsciiMakesASoupOfTriangles) {
  const Scene s = read(
      "solid my part\n"
      "  facet normal 0 0 1\n"
      "    outer loop\n"
      "      vertex 0 0 0\n"
      "      vertex 1 0 0\n"
      "      vertex 0 1 0\n"
      "    endloop\n"
      "  endfacet\n"
      "  FACET NORMAL nan nan nan\n"   // some exporters: upper case, nan normals
      "    OUTER LOOP\n"
      "      VERTEX 1 0 0\n"
      "      VERTEX 0 1 0\n"
      "      VERTEX 0.1 1e-300 -2\n"
      "    ENDLOOP\n"
      "  ENDFACET\n"
      "endsolid my part\n"
      "solid second\n"
      "facet normal 0 0 1 outer loop vertex 0 0 0 vertex 0 0 0 vertex 0 0 0 endloop endfacet\n"
      "endsolid\n",
      "stl");
  ASSERT_EQ(s.vertices.size(), 9u);  // shared corners are not merged
  expect_vertex(s.vertices[3], 1, 0, 0);
  expect_vertex(s.vertices[5], 0.1, 1e-300, -2);
  EXPECT_EQ(s.faces, (Faces{{0, 1, 2}, {3, 4, 5}, {6, 7, 8}}));
}

TEST(Stl, BinaryEvenWhenHeaderSaysSolid) {
  const std::string bytes =
      binary_stl("solid looks like ascii", {{0.1f, 0, 0, 1, 0, 0, 0, 1, 0}, {1, 0, 0, 0, 1, 0, -3.5f, 2, 1e-30f}});
  const Scene s = read(bytes, "stl");
  ASSERT_EQ(s.vertices.size(), 6u);
  EXPECT_EQ(s.vertices[0].x, static_cast<double>(0.1f));  // exact float -> double
  expect_vertex(s.vertices[5], -3.5, 2, static_cast<double>(1e-30f));
  EXPECT_EQ(s.faces, (Faces{{0, 1, 2}, {3, 4, 5}}));

  const Scene empty = read(binary_stl("", {}), "stl");
  EXPECT_TRUE(empty.faces.empty());
}

// --- PLY ------------------------------------------------------------------------------

TEST(Ply, AsciiWithExtraPropertiesAndElements) {
  const Scene s = read(
      "ply\n"
      "format ascii 1.0\n"
      "comment made by hand\n"
      "obj_info nothing\n"
      "element vertex 4\n"
      "property float32 nx\n"
      "property double z\n"
      "property uchar red\n"
      "property float y\n"
      "property list uchar int tags\n"
      "property float x\n"
      "element face 2\n"
      "property uint8 flags\n"
      "property list uchar uint vertex_index\n"
      "property float quality\n"
      "element edge 1\n"
      "property int vertex1\n"
      "property int vertex2\n"
      "end_header\n"
      "0 3 255 2 0 1\n"
      "0.5 0.1 0 1.5 2 7 7 -1\n"
      "nan 0 0 0 0 0\n"          // nan in a skipped property is fine
      "0 0 0 1e-300 1 9 4\n"
      "\n"
      "1 4 0 1 2 3 0.5\n"
      "0 3 3 2 1 nan\n"
      "0 1\n",
      "ply");
  ASSERT_EQ(s.vertices.size(), 4u);
  expect_vertex(s.vertices[0], 1, 2, 3);
  expect_vertex(s.vertices[1], -1, 1.5, 0.1);
  expect_vertex(s.vertices[3], 4, 1e-300, 0);
  EXPECT_EQ(s.faces, (Faces{{0, 1, 2, 3}, {3, 2, 1}}));
}

// Header for a binary PLY with float xyz + uchar colour, a face list with the
// given count/index types, and a material element and a list element to skip.
std::string binary_ply_header(const std::string& format, int nv, int nf) {
  return "ply\nformat " + format +
         " 1.0\n"
         "element vertex " + std::to_string(nv) +
         "\n"
         "property float x\nproperty float y\nproperty float z\nproperty uchar red\n"
         "element material 2\nproperty double shine\nproperty short id\n"
         "element face " + std::to_string(nf) +
         "\n"
         "property list uchar int vertex_indices\n"
         "property list ushort float uv\n"
         "element edge 1\nproperty list int8 int32 ends\n"
         "end_header\n";
}

std::string binary_ply(bool little) {
  Bytes b;
  b.little = little;
  b.text(binary_ply_header(little ? "binary_little_endian" : "binary_big_endian", 4, 2));
  const float xyz[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.1f}, {0, 1, -2}};
  for (const auto& v : xyz) b.put(v[0]).put(v[1]).put(v[2]).put(std::uint8_t{200});
  b.put(1.5).put(std::int16_t{1}).put(2.5).put(std::int16_t{2});
  b.put(std::uint8_t{4}).put(0).put(1).put(2).put(3).put(std::uint16_t{2}).put(0.f).put(1.f);
  b.put(std::uint8_t{3}).put(3).put(2).put(0).put(std::uint16_t{0});
  b.put(std::int8_t{2}).put(0).put(1);
  return b.s;
}

TEST(Ply, BinaryLittleAndBigEndian) {
  for (const bool little : {true, false}) {
    const Scene s = read(binary_ply(little), "ply");
    ASSERT_EQ(s.vertices.size(), 4u) << little;
    expect_vertex(s.vertices[2], 1, 1, static_cast<double>(0.1f));
    expect_vertex(s.vertices[3], 0, 1, -2);
    EXPECT_EQ(s.faces, (Faces{{0, 1, 2, 3}, {3, 2, 0}}));
  }
}

TEST(Ply, BinaryAllScalarTypes) {
  Bytes b;
  b.little = false;
  b.text(
      "ply\nformat binary_big_endian 1.0\n"
      "element vertex 2\n"
      "property char a\nproperty int8 x\nproperty uint16 y\nproperty float64 z\n"
      "property short b\nproperty ushort c\nproperty int d\nproperty uint e\nproperty uint32 f\n"
      "property int16 g\nproperty int32 h\nproperty uint8 i\nproperty float32 j\n"
      "element face 1\nproperty list uint32 int16 vertex_indices\n"
      "end_header\n");
  for (int k = 0; k < 2; ++k) {
    b.put(std::int8_t{1}).put(std::int8_t(-5 + k)).put(std::uint16_t{60000}).put(0.1 * k);
    b.put(std::int16_t{1}).put(std::uint16_t{1}).put(std::int32_t{1}).put(std::uint32_t{1}).put(std::uint32_t{1});
    b.put(std::int16_t{1}).put(std::int32_t{1}).put(std::uint8_t{1}).put(1.0f);
  }
  b.put(std::uint32_t{3}).put(std::int16_t{0}).put(std::int16_t{1}).put(std::int16_t{1});
  const Scene s = read(b.s, "ply");
  expect_vertex(s.vertices[0], -5, 60000, 0);
  expect_vertex(s.vertices[1], -4, 60000, 0.1);
  EXPECT_EQ(s.faces, (Faces{{0, 1, 1}}));
}

TEST(Ply, PointCloudWithoutFaces) {
  const Scene s = read("ply\nformat ascii 1.0\nelement vertex 1\nproperty int x\nproperty int y\n"
                       "property int z\nend_header\n1 2 3\n",
                       "ply");
  EXPECT_EQ(s.vertices.size(), 1u);
  EXPECT_TRUE(s.faces.empty());
}

// --- Malformed inputs ------------------------------------------------------------------

struct BadCase {
  const char* label;
  std::string format;
  std::string bytes;
  std::string prefix;    // the message must start with this (name and place)
  std::string contains;  // and contain this
};

const std::string kTri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
const std::string kOffHead = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n";
const std::string kPlyHead = "ply\nformat ascii 1.0\n";
const std::string kPlyTri =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0\n1 0 0\n0 1 0\n";  // the face line (line 13) follows
const std::string kFacet = "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n";

std::vector<BadCase> bad_cases() {
  std::vector<BadCase> v = {
      // OFF
      {"off empty", "off", "", "bad.off:1: ", "empty file"},
      {"off no header", "off", "3 1 0\n", "bad.off:1: ", "expected the 'OFF' header, found '3'"},
      {"off 4OFF", "off", "4OFF\n0 0 0\n", "bad.off:1: ", "'4OFF': OFF with homogeneous (4OFF)"},
      {"off nOFF", "off", "CnOFF\n0 0 0\n", "bad.off:1: ", "other-dimensional (nOFF) vertices is not read"},
      {"off COFFEE", "off", "COFFEE\n0 0 0\n", "bad.off:1: ", "expected the 'OFF' header, found 'COFFEE'"},
      {"off reversed prefixes", "off", "NCOFF\n0 0 0\n", "bad.off:1: ", "expected the 'OFF' header, found 'NCOFF'"},
      {"off no counts", "off", "OFF\n# nothing\n", "bad.off:2: ", "counts line"},
      {"off count garbage", "off", "OFF\n3x 1 0\n", "bad.off:2: ", "expected the vertex count (a non-negative integer), found '3x'"},
      {"off negative count", "off", "OFF\n-3 1 0\n", "bad.off:2: ", "found '-3'"},
      {"off huge count", "off", "OFF\n99999999999999999999 1 0\n", "bad.off:2: ", "vertex count"},
      {"off counts trailing", "off", "OFF\n3 1 0 junk\n", "bad.off:2: ", "unexpected 'junk'"},
      {"off absurd count vs size", "off", "OFF\n40000000 1 0\n0 0 0\n", "bad.off:2: ", "only 7 bytes follow"},
      {"off truncated vertices", "off", "OFF\n3 1 0\n# padding padding padding padding\n0 0 0\n1 0 0\n",
       "bad.off:5: ", "unexpected end of file: expected 3 vertices, found 2"},
      {"off truncated faces", "off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n# pad pad pad\n", "bad.off:7: ",
       "expected 2 faces, found 1"},
      {"off missing z", "off", "OFF\n3 1 0\n0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "bad.off:3: ",
       "expected the z coordinate of vertex 0 (a number), found end of line"},
      {"off garbage coordinate", "off", "OFF\n3 1 0\n0 0 0\n1 0 0x1\n0 1 0\n3 0 1 2\n", "bad.off:4: ",
       "expected the z coordinate of vertex 1 (a number), found '0x1'"},
      {"off trailing garbage in number", "off", "OFF\n3 1 0\n0 0 0\n1.5.2 0 0\n0 1 0\n3 0 1 2\n", "bad.off:4: ", "'1.5.2'"},
      {"off nan", "off", "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", "bad.off:4: ",
       "the y coordinate of vertex 1 is not a finite number: 'nan'"},
      {"off inf", "off", "OFF\n3 1 0\n0 0 0\n1 0 -inf\n0 1 0\n3 0 1 2\n", "bad.off:4: ", "not a finite number"},
      {"off overflow", "off", "OFF\n3 1 0\n0 0 0\n1e400 0 0\n0 1 0\n3 0 1 2\n", "bad.off:4: ", "not a finite number: '1e400'"},
      {"off index out of range", "off", kOffHead + "3 0 1 3\n", "bad.off:6: ",
       "face 0 has vertex index 3, but there are only 3 vertices"},
      {"off negative index", "off", kOffHead + "3 0 -1 2\n", "bad.off:6: ", "found '-1'"},
      {"off two corners", "off", kOffHead + "2 0 1\n", "bad.off:6: ", "face 0 has 2 corners; a face needs at least 3"},
      {"off missing corner", "off", kOffHead + "4 0 1 2\n", "bad.off:6: ",
       "expected vertex index 3 of face 0 (a non-negative integer), found end of line"},
      {"off corner garbage", "off", kOffHead + "3 0 1 2x\n", "bad.off:6: ", "found '2x'"},
      // OBJ
      {"obj index zero", "obj", kTri + "f 1 2 0\n", "bad.obj:4: ", "vertex index 0"},
      {"obj negative beyond start", "obj", kTri + "f -1 -2 -4\n", "bad.obj:4: ",
       "relative vertex index -4, but only 3 vertices are defined before it"},
      {"obj index past end", "obj", kTri + "f 1 2 4\n# end\n", "bad.obj:4: ",
       "face 0 has vertex index 4, but the file has only 3 vertices"},
      {"obj two corners", "obj", kTri + "\nf 1 2\n", "bad.obj:5: ", "face 0 has 2 corners"},
      {"obj empty face", "obj", kTri + "f\n", "bad.obj:4: ", "0 corners"},
      {"obj too many slashes", "obj", kTri + "f 1/1/1/1 2 3\n", "bad.obj:4: ", "expected a face corner"},
      {"obj bad texture index", "obj", kTri + "f 1/x 2 3\n", "bad.obj:4: ", "'1/x'"},
      {"obj fractional index", "obj", kTri + "f 1.5 2 3\n", "bad.obj:4: ", "'1.5'"},
      {"obj missing coordinate", "obj", "v 0 0\n", "bad.obj:1: ",
       "expected the z coordinate of vertex 1 (a number), found end of line"},
      {"obj garbage coordinate", "obj", "v 0 0 0\nv 0 0 1.5abc\n", "bad.obj:2: ", "'1.5abc'"},
      {"obj nan", "obj", "v 0 nan 0\n", "bad.obj:1: ", "not a finite number"},
      {"obj huge index", "obj", kTri + "f 1 2 99999999999999999999\n", "bad.obj:4: ", "expected a face corner"},
      // STL
      {"stl tiny not solid", "stl", "hello", "bad.stl: ", "not an STL file"},
      {"stl ascii truncated", "stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n",
       "bad.stl:5: ", "expected 'vertex', found end of file"},
      {"stl ascii no endsolid", "stl", "solid t\n" + kFacet, "bad.stl:8: ",
       "expected 'facet' or 'endsolid', found end of file"},
      {"stl ascii bad number", "stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 zz\n", "bad.stl:4: ",
       "expected the z coordinate of triangle 0 vertex 0 (a number), found 'zz'"},
      {"stl ascii nan vertex", "stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 nan 0\n", "bad.stl:4: ",
       "not a finite number"},
      {"stl ascii bad keyword", "stl", "solid t\nfacet normal 0 0 1\nouter loops\n", "bad.stl:3: ",
       "expected 'loop', found 'loops'"},
      {"stl ascii junk after endsolid", "stl", "solid t\n" + kFacet + "endsolid t\njunk\n", "bad.stl:10: ",
       "expected 'solid' or end of file after 'endsolid', found 'junk'"},
      {"stl binary short", "stl", binary_stl("binary", {{0, 0, 0, 1, 0, 0, 0, 1, 0}}, 2), "bad.stl: byte 80: ",
       "header says 2 triangles, which take 184 bytes, but the file has 134 bytes"},
      {"stl binary solid short", "stl", binary_stl("solid x", {{0, 0, 0, 1, 0, 0, 0, 1, 0}}, 3), "bad.stl: byte 80: ",
       "header says 3 triangles"},
      {"stl binary nan", "stl",
       binary_stl("b", {{0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 0, 0, 1, std::numeric_limits<float>::quiet_NaN(), 0, 0, 1, 0}}),
       "bad.stl: byte " + std::to_string(84 + 50 + 12 + 12 + 4) + ": ", "triangle 1 vertex 1 has a non-finite coordinate"},
      // PLY
      {"ply no magic", "ply", "plx\nformat ascii 1.0\n", "bad.ply:1: ", "not a PLY file"},
      {"ply no format", "ply", "ply\nelement vertex 0\nend_header\n", "bad.ply:3: ", "no 'format' line"},
      {"ply bad format", "ply", "ply\nformat binary_middle_endian 1.0\n", "bad.ply:2: ",
       "found 'binary_middle_endian'"},
      {"ply bad version", "ply", "ply\nformat ascii 2.0\n", "bad.ply:2: ", "format version '1.0', found '2.0'"},
      {"ply property first", "ply", kPlyHead + "property float x\n", "bad.ply:3: ", "'property' before any 'element'"},
      {"ply bad type", "ply", kPlyHead + "element vertex 1\nproperty float128 x\n", "bad.ply:4: ", "found 'float128'"},
      {"ply float list count", "ply", kPlyHead + "element face 1\nproperty list float int vertex_indices\n",
       "bad.ply:4: ", "list count type must be an integer"},
      {"ply unknown keyword", "ply", kPlyHead + "elements vertex 1\n", "bad.ply:3: ", "unknown header line 'elements'"},
      {"ply element count garbage", "ply", kPlyHead + "element vertex many\n", "bad.ply:3: ", "found 'many'"},
      {"ply no end_header", "ply", kPlyHead + "element vertex 0\n", "bad.ply:3: ", "expected 'end_header'"},
      {"ply no x", "ply", kPlyHead + "element vertex 1\nproperty float y\nproperty float z\nend_header\n0 0\n",
       "bad.ply:3: ", "element 'vertex' has no property 'x'"},
      {"ply list x", "ply", kPlyHead + "element vertex 1\nproperty list uchar float x\nend_header\n", "bad.ply:4: ",
       "vertex property 'x' must not be a list"},
      {"ply face without indices", "ply",
       kPlyHead + "element vertex 0\nproperty float x\nproperty float y\nproperty float z\nelement face 0\n"
                  "property list uchar int corners\nend_header\n",
       "bad.ply:7: ", "element 'face' has no list property 'vertex_indices'"},
      {"ply float indices", "ply", kPlyHead + "element face 1\nproperty list uchar float vertex_indices\nend_header\n",
       "bad.ply:4: ", "must be a list of an integer type"},
      {"ply absurd count vs size", "ply",
       kPlyHead + "element vertex 1000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n",
       "bad.ply:3: ", "element 'vertex' declares 1000000 records of at least 6 bytes, but only 6 bytes follow the header"},
      {"ply ascii truncated", "ply",
       kPlyHead + "element vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n"
                  "0.000000 0.000000 0.000000\n1.000000 0.000000 0.000000\n",
       "bad.ply:9: ", "unexpected end of file: expected 3 'vertex' records, found 2"},
      {"ply ascii extra value", "ply",
       kPlyHead + "element vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0 7\n",
       "bad.ply:8: ", "unexpected '7' after the properties of 'vertex' record 0"},
      {"ply ascii garbage", "ply",
       kPlyHead + "element vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0e 0\n",
       "bad.ply:8: ", "expected property 'y' of 'vertex' record 0 (a number), found '0e'"},
      {"ply ascii index out of range", "ply", kPlyTri + "3 0 1 3\n", "bad.ply:13: ",
       "face 0 has vertex index 3, but there are only 3 vertices"},
      {"ply ascii negative index", "ply", kPlyTri + "3 0 -1 2\n", "bad.ply:13: ", "face 0 has negative vertex index -1"},
      {"ply ascii two corners", "ply", kPlyTri + "2 0 1\n", "bad.ply:13: ", "face 0 has 2 corners"},
      {"ply ascii short list", "ply", kPlyTri + "4 0 1 2\n", "bad.ply:13: ", "found end of line"},
  };

  // Binary PLY: truncated, nan, index out of range; offsets from the header size.
  const std::string header = binary_ply_header("binary_little_endian", 4, 2);
  const std::string good = binary_ply(true);
  v.push_back({"ply binary truncated", "ply", good.substr(0, good.size() - 3),
               "bad.ply: byte " + std::to_string(good.size() - 8) + ": ",
               "unexpected end of file in property 'ends' of 'edge' record 0"});
  v.push_back({"ply binary cut in vertices", "ply", good.substr(0, header.size() + 20), "bad.ply:3: ",
               "bytes follow the header"});
  std::string nan = good;
  const float qnan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(&nan[header.size() + 13 + 4], &qnan, 4);  // vertex 1, y
  v.push_back({"ply binary nan", "ply", nan, "bad.ply: byte " + std::to_string(header.size() + 17) + ": ",
               "property 'y' of 'vertex' record 1 is not finite"});
  // vismap's JSON scene (.vmscene.json): the line of the problem, and what it is.
  const std::string vs = "{\"vertices\": [[0,0,0],[1,0,0],[0,1,0]],\n";
  for (BadCase c : std::vector<BadCase>{
           {"vmscene not an object", "", "[1]", "bad.vmscene:1: ", "expected '{'"},
           {"vmscene unknown key", "", vs + "\"face\": []}", "bad.vmscene:2: ", "unknown key 'face'"},
           {"vmscene twice", "", vs + "\"faces\": [], \"faces\": []}", "bad.vmscene:2: ", "the key 'faces' appears twice"},
           {"vmscene no faces", "", "{\"vertices\": []}", "bad.vmscene: ", "no \"faces\" key"},
           {"vmscene short vertex", "", "{\"vertices\": [[0,0]]}", "bad.vmscene:1: ", "expected ',' between vertex"},
           {"vmscene string coordinate", "", "{\"vertices\": [[0,\"1\",0]]}", "bad.vmscene:1: ",
            "expected y of vertex 0 (a number), found '\"1\"'"},
           {"vmscene overflow", "", "{\"vertices\": [[0,0,1e999]]}", "bad.vmscene:1: ",
            "z of vertex 0 is '1e999', which is not a finite double"},
           {"vmscene two corners", "", vs + "\"faces\": [[0,1]]}", "bad.vmscene:2: ", "face 0 has 2 corners"},
           {"vmscene negative index", "", vs + "\"faces\": [[0,-1,2]]}", "bad.vmscene:2: ",
            "expected vertex index 1 of face 0 (a non-negative integer), found '-1'"},
           {"vmscene index out of range", "", vs + "\"faces\": [\n[0,1,2],\n[0,1,3]]}", "bad.vmscene:4: ",
            "face 1 has vertex index 3, but there are only 3 vertices"},
           {"vmscene hole out of range", "", vs + "\"faces\": [{\"outer\": [0,1,2], \"holes\": [[0,1,7]]}]}",
            "bad.vmscene:2: ", "hole 0 of face 0 has vertex index 7"},
           {"vmscene no outer", "", vs + "\"faces\": [{\"holes\": []}]}", "bad.vmscene:2: ", "face 0 has no \"outer\" ring"},
           {"vmscene face key", "", vs + "\"faces\": [{\"outer\": [0,1,2], \"hole\": []}]}", "bad.vmscene:2: ",
            "face 0: unknown key 'hole'"},
           {"vmscene trailing", "", vs + "\"faces\": []}\n}", "bad.vmscene:3: ", "expected the end of the file"},
           {"vmscene cut", "", vs + "\"faces\": [[0,1,2]", "bad.vmscene:2: ", "found the end of the file"},
       }) {
    c.format = "vmscene";
    v.push_back(c);
  }
  std::string bad_index = good;
  const std::int32_t nine = 9;
  const std::size_t face0 = header.size() + 4 * 13 + 2 * 10;
  std::memcpy(&bad_index[face0 + 1 + 8], &nine, 4);  // face 0, corner 2
  v.push_back({"ply binary index", "ply", bad_index, "bad.ply: byte " + std::to_string(face0 + 9) + ": ",
               "face 0 has vertex index 9, but there are only 4 vertices"});
  return v;
}

TEST(Malformed, EveryCaseThrowsNamingFileAndPlace) {
  for (const BadCase& c : bad_cases()) {
    const std::string msg = error_of(c.bytes, "bad." + c.format, c.format);
    EXPECT_TRUE(starts_with(msg, c.prefix)) << c.label << ": " << msg;
    EXPECT_NE(msg.find(c.contains), std::string::npos) << c.label << ": " << msg;
  }
}

TEST(Vmscene, FacesWithHolesAnyKeyOrder) {
  const Scene s = vismap::read_scene_bytes(
      "{\"faces\": [[0, 1, 2], {\"holes\": [[4, 5, 6], [4, 6, 7]], \"outer\": [0, 1, 2, 3]}, {\"outer\": [1, 2, 3]}],\n"
      " \"vertices\": [[0, 0, 0], [4, 0, 0], [4, 4, -0.5e1], [0, 4, 1E-3],\n"
      "              [1, 1, 0], [2, 1, 0], [2, 2, 0], [1, 2, 0]]}\n",
      "s.vmscene.json", "vmscene");
  ASSERT_EQ(s.vertices.size(), 8u);
  expect_vertex(s.vertices[2], 4, 4, -5);
  expect_vertex(s.vertices[3], 0, 4, 0.001);
  ASSERT_EQ(s.faces.size(), 3u);
  EXPECT_EQ(s.faces[1], (vismap::IndexRing{0, 1, 2, 3}));
  EXPECT_TRUE(s.holes_of(0).empty());
  ASSERT_EQ(s.holes_of(1).size(), 2u);
  EXPECT_EQ(s.holes_of(1)[1], (vismap::IndexRing{4, 6, 7}));
  EXPECT_TRUE(s.holes_of(2).empty());
  EXPECT_EQ(vismap::sniff_format("  {\"vertices\": []}"), "vmscene");
}

// Absurd counts are refused from the header, before anything is allocated.
TEST(Malformed, LimitsAreEnforced) {
  ReadLimits small;
  small.max_vertices = 3;
  small.max_faces = 1;
  small.max_face_degree = 3;
  EXPECT_EQ(error_of("OFF\n4 1 0\n", "a.off", "off", small), "a.off:2: vertex count 4 exceeds the limit of 3");
  EXPECT_EQ(error_of("OFF\n3 2 0\n", "a.off", "off", small), "a.off:2: face count 2 exceeds the limit of 1");
  EXPECT_TRUE(starts_with(error_of(kOffHead + "4 0 1 2 0\n", "a.off", "off", small), "a.off:6: face 0 has 4 corners"));
  EXPECT_TRUE(starts_with(error_of(kTri + "v 1 1 1\n", "a.obj", "obj", small), "a.obj:4: more than 3 vertices"));
  EXPECT_TRUE(starts_with(error_of(kTri + "f 1 2 3\nf 1 2 3\n", "a.obj", "obj", small), "a.obj:5: more than 1 faces"));
  EXPECT_TRUE(starts_with(error_of(kTri + "f 1 2 3 1\n", "a.obj", "obj", small), "a.obj:4: face 0 has more than 3"));
  EXPECT_TRUE(starts_with(error_of(binary_stl("", {{}, {}}), "a.stl", "stl", small), "a.stl: byte 80: "));
  EXPECT_TRUE(starts_with(error_of("solid\n" + kFacet + kFacet, "a.stl", "stl", small), "a.stl:9: more than 1 triangles"));
  EXPECT_TRUE(starts_with(error_of(kPlyTri + "3 0 1 2\n", "a.ply", "ply", ReadLimits{2, 1, 3}),
                          "a.ply:3: vertex count 3 exceeds the limit of 2"));
  // Within the default limits, but far more than the bytes could hold.
  EXPECT_TRUE(starts_with(error_of("OFF\n49999999 49999999 0\n", "a.off", "off"), "a.off:2: the header promises"));
  EXPECT_TRUE(starts_with(error_of(binary_stl("", {}, 40'000'000), "a.stl", "stl"), "a.stl: byte 80: "));
}

// --- Files ----------------------------------------------------------------------------

TEST(Files, ReadsByExtensionCaseInsensitive) {
  TempDir dir;
  const std::string off = dir.write("m.OFF", kOffHead + "3 0 1 2\n");
  const Scene a = vismap::read_scene(off);
  EXPECT_EQ(a.file, off);
  EXPECT_EQ(a.faces, (Faces{{0, 1, 2}}));
  EXPECT_EQ(vismap::read_scene(dir.write("m.obj", kTri + "f 1 2 3\n")).faces.size(), 1u);
  EXPECT_EQ(vismap::read_scene(dir.write("m.Stl", binary_stl("solid", {{0, 0, 0, 1, 0, 0, 0, 1, 0}}))).faces.size(), 1u);
  EXPECT_EQ(vismap::read_scene(dir.write("m.ply", binary_ply(false))).faces.size(), 2u);
}

TEST(Files, ErrorsNameThePath) {
  TempDir dir;
  auto error = [](const std::string& path) {
    try {
      vismap::read_scene(path);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string missing = (dir.path() / "missing.off").string();
  EXPECT_EQ(error(missing), missing + ": cannot open file: No such file or directory");

  const std::filesystem::path folder = dir.path() / "folder.obj";
  std::filesystem::create_directory(folder);
  EXPECT_EQ(error(folder.string()), folder.string() + ": is a directory, not a mesh file");

  const std::string txt = dir.write("m.txt", "OFF\n0 0 0\n");
  EXPECT_EQ(error(txt), txt + ": unknown file extension '.txt'; expected .off, .obj, .stl, .ply or .vmscene.json (or name the format)");
  const std::string none = dir.write("mesh", "OFF\n0 0 0\n");
  EXPECT_EQ(error(none), none + ": no file extension; expected .off, .obj, .stl, .ply or .vmscene.json (or name the format)");

  const std::string bad = dir.write("bad.off", kOffHead + "3 0 1 7\n");
  EXPECT_EQ(error(bad), bad + ":6: face 0 has vertex index 7, but there are only 3 vertices");

  EXPECT_EQ(error_of("", "x", "gltf"), "x: unknown format 'gltf'; expected off, obj, stl, ply or vmscene");
  EXPECT_EQ(read("OFF\n0 0\n", "OFF").file, "t.OFF");  // format name is case-insensitive too
}

}  // namespace
