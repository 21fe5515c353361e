// PLY (ASCII, binary little- or big-endian). The header declares elements and
// their properties; we take x, y, z from element "vertex" (any scalar types, any
// order) and the list "vertex_indices" (or "vertex_index") from element "face".
// Every other property and element is read past. In ASCII each record is one
// line (blank lines skipped); in binary, records are packed after the header.
#include <algorithm>
#include <optional>
#include <vector>

#include "engine/io/formats.h"
#include "engine/io/reader_util.h"

namespace vismap::io {
namespace {

enum class Type : std::uint8_t { kInt8, kUInt8, kInt16, kUInt16, kInt32, kUInt32, kFloat32, kFloat64 };

std::optional<Type> parse_type(std::string_view s) {
  if (s == "char" || s == "int8") return Type::kInt8;
  if (s == "uchar" || s == "uint8") return Type::kUInt8;
  if (s == "short" || s == "int16") return Type::kInt16;
  if (s == "ushort" || s == "uint16") return Type::kUInt16;
  if (s == "int" || s == "int32") return Type::kInt32;
  if (s == "uint" || s == "uint32") return Type::kUInt32;
  if (s == "float" || s == "float32") return Type::kFloat32;
  if (s == "double" || s == "float64") return Type::kFloat64;
  return std::nullopt;
}

std::uint64_t size_of(Type t) {
  switch (t) {
    case Type::kInt8: case Type::kUInt8: return 1;
    case Type::kInt16: case Type::kUInt16: return 2;
    case Type::kInt32: case Type::kUInt32: case Type::kFloat32: return 4;
    case Type::kFloat64: return 8;
  }
  return 0;
}

bool is_integer(Type t) { return t != Type::kFloat32 && t != Type::kFloat64; }

struct Property {
  std::string name;
  Type type = Type::kFloat32;  // the item type for a list
  bool list = false;
  Type count_type = Type::kUInt8;
  std::uint64_t line = 0;  // header line, for messages
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> props;
  std::uint64_t line = 0;

