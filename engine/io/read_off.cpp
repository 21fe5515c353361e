// OFF: "OFF" header (counts may follow on the same line), "nv nf [ne]", then
// one vertex "x y z ..." per line and one face "n i1 .. in ..." per line.
// '#' starts a comment; blank lines are skipped; values after the ones we need
// (vertex colours, face colours) are ignored, as is anything after the faces.
#include <algorithm>
#include <vector>

#include "engine/io/formats.h"
#include "engine/io/reader_util.h"

namespace vismap::io {

void read_off(std::string_view bytes, const std::string& name, const ReadLimits& limits, Scene& out) {
  TextCursor c(bytes, name, '#');
  if (!c.skip_blank_lines()) c.fail("empty file; expected the 'OFF' header");
  const std::string_view magic = c.token();
  if (magic != "OFF") c.fail(cat("expected the 'OFF' header, found ", quote(magic)));
  if (c.at_eol()) {
    c.next_line();
    if (!c.skip_blank_lines()) c.fail("expected the counts line 'vertices faces edges', found end of file");
  }
  const std::uint64_t nv = c.count("the vertex count");
  const std::uint64_t nf = c.count("the face count");
  if (!c.at_eol()) c.count("the edge count");  // unused, and often omitted
  c.expect_eol("the counts 'vertices faces edges'");

  // Refuse impossible counts before allocating: over the limits, or more than
  // the rest of the file could hold ("0 0 0\n" is 6 bytes, "3 0 1 2\n" is 8;
  // the last line may lack its newline).
  const std::string mem = memory_problem(limits, bytes.size(), nv, nf, 3 * std::min<std::uint64_t>(nf, ~0ull / 4),
                                         cat("the header's ", nv, " vertices and ", nf, " faces"));
  if (!mem.empty()) c.fail(mem);
  if (nv > vertex_limit(limits)) c.fail(cat("vertex count ", nv, " exceeds the limit of ", vertex_limit(limits)));
  if (nf > limits.max_faces) c.fail(cat("face count ", nf, " exceeds the limit of ", limits.max_faces));
  std::uint64_t budget = bytes.size() - c.offset() + 1;
  if (!take_bytes(nv, 6, budget) || !take_bytes(nf, 8, budget)) {
    c.fail(cat("the header promises ", nv, " vertices and ", nf, " faces, but only ",
               bytes.size() - c.offset(), " bytes follow"));
  }
  c.next_line();

  out.vertices.reserve(nv);
  for (std::uint64_t i = 0; i < nv; ++i) {
    if (!c.skip_blank_lines()) c.fail(cat("unexpected end of file: expected ", nv, " vertices, found ", i));
    double xyz[3];
    for (int a = 0; a < 3; ++a) {
      xyz[a] = c.coordinate([&] { return cat("the ", "xyz"[a], " coordinate of vertex ", i); });
    }
    out.vertices.push_back({xyz[0], xyz[1], xyz[2]});
    c.next_line();
  }

  out.faces.reserve(nf);
  std::vector<std::uint32_t> corners;  // reused; grows only with indices actually read
  for (std::uint64_t f = 0; f < nf; ++f) {
    if (!c.skip_blank_lines()) c.fail(cat("unexpected end of file: expected ", nf, " faces, found ", f));
    const std::uint64_t n = c.count([&] { return cat("the corner count of face ", f); });
    if (n < 3) c.fail(cat("face ", f, " has ", n, " corners; a face needs at least 3"));
    if (n > limits.max_face_degree) {
      c.fail(cat("face ", f, " has ", n, " corners, more than the limit of ", limits.max_face_degree));
    }
    corners.clear();
    for (std::uint64_t k = 0; k < n; ++k) {
      const std::uint64_t idx = c.count([&] { return cat("vertex index ", k, " of face ", f); });
      if (idx >= nv) c.fail(cat("face ", f, " has vertex index ", idx, ", but there are only ", nv, " vertices"));
      corners.push_back(static_cast<std::uint32_t>(idx));
    }
    out.faces.emplace_back(corners.begin(), corners.end());
    c.next_line();
  }
}

}  // namespace vismap::io
