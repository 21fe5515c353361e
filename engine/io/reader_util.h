// Shared pieces of the mesh readers: error messages, exact number parsing,
// a line-aware text cursor and little/big-endian loads. Internal to vismap_io.
#pragma once
#include <bit>
#include <cfenv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

#include "engine/scene.h"

namespace vismap::io {

// --- Errors -------------------------------------------------------------------
// Every message starts with the file name as given, then the place, then text:
//   "name: text"  "name:LINE: text"  "name: byte OFFSET: text".
[[noreturn]] void fail(const std::string& name, std::string_view msg);
[[noreturn]] void fail_at_line(const std::string& name, std::uint64_t line, std::string_view msg);
[[noreturn]] void fail_at_byte(const std::string& name, std::uint64_t offset, std::string_view msg);

// A token from the file for a message: single-quoted, cut to a readable length,
// non-printable bytes as \xNN (binary junk must not garble the terminal).
std::string quote(std::string_view token);

// Most vertices a scene can have: the limit, capped so indices fit uint32.
std::uint64_t vertex_limit(const ReadLimits& limits);

// Empty when a scene of this size fits limits.max_memory (estimate_memory);
// otherwise the message: "<what> would need about 1.9 TiB of memory, more than
// the limit of 8 GiB (set with --max-memory)". `what` says what has the size,
// e.g. "the header's 3 vertices and 1000000000 faces".
std::string memory_problem(const ReadLimits& limits, std::uint64_t file_bytes, std::uint64_t vertices,
                           std::uint64_t faces, std::uint64_t corners, std::string_view what);

// For readers that learn the size as they go (OBJ, ASCII STL): a message, or
// empty, for the scene read so far. Cheap; call it per record.
inline bool over_memory(const ReadLimits& limits, std::uint64_t file_bytes, std::uint64_t vertices,
                        std::uint64_t faces, std::uint64_t corners) {
  return limits.max_memory != 0 && estimate_memory(file_bytes, vertices, faces, corners) > limits.max_memory;
}

// --- Numbers --------------------------------------------------------------------
// Whole-token parses; false when the token is not entirely one number.
// parse_double gives the nearest double (from_chars semantics, a leading '+'
// allowed); overflow gives +-inf and underflow +-0, so callers decide on
// finiteness themselves. "nan"/"inf" parse (as from_chars does).
bool parse_double(std::string_view token, double& out);
bool parse_int(std::string_view token, std::int64_t& out);
bool parse_uint(std::string_view token, std::uint64_t& out);

// --- Text ---------------------------------------------------------------------------
// Walks a text buffer token by token, counting lines for messages. Lines end at
// '\n'; '\r' counts as blank so CRLF files read the same. With a comment
// character, everything from it to the end of the line is invisible.
class TextCursor {
 public:
  TextCursor(std::string_view text, const std::string& name, char comment = 0);
  // A piece of a larger text, from the start of its line `first_line` (no
  // byte-order mark looked for): messages name the larger text's lines.
  TextCursor(std::string_view piece, const std::string& name, char comment, std::uint64_t first_line)
      : text_(piece), name_(name), comment_(comment), line_(first_line), nearest_(std::fegetround() == FE_TONEAREST) {}

  const std::string& name() const { return name_; }
  std::uint64_t line() const { return line_; }
  std::size_t offset() const { return pos_; }
  bool eof() const { return pos_ >= text_.size(); }

  // Line mode: tokens of the current line only.
  std::string_view token();  // next token on this line; empty at its end
  bool at_eol();             // nothing but blanks/comment left on this line
  void next_line();          // drop the rest of this line
  bool skip_blank_lines();   // to the next line with a token; false at EOF

  // Stream mode: the next token wherever it is; empty at EOF.
  std::string_view token_any();

