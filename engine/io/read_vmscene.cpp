// vismap's own scene format (.vmscene.json; docs/format.md): one JSON object
//   {"vertices": [[x, y, z], ...],
//    "faces": [[i, j, k, ...], {"outer": [i, j, ...], "holes": [[...], ...]}, ...]}
// Coordinates are JSON numbers read as the nearest doubles (as in every
// format); indices count from 0. A face is an index list or an object with
// "outer" and optional "holes". Keys may come in any order; an unknown key, a
// duplicate one, or anything after the object is an error, so that a typo is
// never silently ignored. Indices are checked once all vertices are known.
#include <vector>

#include "engine/io/formats.h"
#include "engine/io/reader_util.h"

namespace vismap::io {
namespace {

// A JSON cursor over the bytes: skips white space, counts lines for messages.
class JsonCursor {
 public:
  JsonCursor(std::string_view text, const std::string& name) : text_(text), name_(name) {}

  std::uint64_t line() const { return line_; }
  std::size_t offset() const { return pos_; }

  // The next non-blank byte without taking it; 0 at the end.
  char peek() {
    skip_blanks();
    return pos_ < text_.size() ? text_[pos_] : '\0';
  }
  void expect(char ch, std::string_view what) {
    if (peek() != ch) fail_expected(what);
    ++pos_;
  }
  // Takes `ch` if it comes next.
  bool take(char ch) {
    if (peek() != ch) return false;
    ++pos_;
    return true;
  }
  // A string's contents (no escapes needed for keys: any escape is refused).
  std::string_view string(std::string_view what) {
    expect('"', what);
    const std::size_t start = pos_;
    while (pos_ < text_.size() && text_[pos_] != '"' && text_[pos_] != '\\' && text_[pos_] != '\n') ++pos_;
    if (pos_ >= text_.size() || text_[pos_] != '"') fail("a key is a plain string on one line, without escapes");
    return text_.substr(start, pos_++ - start);
  }
  // A JSON number token (the characters a number may hold); empty if none.
  std::string_view number_token() {
    skip_blanks();
    const std::size_t start = pos_;
    while (pos_ < text_.size() && is_number_char(text_[pos_])) ++pos_;
    return text_.substr(start, pos_ - start);
  }

  [[noreturn]] void fail(std::string_view msg) const { fail_at_line(name_, line_, msg); }
  [[noreturn]] void fail_expected(std::string_view what) {
    fail(cat("expected ", what, ", found ", found()));
  }
  // The same for a number token already taken (or, when empty, what comes next).
  [[noreturn]] void fail_expected(std::string_view what, std::string_view token) {
    if (token.empty()) fail_expected(what);
    fail(cat("expected ", what, ", found ", quote(token)));
  }
  // The line of the next token (blanks before it skipped).
  std::uint64_t next_line() {
    peek();
    return line_;
  }

 private:
  static bool is_number_char(char ch) {
    return (ch >= '0' && ch <= '9') || ch == '-' || ch == '+' || ch == '.' || ch == 'e' || ch == 'E';
  }
  std::string found() {
    if (pos_ >= text_.size()) return "the end of the file";
    std::size_t end = pos_ + 1;
    while (end < text_.size() && end - pos_ < 20 && text_[end] != '\n' && text_[end] != ' ' && text_[end] != ',')
      ++end;
    return quote(text_.substr(pos_, end - pos_));
  }
  void skip_blanks() {
    while (pos_ < text_.size()) {
      const char ch = text_[pos_];
      if (ch == '\n') ++line_;
      else if (ch != ' ' && ch != '\t' && ch != '\r') break;
      ++pos_;
    }
  }

  std::string_view text_;
  const std::string& name_;
  std::size_t pos_ = 0;
  std::uint64_t line_ = 1;
};

class VmsceneReader {
 public:
  VmsceneReader(std::string_view bytes, const std::string& name, const ReadLimits& limits, Scene& out)
      : c_(bytes, name), name_(name), bytes_(bytes.size()), limits_(limits), out_(out) {}

  void read() {
    c_.expect('{', "'{' (a vmscene file is one JSON object with \"vertices\" and \"faces\")");
    bool have_vertices = false, have_faces = false;
    if (!c_.take('}')) {
      do {
        const std::uint64_t line = c_.next_line();
        const std::string_view key = c_.string("a key in quotes");
        c_.expect(':', "':' after the key");
        bool& seen = key == "vertices" ? have_vertices : have_faces;
        if (key != "vertices" && key != "faces")
          fail_at_line(name_, line, cat("unknown key ", quote(key), "; expected \"vertices\" or \"faces\""));
        if (seen) fail_at_line(name_, line, cat("the key ", quote(key), " appears twice"));
        seen = true;
        if (key == "vertices") vertices();
        else faces();
      } while (c_.take(','));
      c_.expect('}', "',' or '}'");
    }
    if (c_.peek() != '\0') c_.fail_expected("the end of the file after the scene's object");
    if (!have_vertices) fail(name_, "no \"vertices\" key; a vmscene has \"vertices\" and \"faces\"");
    if (!have_faces) fail(name_, "no \"faces\" key; a vmscene has \"vertices\" and \"faces\"");
    check_indices();
  }

