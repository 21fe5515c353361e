// STL, binary or ASCII. Every triangle becomes a face with three new vertices
// (a polygon soup: vertices are not merged; the engine does that if it wants).
//
// Binary: 80-byte header, uint32 triangle count, then 50 bytes per triangle
// (normal, 3 vertices as little-endian float32, uint16 attribute). Binary
// files may begin with "solid" too, so the size decides: exactly 84 + 50*count
// bytes means binary; otherwise a file starting with "solid" is ASCII.
#include <algorithm>
#include <cmath>

#include "engine/io/formats.h"
#include "engine/io/reader_util.h"

namespace vismap::io {
namespace {

constexpr std::uint64_t kHeader = 84;
constexpr std::uint64_t kTriangle = 50;

std::uint64_t binary_count(std::string_view bytes) {
  return load<std::uint32_t>(bytes.data() + 80, /*little_endian=*/true);
}

void read_binary(std::string_view bytes, const std::string& name, const ReadLimits& limits, Scene& out) {
  const std::uint64_t n = binary_count(bytes);  // the caller checked the size
  const std::string mem = memory_problem(limits, bytes.size(), 3 * n, n, 3 * n, cat("the header's ", n, " triangles"));
  if (!mem.empty()) fail_at_byte(name, 80, mem);
  if (n > limits.max_faces || 3 * n > vertex_limit(limits)) {
    fail_at_byte(name, 80, cat("binary STL header says ", n, " triangles, more than the limits allow (",
                               limits.max_faces, " faces, ", vertex_limit(limits), " vertices)"));
  }
  out.vertices.reserve(3 * n);
  out.faces.reserve(n);
  for (std::uint64_t t = 0; t < n; ++t) {
    const std::uint64_t at = kHeader + kTriangle * t + 12;  // skip the normal
    for (int k = 0; k < 3; ++k) {
      float xyz[3];
      for (int a = 0; a < 3; ++a) {
        const std::uint64_t off = at + 12 * k + 4 * a;
        xyz[a] = load<float>(bytes.data() + off, /*little_endian=*/true);
        if (!std::isfinite(xyz[a])) {
          fail_at_byte(name, off, cat("triangle ", t, " vertex ", k, " has a non-finite coordinate"));
        }
      }
      out.vertices.push_back({xyz[0], xyz[1], xyz[2]});  // float -> double is exact
    }
    const auto v0 = static_cast<std::uint32_t>(3 * t);
    out.faces.push_back({v0, v0 + 1, v0 + 2});
  }
}

// Keywords are matched case-insensitively: some exporters write "FACET".
bool is_keyword(std::string_view tok, std::string_view kw) {
  if (tok.size() != kw.size()) return false;
  for (std::size_t i = 0; i < tok.size(); ++i) {
    char ch = tok[i];
    if (ch >= 'A' && ch <= 'Z') ch = static_cast<char>(ch - 'A' + 'a');
    if (ch != kw[i]) return false;
  }
  return true;
}

void expect_keyword(TextCursor& c, std::string_view kw) {
  const std::string_view tok = c.token_any();
  if (!is_keyword(tok, kw)) c.fail_expected(cat("'", kw, "'"), tok);
}

// Tokens may be spread over lines any way; "solid"/"endsolid" take the rest of
// their line as the name. Several solids may follow each other.
void read_ascii(std::string_view bytes, const std::string& name, const ReadLimits& limits, Scene& out) {
  TextCursor c(bytes, name);
  expect_keyword(c, "solid");
  c.next_line();
  const std::uint64_t max_triangles = std::min(limits.max_faces, vertex_limit(limits) / 3);
  for (;;) {
    const std::string_view tok = c.token_any();
    if (is_keyword(tok, "endsolid")) {
      c.next_line();
      const std::string_view next = c.token_any();
      if (next.empty()) return;
      if (!is_keyword(next, "solid")) c.fail_expected("'solid' or end of file after 'endsolid'", next);
      c.next_line();
      continue;
    }
    if (!is_keyword(tok, "facet")) c.fail_expected("'facet' or 'endsolid'", tok);
    const std::size_t t = out.faces.size();
    if (t >= max_triangles) c.fail(cat("more than ", max_triangles, " triangles, the limit"));
    expect_keyword(c, "normal");
    for (int a = 0; a < 3; ++a) {
      c.skip_blank_lines();
      c.number([&] { return cat("normal component ", a, " of triangle ", t); });  // unused; may be nan
    }
    expect_keyword(c, "outer");
    expect_keyword(c, "loop");
    const auto v0 = static_cast<std::uint32_t>(out.vertices.size());
    for (int k = 0; k < 3; ++k) {
      expect_keyword(c, "vertex");
      double xyz[3];
      for (int a = 0; a < 3; ++a) {
        c.skip_blank_lines();
        xyz[a] = c.coordinate([&] { return cat("the ", "xyz"[a], " coordinate of triangle ", t, " vertex ", k); });
      }
      out.vertices.push_back({xyz[0], xyz[1], xyz[2]});
    }
    expect_keyword(c, "endloop");
    expect_keyword(c, "endfacet");
    out.faces.push_back({v0, v0 + 1, v0 + 2});
    if (over_memory(limits, bytes.size(), out.vertices.size(), out.faces.size(), 3 * out.faces.size())) {
      c.fail(memory_problem(limits, bytes.size(), out.vertices.size(), out.faces.size(), 3 * out.faces.size(),
                            cat(out.faces.size(), " triangles")));
    }
  }
}

// Starts with "solid" (after blanks), as an ASCII STL must.
bool starts_with_solid(std::string_view bytes) {
  const std::size_t i = bytes.find_first_not_of(" \t\r\n");
  return i != std::string_view::npos && is_keyword(bytes.substr(i, 5), "solid");
}

}  // namespace

void read_stl(std::string_view bytes, const std::string& name, const ReadLimits& limits, Scene& out) {
  const std::uint64_t size = bytes.size();
  if (size >= kHeader) {
    const std::uint64_t n = binary_count(bytes);
    if (kHeader + kTriangle * n == size) return read_binary(bytes, name, limits, out);
    // A "solid" file with NUL bytes near the start is a binary STL with a
    // wrong count, not ASCII: say so rather than report odd ASCII errors.
    const bool text = bytes.substr(0, 4096).find('\0') == std::string_view::npos;
    if (!starts_with_solid(bytes) || !text) {
      fail_at_byte(name, 80, cat("binary STL header says ", n, " triangles, which take ", kHeader + kTriangle * n,
                                 " bytes, but the file has ", size, " bytes"));
    }
  } else if (!starts_with_solid(bytes)) {
    fail(name, cat("not an STL file: ", size, " bytes is too short for binary STL (84 at least) and it does not "
                   "start with 'solid'"));
  }
  read_ascii(bytes, name, limits, out);
}

}  // namespace vismap::io