  // Typed reads of token(); on failure each throws "expected WHAT (a number),
  // found ...". `what` is a string or, so that the hot path builds no string,
  // a callable returning one, called only on failure.
  template <class What>
  double coordinate(const What& what) {  // a finite double
    double v;
    if (finite_in_place(v)) [[likely]] return v;
    const std::string_view tok = token();
    if (parse_double(tok, v) && std::isfinite(v)) return v;
    bad_value(tok, describe(what), Kind::kCoordinate);
  }
  template <class What>
  double number(const What& what) {  // any double, nan/inf included
    const std::string_view tok = token();
    double v;
    if (parse_double(tok, v)) [[likely]] return v;
    bad_value(tok, describe(what), Kind::kNumber);
  }
  template <class What>
  std::uint64_t count(const What& what) {
    std::uint64_t v;
    if (count_in_place(v)) [[likely]] return v;
    const std::string_view tok = token();
    if (parse_uint(tok, v)) return v;
    bad_value(tok, describe(what), Kind::kCount);
  }
  template <class What>
  std::int64_t integer(const What& what) {
    const std::string_view tok = token();
    std::int64_t v;
    if (parse_int(tok, v)) [[likely]] return v;
    bad_value(tok, describe(what), Kind::kInteger);
  }
  // Throws unless the line is finished; `after` says what came before.
  void expect_eol(std::string_view after);

  [[noreturn]] void fail(std::string_view msg) const;
  [[noreturn]] void fail_expected(std::string_view what, std::string_view found) const;

 private:
  enum class Kind { kCoordinate, kNumber, kCount, kInteger };
  template <class What>
  static std::string describe(const What& what) {
    if constexpr (std::is_invocable_v<const What&>) {
      return std::string(what());
    } else {
      return std::string(std::string_view(what));
    }
  }
  [[noreturn]] void bad_value(std::string_view tok, const std::string& what, Kind kind) const;

  bool is_comment(char ch) const { return comment_ != 0 && ch == comment_; }
  void skip_blanks();
  // The common case of coordinate() and count() without finding the token
  // first (a mesh is millions of them): the number is parsed where it starts,
  // and taken only if it ends where the token does; otherwise the cursor has
  // not moved and the general path (token, then parse) decides, as before.
  bool ends_token(std::size_t at) const {
    return at == text_.size() || is_blank(text_[at]) || text_[at] == '\n' || is_comment(text_[at]);
  }
  static bool is_blank(char ch) { return ch == ' ' || ch == '\t' || ch == '\r' || ch == '\v' || ch == '\f'; }
  bool finite_in_place(double& v);   // (nan and inf too take the general path)
  bool count_in_place(std::uint64_t& v);

  std::string_view text_;
  const std::string& name_;
  char comment_;
  std::size_t pos_ = 0;
  std::uint64_t line_ = 1;
  bool nearest_;   // (the thread rounds to nearest: the plain decimals' fast path is exact)
};

// Builds a message from pieces without iostreams: cat("face ", 3, " has ...").
inline void append_piece(std::string& s, std::string_view v) { s += v; }
inline void append_piece(std::string& s, const char* v) { s += v; }
inline void append_piece(std::string& s, const std::string& v) { s += v; }
inline void append_piece(std::string& s, char v) { s += v; }
template <class Int>
  requires std::is_integral_v<Int>
void append_piece(std::string& s, Int v) {
  s += std::to_string(v);
}
template <class... Ts>
std::string cat(const Ts&... parts) {
  std::string s;
  (append_piece(s, parts), ...);
  return s;
}

// --- Binary -------------------------------------------------------------------------
// Loads a T stored with the given byte order from unaligned bytes.
template <class T>
T load(const char* p, bool little_endian) {
  static_assert(std::is_trivially_copyable_v<T>);
  unsigned char b[sizeof(T)];
  std::memcpy(b, p, sizeof(T));
  if (little_endian != (std::endian::native == std::endian::little)) {
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
  }
  T v;
  std::memcpy(&v, b, sizeof(T));
  return v;
}

// True when `count` items of `each` bytes fit in `budget`; then takes them
// from it. Division first, so absurd header counts cannot overflow.
inline bool take_bytes(std::uint64_t count, std::uint64_t each, std::uint64_t& budget) {
  if (each != 0 && count > budget / each) return false;
  budget -= count * each;
  return true;
}

}  // namespace vismap::io
