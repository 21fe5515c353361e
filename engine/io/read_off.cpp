// OFF: "OFF" header (or COFF, NOFF, STOFF...: is_off_header; counts may follow
// on the same line), "nv nf [ne]", then one vertex "x y z ..." per line and one
// face "n i1 .. in ..." per line. '#' starts a comment; blank lines are skipped;
// values after the ones we need (vertex colours, normals and texture
// coordinates, face colours) are ignored, as is anything after the faces.
#include <algorithm>
#include <exception>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "engine/io/formats.h"
#include "engine/io/reader_util.h"

namespace vismap::io {
namespace {

// The vertices and faces after the counts line are records: the lines with a
// token, record r vertex r (r < nv), then face r - nv.
struct Records {
  const std::string& name;
  const ReadLimits& limits;
  std::uint64_t nv, nf;
  Scene& out;   // (vertices and faces already sized)

  void vertex(TextCursor& c, std::uint64_t i) const {
    double xyz[3];
    for (int a = 0; a < 3; ++a) {
      xyz[a] = c.coordinate([&] { return cat("the ", "xyz"[a], " coordinate of vertex ", i); });
    }
    out.vertices[i] = {xyz[0], xyz[1], xyz[2]};
  }

  void face(TextCursor& c, std::uint64_t f, std::vector<std::uint32_t>& corners) const {
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
    out.faces[f].assign(corners.begin(), corners.end());
  }

  // Reads records from number r on, until the cursor's text ends or the faces
  // do; returns the number of the next record.
  std::uint64_t read(TextCursor& c, std::uint64_t r) const {
    std::vector<std::uint32_t> corners;  // reused; grows only with indices actually read
    for (; r < nv + nf && c.skip_blank_lines(); ++r) {
      if (r < nv) vertex(c, r);
      else face(c, r - nv, corners);
      c.next_line();
    }
    return r;
  }
};

// The records of body, a whole number of lines from line `line`: in one piece,
// or where it is large and threads are given, in pieces of whole lines side by
// side (the records of each counted first, so that each knows its first
// record's number). Throws the first error in the file's order, as one piece
// would. Returns the number of records read and sets `line` to the body's end.
std::uint64_t read_body(std::string_view body, std::uint64_t& line, const Records& rec) {
  int pieces = 1;
#ifdef _OPENMP
  // (Bytes a piece is worth a thread for: ~0.5 ms of parsing. The pieces are
  // handed out one at a time: several per thread even out a thread that starts late.)
  const std::size_t least = std::size_t{1} << 18;
  if (rec.limits.threads > 1 && body.size() >= 2 * least)
    pieces = static_cast<int>(std::min<std::size_t>(4 * static_cast<std::size_t>(rec.limits.threads), body.size() / least));
#endif
  if (pieces == 1) {
    TextCursor c(body, rec.name, '#', line);
    const std::uint64_t r = rec.read(c, 0);
    line = c.line();
    return r;
  }
  std::vector<std::size_t> start(static_cast<std::size_t>(pieces) + 1, body.size());
  start[0] = 0;
  for (int k = 1; k < pieces; ++k) {
    const std::size_t nl = body.find('\n', std::max(start[k - 1], body.size() / pieces * k));
    start[k] = nl == std::string_view::npos ? body.size() : nl + 1;
  }
  auto piece = [&](int k) { return body.substr(start[k], start[k + 1] - start[k]); };
  // Each piece's lines and records, then where each starts.
  std::vector<std::uint64_t> lines(pieces + 1, 0), records(pieces + 1, 0);
#pragma omp parallel for num_threads(rec.limits.threads) schedule(dynamic, 1)
  for (int k = 0; k < pieces; ++k) {
    TextCursor c(piece(k), rec.name, '#', 0);
    std::uint64_t n = 0;
    for (; c.skip_blank_lines(); ++n) c.next_line();
    lines[k + 1] = c.line();
    records[k + 1] = n;
  }
  lines[0] = line;
  for (int k = 0; k < pieces; ++k) {
    lines[k + 1] += lines[k];
    records[k + 1] += records[k];
  }
  std::vector<std::exception_ptr> error(pieces);
#pragma omp parallel for num_threads(rec.limits.threads) schedule(dynamic, 1)
  for (int k = 0; k < pieces; ++k) {
    if (records[k] >= rec.nv + rec.nf) continue;   // (past the faces)
    try {
      TextCursor c(piece(k), rec.name, '#', lines[k]);
      rec.read(c, records[k]);
    } catch (...) {
      error[k] = std::current_exception();
    }
  }
  for (const std::exception_ptr& e : error)
    if (e) std::rethrow_exception(e);
  line = lines[pieces];
  return std::min(records[pieces], rec.nv + rec.nf);
}

}  // namespace

bool is_off_header(std::string_view word) {
  auto take = [&](std::string_view prefix) {
    if (word.substr(0, prefix.size()) == prefix) word.remove_prefix(prefix.size());
  };
  take("ST");
  take("C");
  take("N");
  return word == "OFF";
}

void read_off(std::string_view bytes, const std::string& name, const ReadLimits& limits, Scene& out) {
  TextCursor c(bytes, name, '#');
  if (!c.skip_blank_lines()) c.fail("empty file; expected the 'OFF' header");
  const std::string_view magic = c.token();
  const bool other_dimension = magic.size() > 3 && magic.substr(magic.size() - 3) == "OFF" &&
                               magic.substr(0, magic.size() - 3).find_first_not_of("STCN4n") == std::string_view::npos &&
                               magic.find_first_of("4n") != std::string_view::npos;
  if (other_dimension)
    c.fail(cat(quote(magic), ": OFF with homogeneous (4OFF) or other-dimensional (nOFF) vertices is not read; "
               "convert it to OFF"));
  if (!is_off_header(magic)) c.fail(cat("expected the 'OFF' header, found ", quote(magic)));
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

  out.vertices.resize(nv);
  out.faces.resize(nf);
  std::uint64_t line = c.line();
  const std::uint64_t read = read_body(bytes.substr(c.offset()), line, Records{name, limits, nv, nf, out});
  if (read < nv + nf) {
    // At the end of the file: after a final newline, name the last real line.
    if (line > 1 && !bytes.empty() && bytes.back() == '\n') --line;
    fail_at_line(name, line, read < nv ? cat("unexpected end of file: expected ", nv, " vertices, found ", read)
                                       : cat("unexpected end of file: expected ", nf, " faces, found ", read - nv));
  }
}

}  // namespace vismap::io