  // Smallest record: what a binary record takes with every list empty.
  std::uint64_t min_binary_size() const {
    std::uint64_t n = 0;
    for (const Property& p : props) n += size_of(p.list ? p.count_type : p.type);
    return n;
  }
  bool fixed_size() const {
    for (const Property& p : props) {
      if (p.list) return false;
    }
    return true;
  }
};

enum class Encoding { kAscii, kBinaryLittle, kBinaryBig };

struct Header {
  Encoding encoding = Encoding::kAscii;
  std::vector<Element> elements;
  std::size_t data_start = 0;  // byte offset just past "end_header\n"
};

Header read_header(TextCursor& c) {
  if (c.token() != "ply" || !c.at_eol()) fail_at_line(c.name(), 1, "not a PLY file: the first line must be 'ply'");
  c.next_line();
  Header h;
  bool have_format = false;
  for (;;) {
    if (!c.skip_blank_lines()) c.fail("unexpected end of file in the header; expected 'end_header'");
    const std::string_view kw = c.token();
    if (kw == "format") {
      const std::string_view enc = c.token();
      if (enc == "ascii") {
        h.encoding = Encoding::kAscii;
      } else if (enc == "binary_little_endian") {
        h.encoding = Encoding::kBinaryLittle;
      } else if (enc == "binary_big_endian") {
        h.encoding = Encoding::kBinaryBig;
      } else {
        c.fail_expected("'ascii', 'binary_little_endian' or 'binary_big_endian'", enc);
      }
      const std::string_view version = c.token();
      if (version != "1.0") c.fail_expected("format version '1.0'", version);
      c.expect_eol("the format line");
      have_format = true;
    } else if (kw == "comment" || kw == "obj_info") {
      // free text
    } else if (kw == "element") {
      Element e;
      e.name = c.token();
      if (e.name.empty()) c.fail_expected("an element name", e.name);
      e.count = c.count("the element count");
      c.expect_eol("the element count");
      e.line = c.line();
      h.elements.push_back(std::move(e));
    } else if (kw == "property") {
      if (h.elements.empty()) c.fail("'property' before any 'element'");
      Property p;
      p.line = c.line();
      auto type = [&c] {
        const std::string_view tok = c.token();
        const std::optional<Type> t = parse_type(tok);
        if (!t) c.fail_expected("a property type (char, uchar, short, ushort, int, uint, float, double, int8, ..., float64)", tok);
        return *t;
      };
      std::string_view first = c.token();
      if (first == "list") {
        p.list = true;
        p.count_type = type();
        p.type = type();
        if (!is_integer(p.count_type)) c.fail("a list count type must be an integer type");
      } else {
        const std::optional<Type> t = parse_type(first);
        if (!t) c.fail_expected("'list' or a property type (char, uchar, short, ushort, int, uint, float, double, int8, ..., float64)", first);
        p.type = *t;
      }
      p.name = c.token();
      if (p.name.empty()) c.fail_expected("a property name", p.name);
      c.expect_eol("the property name");
      h.elements.back().props.push_back(std::move(p));
    } else if (kw == "end_header") {
      c.expect_eol("'end_header'");
      if (!have_format) c.fail("no 'format' line before 'end_header'");
      c.next_line();
      h.data_start = c.offset();
      return h;
    } else {
      c.fail(cat("unknown header line ", quote(kw), "; expected format, comment, obj_info, element, property or end_header"));
    }
    c.next_line();
  }
}

// What we take from the file: which element and properties hold the geometry.
struct Roles {
  const Element* vertex = nullptr;
  int xyz[3] = {-1, -1, -1};  // property positions of x, y, z in vertex
  const Element* face = nullptr;
  int indices = -1;  // property position of the index list in face
};

Roles find_roles(const Header& h, const std::string& name) {
  Roles r;
  for (const Element& e : h.elements) {
    if (e.name == "vertex") {
      if (r.vertex) fail_at_line(name, e.line, "a second element 'vertex'");
      r.vertex = &e;
      for (int a = 0; a < 3; ++a) {
        const std::string_view axis = std::string_view("xyz").substr(a, 1);
        for (std::size_t j = 0; j < e.props.size(); ++j) {
          if (e.props[j].name != axis) continue;
          if (e.props[j].list) fail_at_line(name, e.props[j].line, cat("vertex property '", axis, "' must not be a list"));
          r.xyz[a] = static_cast<int>(j);
        }
        if (r.xyz[a] < 0) fail_at_line(name, e.line, cat("element 'vertex' has no property '", axis, "'"));
      }
    } else if (e.name == "face") {
      if (r.face) fail_at_line(name, e.line, "a second element 'face'");
      r.face = &e;
      for (std::size_t j = 0; j < e.props.size(); ++j) {
        const Property& p = e.props[j];
        if (p.name != "vertex_indices" && p.name != "vertex_index") continue;
        if (!p.list || !is_integer(p.type)) {
          fail_at_line(name, p.line, cat("face property '", p.name, "' must be a list of an integer type"));
        }
        r.indices = static_cast<int>(j);
      }
      if (r.indices < 0) fail_at_line(name, e.line, "element 'face' has no list property 'vertex_indices'");
    }
  }
  return r;
}

// Refuses counts over the limits or beyond what the rest of the file can hold,
// before anything is allocated for them.
void check_counts(const Header& h, const Roles& r, std::uint64_t file_size, const std::string& name,
                  const ReadLimits& limits) {
  const std::uint64_t nv = r.vertex ? r.vertex->count : 0, nf = r.face ? r.face->count : 0;
  const std::string mem = memory_problem(limits, file_size, nv, nf, 3 * std::min<std::uint64_t>(nf, ~0ull / 4),
                                         cat("the header's ", nv, " vertices and ", nf, " faces"));
  if (!mem.empty()) {
    std::uint64_t line = 1;  // the later of the two element lines
    if (r.vertex) line = r.vertex->line;
    if (r.face && r.face->line > line) line = r.face->line;
    fail_at_line(name, line, mem);
  }
  if (r.vertex && r.vertex->count > vertex_limit(limits)) {
    fail_at_line(name, r.vertex->line,
                 cat("vertex count ", r.vertex->count, " exceeds the limit of ", vertex_limit(limits)));
  }
  if (r.face && r.face->count > limits.max_faces) {
    fail_at_line(name, r.face->line, cat("face count ", r.face->count, " exceeds the limit of ", limits.max_faces));
  }
  // ASCII: each value takes a character and a separator; the last newline may
  // be missing, hence the +1.
  const bool ascii = h.encoding == Encoding::kAscii;
  const std::uint64_t available = file_size - h.data_start;
  std::uint64_t budget = available + (ascii ? 1 : 0);
  for (const Element& e : h.elements) {
    const std::uint64_t each = ascii ? 2 * e.props.size() : e.min_binary_size();
    if (!take_bytes(e.count, each, budget)) {
      fail_at_line(name, e.line, cat("element '", e.name, "' declares ", e.count, " records of at least ", each,
                                     " bytes, but only ", available, " bytes follow the header"));
    }
  }
}

// Record reader for ASCII bodies: one record per line.
class AsciiBody {
 public:
  explicit AsciiBody(TextCursor& c) : c_(c) {}

