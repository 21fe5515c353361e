#include "engine/io/reader_util.h"

#include <algorithm>
#include <cfenv>
#include <charconv>
#include <cmath>
#include <limits>

namespace vismap::io {

// --- Errors -------------------------------------------------------------------

void fail(const std::string& name, std::string_view msg) {
  throw InputError(cat(name, ": ", msg));
}

void fail_at_line(const std::string& name, std::uint64_t line, std::string_view msg) {
  throw InputError(cat(name, ":", line, ": ", msg));
}

void fail_at_byte(const std::string& name, std::uint64_t offset, std::string_view msg) {
  throw InputError(cat(name, ": byte ", offset, ": ", msg));
}

std::string quote(std::string_view token) {
  constexpr std::size_t kMax = 40;
  std::string s = "'";
  for (std::size_t i = 0; i < token.size() && i < kMax; ++i) {
    const auto ch = static_cast<unsigned char>(token[i]);
    if (ch >= 0x20 && ch < 0x7f) {
      s += static_cast<char>(ch);
    } else {
      constexpr char kHex[] = "0123456789abcdef";
      s += "\\x";
      s += kHex[ch >> 4];
      s += kHex[ch & 15];
    }
  }
  if (token.size() > kMax) s += "...";
  s += '\'';
  return s;
}

std::uint64_t vertex_limit(const ReadLimits& limits) {
  return std::min<std::uint64_t>(limits.max_vertices, std::numeric_limits<std::uint32_t>::max());
}

std::string memory_problem(const ReadLimits& limits, std::uint64_t file_bytes, std::uint64_t vertices,
                           std::uint64_t faces, std::uint64_t corners, std::string_view what) {
  if (!over_memory(limits, file_bytes, vertices, faces, corners)) return {};
  const std::uint64_t need = estimate_memory(file_bytes, vertices, faces, corners);
  return cat(what, " would need about ", format_bytes(need), " of memory, more than the memory limit of ",
             format_bytes(limits.max_memory));
}

// --- Numbers --------------------------------------------------------------------

namespace {

// from_chars does not take a leading '+', strtod does; accept one (not "+-1").
bool strip_plus(const char*& b, const char* e) {
  if (b != e && *b == '+') {
    ++b;
    if (b != e && (*b == '+' || *b == '-')) return false;
  }
  return b != e;
}

// For a syntactically valid decimal that from_chars found out of range: is its
// magnitude >= 1 (overflow) rather than tiny (underflow)? Computes the decimal
// exponent of the leading nonzero digit; the mantissa is nonzero here.
bool magnitude_at_least_one(const char* b, const char* e) {
  if (b != e && *b == '-') ++b;
  bool seen_point = false, seen_nonzero = false;
  std::int64_t int_digits = 0, frac_zeros = 0;
  for (; b != e && *b != 'e' && *b != 'E'; ++b) {
    if (*b == '.') {
      seen_point = true;
    } else if (!seen_nonzero && *b == '0') {
      if (seen_point) ++frac_zeros;
    } else {
      if (!seen_point) ++int_digits;
      seen_nonzero = true;
    }
  }
  // Decimal exponent of the first nonzero digit, before the 'e' part.
  const std::int64_t lead = int_digits > 0 ? int_digits - 1 : -frac_zeros - 1;
  std::int64_t exp = 0;
  if (b != e) {  // exponent, saturated: anything past 1e9 decides the same way
    ++b;
    bool neg = false;
    if (b != e && (*b == '+' || *b == '-')) neg = *b++ == '-';
    for (; b != e; ++b) exp = std::min<std::int64_t>(exp * 10 + (*b - '0'), 1'000'000'000);
    if (neg) exp = -exp;
  }
  return lead + exp >= 0;
}

}  // namespace

bool parse_double(std::string_view token, double& out) {
  const char* b = token.data();
  const char* e = b + token.size();
  if (!strip_plus(b, e)) return false;
  const auto r = std::from_chars(b, e, out);
  if (r.ptr != e) return false;
  if (r.ec == std::errc()) return true;
  if (r.ec != std::errc::result_out_of_range) return false;
  // Nearest double of an out-of-range decimal: +-inf or +-0 (strtod's answer,
  // without strtod's dependence on the C locale's decimal point).
  const double mag = magnitude_at_least_one(b, e) ? std::numeric_limits<double>::infinity() : 0.0;
  out = *b == '-' ? -mag : mag;
  return true;
}

bool parse_int(std::string_view token, std::int64_t& out) {
  const char* b = token.data();
  const char* e = b + token.size();
  if (!strip_plus(b, e)) return false;
  const auto r = std::from_chars(b, e, out);
  return r.ec == std::errc() && r.ptr == e;
}

bool parse_uint(std::string_view token, std::uint64_t& out) {
  const char* b = token.data();
  const char* e = b + token.size();
  if (!strip_plus(b, e)) return false;
  const auto r = std::from_chars(b, e, out);
  return r.ec == std::errc() && r.ptr == e;
}

// --- TextCursor ---------------------------------------------------------------------

TextCursor::TextCursor(std::string_view text, const std::string& name, char comment)
    : text_(text), name_(name), comment_(comment), nearest_(std::fegetround() == FE_TONEAREST) {
  // A UTF-8 byte-order mark is not content.
  if (text_.substr(0, 3) == "\xEF\xBB\xBF") pos_ = 3;
}

void TextCursor::skip_blanks() {
  const char* const b = text_.data();
  std::size_t p = pos_;
  const std::size_t n = text_.size();
  while (p < n && is_blank(b[p])) ++p;
  pos_ = p;
}

namespace {

// A plain decimal ("-12.375": no exponent, no '+') whose digits, the point
// dropped, make an integer below 2^53 with at most 22 of them after the point:
// that integer and 10^k are doubles exactly, so one division rounded to nearest
// is the nearest double to the decimal (Clinger's fast path). Returns where the
// number ends, or nullptr where it is not such a decimal.
const char* plain_decimal(const char* p, const char* e, double& out) {
  const bool negative = p != e && *p == '-';
  if (negative) ++p;
  std::uint64_t m = 0;
  int digits = 0, after = -1;   // (after: digits after the point, -1 before one)
  for (; p != e; ++p) {
    const unsigned d = static_cast<unsigned char>(*p) - unsigned{'0'};
    if (d <= 9) {
      if (++digits > 15) return nullptr;   // (15 digits stay below 2^53)
      m = m * 10 + d;
      if (after >= 0) ++after;
    } else if (*p == '.' && after < 0) {
      after = 0;
    } else {
      break;
    }
  }
  if (digits == 0 || (p != e && (*p == 'e' || *p == 'E'))) return nullptr;
  static constexpr double kTen[] = {1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11,
                                    1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  const double v = after > 0 ? static_cast<double>(m) / kTen[after] : static_cast<double>(m);
  out = negative ? -v : v;
  return p;
}

}  // namespace

bool TextCursor::finite_in_place(double& v) {
  skip_blanks();
  const char* const b = text_.data() + pos_;
  const char* const e = text_.data() + text_.size();
  const char* end = nearest_ ? plain_decimal(b, e, v) : nullptr;
  if (end == nullptr) {
    const auto r = std::from_chars(b, e, v);
    if (r.ec != std::errc() || r.ptr == b) return false;
    end = r.ptr;
  }
  const std::size_t at = pos_ + static_cast<std::size_t>(end - b);
  if (!ends_token(at) || !std::isfinite(v)) return false;
  pos_ = at;
  return true;
}

bool TextCursor::count_in_place(std::uint64_t& out) {
  skip_blanks();
  // Up to 19 digits cannot overflow 64 bits; longer numbers take the general path.
  const char* const b = text_.data() + pos_;
  const char* const e = text_.data() + std::min(text_.size(), pos_ + 19);
  const char* p = b;
  std::uint64_t v = 0;
  for (unsigned d; p != e && (d = static_cast<unsigned char>(*p) - unsigned{'0'}) <= 9; ++p) v = v * 10 + d;
  const std::size_t at = pos_ + static_cast<std::size_t>(p - b);
  if (p == b || !ends_token(at)) return false;
  out = v;
  pos_ = at;
  return true;
}

std::string_view TextCursor::token() {
  skip_blanks();
  const std::size_t start = pos_;
  while (pos_ < text_.size()) {
    const char ch = text_[pos_];
    if (is_blank(ch) || ch == '\n' || is_comment(ch)) break;
    ++pos_;
  }
  return text_.substr(start, pos_ - start);
}

bool TextCursor::at_eol() {
  skip_blanks();
  return eof() || text_[pos_] == '\n' || is_comment(text_[pos_]);
}

void TextCursor::next_line() {
  const std::size_t nl = text_.find('\n', pos_);
  if (nl == std::string_view::npos) {
    pos_ = text_.size();
  } else {
    pos_ = nl + 1;
    ++line_;
  }
}

bool TextCursor::skip_blank_lines() {
  while (at_eol()) {
    if (eof()) return false;
    next_line();
  }
  return true;
}

std::string_view TextCursor::token_any() {
  return skip_blank_lines() ? token() : std::string_view{};
}

void TextCursor::bad_value(std::string_view tok, const std::string& what, Kind kind) const {
  double v;
  if (kind == Kind::kCoordinate && parse_double(tok, v)) fail(cat(what, " is not a finite number: ", quote(tok)));
  const char* type = kind == Kind::kCount     ? " (a non-negative integer)"
                     : kind == Kind::kInteger ? " (an integer)"
                                              : " (a number)";
  fail_expected(cat(what, type), tok);
}

void TextCursor::expect_eol(std::string_view after) {
  if (!at_eol()) fail(cat("unexpected ", quote(token()), " after ", after));
}

void TextCursor::fail(std::string_view msg) const {
  // At EOF after a final newline the cursor sits on a line that does not
  // exist; name the last real line instead.
  std::uint64_t line = line_;
  if (eof() && line > 1 && !text_.empty() && text_.back() == '\n') --line;
  fail_at_line(name_, line, msg);
}

void TextCursor::fail_expected(std::string_view what, std::string_view found) const {
  if (!found.empty()) fail(cat("expected ", what, ", found ", quote(found)));
  fail(cat("expected ", what, ", found end of ", eof() ? "file" : "line"));
}

}  // namespace vismap::io