 private:
  void vertices() {
    c_.expect('[', "'[' (the list of vertices)");
    if (c_.take(']')) return;
    const std::uint64_t vmax = vertex_limit(limits_);
    do {
      if (out_.vertices.size() >= vmax) c_.fail(cat("vertex count exceeds the limit of ", vmax));
      const std::size_t v = out_.vertices.size();
      c_.expect('[', "'[' (vertex " + std::to_string(v) + " as [x, y, z])");
      Vec3 p;
      p.x = coordinate(v, "x");
      c_.expect(',', "',' between vertex coordinates");
      p.y = coordinate(v, "y");
      c_.expect(',', "',' between vertex coordinates");
      p.z = coordinate(v, "z");
      c_.expect(']', "']' after vertex " + std::to_string(v) + "'s three coordinates");
      out_.vertices.push_back(p);
      check_memory();
    } while (c_.take(','));
    c_.expect(']', "',' or ']' in the list of vertices");
  }

  double coordinate(std::size_t v, const char* axis) {
    const std::string_view tok = c_.number_token();
    double d;
    if (tok.empty() || !parse_double(tok, d) || tok.front() == '+')
      c_.fail_expected(cat(axis, " of vertex ", v, " (a number)"), tok);
    if (!std::isfinite(d)) c_.fail(cat(axis, " of vertex ", v, " is ", quote(tok), ", which is not a finite double"));
    return d;
  }

  void faces() {
    c_.expect('[', "'[' (the list of faces)");
    if (c_.take(']')) return;
    do {
      if (out_.faces.size() >= limits_.max_faces) c_.fail(cat("face count exceeds the limit of ", limits_.max_faces));
      const std::size_t f = out_.faces.size();
      lines_.push_back(c_.next_line());
      if (c_.peek() == '{') face_with_holes(f);
      else out_.faces.push_back(ring("face " + std::to_string(f)));
      check_memory();
    } while (c_.take(','));
    c_.expect(']', "',' or ']' in the list of faces");
  }

  void face_with_holes(std::size_t f) {
    c_.expect('{', "'{'");
    bool have_outer = false, have_holes = false;
    IndexRing outer;
    std::vector<IndexRing> holes;
    if (!c_.take('}')) {
      do {
        const std::uint64_t line = c_.next_line();
        const std::string_view key = c_.string("a key in quotes");
        c_.expect(':', "':' after the key");
        if (key != "outer" && key != "holes")
          fail_at_line(name_, line, cat("face ", f, ": unknown key ", quote(key), "; expected \"outer\" or \"holes\""));
        bool& seen = key == "outer" ? have_outer : have_holes;
        if (seen) fail_at_line(name_, line, cat("face ", f, ": the key ", quote(key), " appears twice"));
        seen = true;
        if (key == "outer") {
          outer = ring("face " + std::to_string(f));
          continue;
        }
        c_.expect('[', "'[' (face " + std::to_string(f) + "'s list of holes)");
        if (c_.take(']')) continue;
        do holes.push_back(ring(cat("hole ", holes.size(), " of face ", f)));
        while (c_.take(','));
        c_.expect(']', "',' or ']' in face " + std::to_string(f) + "'s list of holes");
      } while (c_.take(','));
      c_.expect('}', "',' or '}'");
    }
    if (!have_outer) c_.fail(cat("face ", f, " has no \"outer\" ring"));
    out_.faces.push_back(std::move(outer));
    if (!holes.empty()) {
      out_.holes.resize(f + 1);
      out_.holes[f] = std::move(holes);
    }
  }

  // [i, j, k, ...]: at least three indices.
  IndexRing ring(const std::string& what) {
    c_.expect('[', "'[' (" + what + "'s vertex indices)");
    IndexRing r;
    if (!c_.take(']')) {
      do {
        const std::string_view tok = c_.number_token();
        std::uint64_t i;
        if (tok.empty() || !parse_uint(tok, i) || tok.front() == '+')
          c_.fail_expected(cat("vertex index ", r.size(), " of ", what, " (a non-negative integer)"), tok);
        if (r.size() >= limits_.max_face_degree)
          c_.fail(cat(what, " has more than ", limits_.max_face_degree, " corners, the limit"));
        if (i > 0xffffffffull) c_.fail(cat(what, " has vertex index ", i, ", more than any scene can hold"));
        r.push_back(static_cast<std::uint32_t>(i));
        ++corners_;
      } while (c_.take(','));
      c_.expect(']', "',' or ']' in " + what + "'s vertex indices");
    }
    if (r.size() < 3) c_.fail(cat(what, " has ", r.size(), " corners; a ring needs at least 3"));
    return r;
  }

  void check_memory() {
    if (over_memory(limits_, bytes_, out_.vertices.size(), out_.faces.size(), corners_))
      c_.fail(memory_problem(limits_, bytes_, out_.vertices.size(), out_.faces.size(), corners_, "the scene"));
  }

  // Every index names a vertex (vertices may come after the faces in the file).
  void check_indices() const {
    const std::size_t n = out_.vertices.size();
    auto check = [&](std::size_t f, const IndexRing& r, const std::string& what) {
      for (std::uint32_t i : r)
        if (i >= n)
          fail_at_line(name_, lines_[f], cat(what, " has vertex index ", i, ", but there are only ", n, " vertices"));
    };
    for (std::size_t f = 0; f < out_.faces.size(); ++f) {
      check(f, out_.faces[f], "face " + std::to_string(f));
      const std::vector<IndexRing>& holes = out_.holes_of(f);
      for (std::size_t h = 0; h < holes.size(); ++h) check(f, holes[h], cat("hole ", h, " of face ", f));
    }
  }

  JsonCursor c_;
  const std::string& name_;
  std::uint64_t bytes_;
  const ReadLimits& limits_;
  Scene& out_;
  std::vector<std::uint64_t> lines_;   // the line where each face starts
  std::uint64_t corners_ = 0;
};

}  // namespace

void read_vmscene(std::string_view bytes, const std::string& name, const ReadLimits& limits, Scene& out) {
  VmsceneReader(bytes, name, limits, out).read();
}

}  // namespace vismap::io