  void begin_record(const Element& e, std::uint64_t i) {
    if (!c_.skip_blank_lines()) {
      c_.fail(cat("unexpected end of file: expected ", e.count, " '", e.name, "' records, found ", i));
    }
  }
  void end_record(const Element& e, std::uint64_t i) {
    c_.expect_eol(cat("the properties of '", e.name, "' record ", i));
    c_.next_line();
  }
  double coordinate(Type, const Element& e, const Property& p, std::uint64_t i) {
    return c_.coordinate([&] { return cat("property '", p.name, "' of '", e.name, "' record ", i); });
  }
  // List counts and indices.
  std::int64_t integer(Type, const Element& e, const Property& p, std::uint64_t i) {
    return c_.integer([&] { return cat("an entry of list '", p.name, "' of '", e.name, "' record ", i); });
  }
  void skip_property(const Element& e, const Property& p, std::uint64_t i) {
    auto what = [&] { return cat("property '", p.name, "' of '", e.name, "' record ", i); };
    if (!p.list) {
      c_.number(what);
      return;
    }
    const std::uint64_t n = c_.count(what);
    for (std::uint64_t k = 0; k < n; ++k) c_.number(what);  // ends early at end of line
  }
  bool skip_fixed_element(const Element&) { return false; }
  [[noreturn]] void fail(std::string_view msg) const { c_.fail(msg); }

 private:
  TextCursor& c_;
};

// Record reader for binary bodies; messages give the offset of the value.
class BinaryBody {
 public:
  BinaryBody(std::string_view bytes, std::size_t start, bool little, const std::string& name)
      : bytes_(bytes), pos_(start), value_pos_(start), little_(little), name_(name) {}

  void begin_record(const Element&, std::uint64_t) {}
  void end_record(const Element&, std::uint64_t) {}

  double coordinate(Type t, const Element& e, const Property& p, std::uint64_t i) {
    const double v = read(t, e, p, i);
    if (!std::isfinite(v)) fail(cat("property '", p.name, "' of '", e.name, "' record ", i, " is not finite"));
    return v;
  }
  std::int64_t integer(Type t, const Element& e, const Property& p, std::uint64_t i) {
    return static_cast<std::int64_t>(read(t, e, p, i));  // integer types only: exact
  }
  void skip_property(const Element& e, const Property& p, std::uint64_t i) {
    if (!p.list) {
      need(size_of(p.type), e, p, i);
      pos_ += size_of(p.type);
      return;
    }
    const std::int64_t n = integer(p.count_type, e, p, i);
    if (n < 0) fail(cat("list '", p.name, "' of '", e.name, "' record ", i, " has negative length ", n));
    std::uint64_t left = bytes_.size() - pos_;
    value_pos_ = pos_;  // the list items
    if (!take_bytes(static_cast<std::uint64_t>(n), size_of(p.type), left)) truncated(e, p, i);
    pos_ += static_cast<std::uint64_t>(n) * size_of(p.type);
  }
  // Elements without lists are skipped in one step.
  bool skip_fixed_element(const Element& e) {
    if (!e.fixed_size()) return false;
    std::uint64_t left = bytes_.size() - pos_;
    value_pos_ = pos_;
    if (!take_bytes(e.count, e.min_binary_size(), left)) {
      fail(cat("unexpected end of file in element '", e.name, "' (", e.count, " records of ", e.min_binary_size(),
               " bytes declared)"));
    }
    pos_ += e.count * e.min_binary_size();
    return true;
  }
  [[noreturn]] void fail(std::string_view msg) const { fail_at_byte(name_, value_pos_, msg); }

