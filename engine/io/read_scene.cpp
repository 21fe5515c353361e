// Entry points: pick the reader by extension / format name, read files whole.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

#include "engine/io/formats.h"
#include "engine/io/reader_util.h"
#include "engine/scene.h"

namespace vismap {
namespace {

std::string lowercase(std::string_view s) {
  std::string r(s);
  for (char& ch : r) {
    if (ch >= 'A' && ch <= 'Z') ch = static_cast<char>(ch - 'A' + 'a');
  }
  return r;
}

using Reader = void (*)(std::string_view, const std::string&, const ReadLimits&, Scene&);

// nullptr for an unknown format name (already lowercase).
Reader reader_for(const std::string& format) {
  if (format == "off") return io::read_off;
  if (format == "obj") return io::read_obj;
  if (format == "stl") return io::read_stl;
  if (format == "ply") return io::read_ply;
  if (format == "vmscene" || format == "json") return io::read_vmscene;   // (a .vmscene.json's extension is .json)
  return nullptr;
}

const char* const kStdinName = "<stdin>";

[[noreturn]] void too_big(const std::string& name, std::uint64_t size, bool at_least, const ReadLimits& limits) {
  io::fail(name, io::cat(at_least ? "more than " : "", format_bytes(size), " (", size,
                         " bytes) to read, more than the memory limit of ", format_bytes(limits.max_memory)));
}

// Reads until EOF into `data` (which holds `used` bytes so far), doubling it;
// refuses to hold more than the memory limit.
void read_all(std::FILE* f, const std::string& name, const ReadLimits& limits, std::string& data) {
  std::size_t used = 0;
  if (data.empty()) data.resize(std::size_t{1} << 16);
  for (;;) {
    used += std::fread(data.data() + used, 1, data.size() - used, f);
    if (used < data.size()) break;
    if (limits.max_memory != 0 && used > limits.max_memory) too_big(name, used, true, limits);
    data.resize(data.size() * 2);
  }
  if (std::ferror(f)) io::fail(name, io::cat("cannot read: ", std::strerror(errno)));
  data.resize(used);
}

// The whole file in one buffer: every reader then parses from memory.
std::string read_file(const std::string& path, const ReadLimits& limits) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) io::fail(path, "is a directory, not a mesh file");

  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!f) io::fail(path, io::cat("cannot open file: ", std::strerror(errno)));

  // The size is only a hint (the file may change, or be a pipe); read until EOF regardless.
  std::string data;
  const auto hint = std::filesystem::file_size(path, ec);
  if (!ec && limits.max_memory != 0 && hint > limits.max_memory) too_big(path, hint, false, limits);
  if (!ec) data.resize(static_cast<std::size_t>(hint) + 1);
  read_all(f.get(), path, limits, data);
  return data;
}

bool is_blank(char ch) { return ch == ' ' || ch == '\t' || ch == '\r' || ch == '\n' || ch == '\f' || ch == '\v'; }

}  // namespace

Scene read_scene_bytes(std::string_view bytes, const std::string& name, const std::string& format,
                       const ReadLimits& limits) {
  const Reader reader = reader_for(lowercase(format));
  if (!reader) io::fail(name, io::cat("unknown format ", io::quote(format), "; expected off, obj, stl, ply or vmscene"));
  Scene scene;
  scene.file = name;
  reader(bytes, name, limits, scene);
  return scene;
}

std::string sniff_format(std::string_view bytes) {
  // Binary STL: the size is exactly what the triangle count says.
  if (bytes.size() >= 84) {
    const std::uint64_t n = io::load<std::uint32_t>(bytes.data() + 80, true);
    if (84 + 50 * n == bytes.size()) return "stl";
  }
  // Otherwise the first word, past blank lines and '#' comment lines.
  std::size_t i = 0;
  for (;;) {
    while (i < bytes.size() && is_blank(bytes[i])) ++i;
    if (i < bytes.size() && bytes[i] == '#') {
      while (i < bytes.size() && bytes[i] != '\n') ++i;
      continue;
    }
    break;
  }
  if (i < bytes.size() && bytes[i] == '{') return "vmscene";
  std::size_t j = i;
  while (j < bytes.size() && !is_blank(bytes[j]) && bytes[j] != '#') ++j;
  if (io::is_off_header(bytes.substr(i, j - i))) return "off";
  const std::string word = lowercase(bytes.substr(i, j - i));
  if (word == "off") return "off";
  if (word == "ply") return "ply";
  if (word == "solid") return "stl";
  static const char* const kObj[] = {"v", "vt", "vn", "vp", "f", "l", "p", "o", "g", "s", "mtllib", "usemtl"};
  for (const char* k : kObj)
    if (word == k) return "obj";
  return "";
}

Scene read_scene(const std::string& path, const ReadLimits& limits, const std::string& format) {
  if (path == "-") {
    std::string data;
    read_all(stdin, kStdinName, limits, data);
    std::string fmt = lowercase(format);
    if (fmt.empty()) fmt = sniff_format(data);
    if (fmt.empty()) {
      io::fail(kStdinName, data.empty() ? "empty input; expected an OFF, OBJ, STL or PLY mesh, or a vmscene"
                                        : "cannot tell the mesh format from the content; name it: off, obj, stl, ply or vmscene");
    }
    return read_scene_bytes(data, kStdinName, fmt, limits);
  }
  std::string fmt = lowercase(format);
  if (fmt.empty()) {
    // Check the extension before touching the file: a wrong name fails fast.
    const std::string ext = lowercase(std::filesystem::path(path).extension().string());
    if (ext.empty() || !reader_for(ext.substr(1))) {
      io::fail(path, ext.empty() ? std::string("no file extension; expected .off, .obj, .stl, .ply or .vmscene.json (or name the format)")
                                 : io::cat("unknown file extension ", io::quote(ext),
                                           "; expected .off, .obj, .stl, .ply or .vmscene.json (or name the format)"));
    }
    fmt = ext.substr(1);
  } else if (!reader_for(fmt)) {
    io::fail(path, io::cat("unknown format ", io::quote(format), "; expected off, obj, stl, ply or vmscene"));
  }
  return read_scene_bytes(read_file(path, limits), path, fmt, limits);
}

}  // namespace vismap
