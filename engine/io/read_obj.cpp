// Wavefront OBJ: only "v x y z [w]" and "f c1 c2 c3 ..." matter. A corner is
// "i", "i/t", "i//n" or "i/t/n"; i counts from 1, or back from the last vertex
// defined so far when negative (-1 = the latest). Every other record (vt, vn,
// vp, g, o, s, usemtl, mtllib, l, p, unknown ones) is skipped; '#' starts a
// comment. Faces are numbered in the order of their "f" lines. A positive
// index may refer to a vertex defined later in the file (checked at the end).
// A line ending in a backslash continues on the next line (OBJ spec).
// A record's keyword must look like one (letters, digits, '_', starting with a
// letter or '_'), so that binary junk is an error rather than an empty scene;
// and a file with no record at all (empty, or only blanks and comments) is an
// error too.
#include <vector>

#include "engine/io/formats.h"
#include "engine/io/reader_util.h"

namespace vismap::io {
namespace {

// Joins backslash-continued lines. The swallowed newlines are put back after
// the logical line, so every later line keeps its number and an error inside
// a joined line names its first physical line.
std::string join_continued_lines(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  std::size_t pending = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char ch = s[i];
    if (ch == '\\') {
      std::size_t j = i + 1;
      while (j < s.size() && (s[j] == ' ' || s[j] == '\t' || s[j] == '\r')) ++j;
      if (j == s.size() || s[j] == '\n') {
        out += ' ';
        if (j < s.size()) ++pending;
        i = j;
        continue;
      }
    }
    out += ch;
    if (ch == '\n') {
      out.append(pending, '\n');
      pending = 0;
    }
  }
  out.append(pending, '\n');
  return out;
}

// The vertex part of a face corner; the texture and normal parts, when
// present, must be integers too but are not used.
std::int64_t corner_vertex(const TextCursor& c, std::string_view tok) {
  std::int64_t v = 0, unused = 0;
  const std::size_t s1 = tok.find('/');
  bool ok = parse_int(tok.substr(0, s1), v);
  if (ok && s1 != std::string_view::npos) {
    const std::string_view rest = tok.substr(s1 + 1);
    const std::size_t s2 = rest.find('/');
    const std::string_view t = rest.substr(0, s2);
    if (s2 == std::string_view::npos) {
      ok = parse_int(t, unused);  // i/t
    } else {                      // i//n or i/t/n
      ok = (t.empty() || parse_int(t, unused)) && parse_int(rest.substr(s2 + 1), unused);
    }
  }
  if (!ok) c.fail_expected("a face corner 'i', 'i/t', 'i//n' or 'i/t/n' (integers)", tok);
  return v;
}

// What an OBJ keyword looks like: [A-Za-z_][A-Za-z0-9_]*.
bool is_keyword(std::string_view tok) {
  if (tok.empty()) return false;
  for (std::size_t i = 0; i < tok.size(); ++i) {
    const char ch = tok[i];
    const bool letter = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || ch == '_';
    if (!letter && !(i > 0 && ch >= '0' && ch <= '9')) return false;
  }
  return true;
}

}  // namespace

void read_obj(std::string_view bytes, const std::string& name, const ReadLimits& limits, Scene& out) {
  std::string joined;
  if (bytes.find('\\') != std::string_view::npos) {
    joined = join_continued_lines(bytes);
    bytes = joined;
  }
  TextCursor c(bytes, name, '#');
  const std::uint64_t vmax = vertex_limit(limits);

  // Positive indices past the vertices read so far, checked once all are read.
  struct Forward {
    std::uint64_t line;
    std::size_t face;
    std::int64_t index;
  };
  std::vector<Forward> forward;
  std::vector<std::uint32_t> corners;  // reused between faces
  std::uint64_t corner_total = 0;
  auto check_memory = [&] {
    if (over_memory(limits, bytes.size(), out.vertices.size(), out.faces.size(), corner_total)) {
      c.fail(memory_problem(limits, bytes.size(), out.vertices.size(), out.faces.size(), corner_total,
                            cat(out.vertices.size(), " vertices and ", out.faces.size(), " faces")));
    }
  };

  bool any_record = false;
  while (c.skip_blank_lines()) {
    const std::string_view keyword = c.token();
    if (!is_keyword(keyword)) c.fail_expected("an OBJ record such as 'v' or 'f'", keyword);
    any_record = true;
    if (keyword == "v") {
      const std::size_t i = out.vertices.size() + 1;  // OBJ numbering in messages
      if (i > vmax) c.fail(cat("more than ", vmax, " vertices, the limit"));
      double xyz[3];
      for (int a = 0; a < 3; ++a) {
        xyz[a] = c.coordinate([&] { return cat("the ", "xyz"[a], " coordinate of vertex ", i); });
      }
      out.vertices.push_back({xyz[0], xyz[1], xyz[2]});  // w and any vertex colour are ignored
      check_memory();
    } else if (keyword == "f") {
      const std::size_t f = out.faces.size();
      if (f >= limits.max_faces) c.fail(cat("more than ", limits.max_faces, " faces, the limit"));
      const std::uint64_t defined = out.vertices.size();
      corners.clear();
      for (std::string_view tok = c.token(); !tok.empty(); tok = c.token()) {
        if (corners.size() >= limits.max_face_degree) {
          c.fail(cat("face ", f, " has more than ", limits.max_face_degree, " corners, the limit"));
        }
        const std::int64_t v = corner_vertex(c, tok);
        std::uint64_t idx = 0;
        if (v > 0) {
          idx = static_cast<std::uint64_t>(v) - 1;
          if (idx >= vmax) c.fail(cat("face ", f, " has vertex index ", v, ", beyond the limit of ", vmax, " vertices"));
          if (idx >= defined) forward.push_back({c.line(), f, v});
        } else if (v < 0) {
          if (v < -static_cast<std::int64_t>(defined)) {
            c.fail(cat("face ", f, " has relative vertex index ", v, ", but only ", defined,
                       " vertices are defined before it"));
          }
          idx = defined - static_cast<std::uint64_t>(-v);
        } else {
          c.fail(cat("face ", f, " has vertex index 0; OBJ indices start at 1 (negative ones count back)"));
        }
        corners.push_back(static_cast<std::uint32_t>(idx));
      }
      if (corners.size() < 3) c.fail(cat("face ", f, " has ", corners.size(), " corners; a face needs at least 3"));
      out.faces.emplace_back(corners.begin(), corners.end());
      corner_total += corners.size();
      check_memory();
    }
    c.next_line();
  }

  if (!any_record) c.fail("no OBJ records (an empty file, or only comments); expected 'v' and 'f' lines");

  for (const Forward& fw : forward) {
    if (static_cast<std::uint64_t>(fw.index) > out.vertices.size()) {
      fail_at_line(name, fw.line, cat("face ", fw.face, " has vertex index ", fw.index, ", but the file has only ",
                                      out.vertices.size(), " vertices"));
    }
  }
}

}  // namespace vismap::io