 private:
  void need(std::uint64_t n, const Element& e, const Property& p, std::uint64_t i) {
    value_pos_ = pos_;
    if (bytes_.size() - pos_ < n) truncated(e, p, i);
  }
  [[noreturn]] void truncated(const Element& e, const Property& p, std::uint64_t i) const {
    fail(cat("unexpected end of file in property '", p.name, "' of '", e.name, "' record ", i, " (", e.count,
             " records declared)"));
  }
  double read(Type t, const Element& e, const Property& p, std::uint64_t i) {
    need(size_of(t), e, p, i);
    const char* b = bytes_.data() + pos_;
    pos_ += size_of(t);
    switch (t) {
      case Type::kInt8: return load<std::int8_t>(b, little_);
      case Type::kUInt8: return load<std::uint8_t>(b, little_);
      case Type::kInt16: return load<std::int16_t>(b, little_);
      case Type::kUInt16: return load<std::uint16_t>(b, little_);
      case Type::kInt32: return load<std::int32_t>(b, little_);
      case Type::kUInt32: return load<std::uint32_t>(b, little_);
      case Type::kFloat32: return load<float>(b, little_);  // float -> double is exact
      case Type::kFloat64: return load<double>(b, little_);
    }
    return 0;
  }

  std::string_view bytes_;
  std::size_t pos_;
  std::size_t value_pos_;  // where the value being read starts
  bool little_;
  const std::string& name_;
};

template <class Body>
void read_body(Body& b, const Header& h, const Roles& r, const ReadLimits& limits, Scene& out) {
  const std::uint64_t nv = r.vertex ? r.vertex->count : 0;
  std::vector<std::uint32_t> corners;  // reused; grows only with indices actually read
  for (const Element& e : h.elements) {
    if (e.props.empty()) continue;  // records without properties hold no bytes
    if (&e == r.vertex) {
      out.vertices.reserve(e.count);
      for (std::uint64_t i = 0; i < e.count; ++i) {
        b.begin_record(e, i);
        double xyz[3] = {0, 0, 0};
        for (std::size_t j = 0; j < e.props.size(); ++j) {
          const Property& p = e.props[j];
          const int axis = j == std::size_t(r.xyz[0]) ? 0 : j == std::size_t(r.xyz[1]) ? 1 : j == std::size_t(r.xyz[2]) ? 2 : -1;
          if (axis >= 0) {
            xyz[axis] = b.coordinate(p.type, e, p, i);
          } else {
            b.skip_property(e, p, i);
          }
        }
        out.vertices.push_back({xyz[0], xyz[1], xyz[2]});
        b.end_record(e, i);
      }
    } else if (&e == r.face) {
      out.faces.reserve(e.count);
      for (std::uint64_t f = 0; f < e.count; ++f) {
        b.begin_record(e, f);
        for (std::size_t j = 0; j < e.props.size(); ++j) {
          const Property& p = e.props[j];
          if (j != std::size_t(r.indices)) {
            b.skip_property(e, p, f);
            continue;
          }
          const std::int64_t n = b.integer(p.count_type, e, p, f);
          if (n < 3) b.fail(cat("face ", f, " has ", n, " corners; a face needs at least 3"));
          if (std::uint64_t(n) > limits.max_face_degree) {
            b.fail(cat("face ", f, " has ", n, " corners, more than the limit of ", limits.max_face_degree));
          }
          corners.clear();
          for (std::int64_t k = 0; k < n; ++k) {
            const std::int64_t idx = b.integer(p.type, e, p, f);
            if (idx < 0) b.fail(cat("face ", f, " has negative vertex index ", idx));
            if (std::uint64_t(idx) >= nv) {
              b.fail(cat("face ", f, " has vertex index ", idx, ", but there are only ", nv, " vertices"));
            }
            corners.push_back(static_cast<std::uint32_t>(idx));
          }
        }
        out.faces.emplace_back(corners.begin(), corners.end());
        b.end_record(e, f);
      }
    } else if (!b.skip_fixed_element(e)) {
      for (std::uint64_t i = 0; i < e.count; ++i) {
        b.begin_record(e, i);
        for (const Property& p : e.props) b.skip_property(e, p, i);
        b.end_record(e, i);
      }
    }
  }
}

}  // namespace

void read_ply(std::string_view bytes, const std::string& name, const ReadLimits& limits, Scene& out) {
  TextCursor c(bytes, name);
  const Header h = read_header(c);
  const Roles r = find_roles(h, name);
  check_counts(h, r, bytes.size(), name, limits);
  if (h.encoding == Encoding::kAscii) {
    AsciiBody body(c);
    read_body(body, h, r, limits, out);
  } else {
    BinaryBody body(bytes, h.data_start, h.encoding == Encoding::kBinaryLittle, name);
    read_body(body, h, r, limits, out);
  }
}

}  // namespace vismap::io
