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
  return nullptr;
}

// The whole file in one buffer: every reader then parses from memory.
std::string read_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) io::fail(path, "is a directory, not a mesh file");

  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!f) io::fail(path, io::cat("cannot open file: ", std::strerror(errno)));

  // The size is only a hint (the file may change); read until EOF regardless.
  std::string data;
  const auto hint = std::filesystem::file_size(path, ec);
  data.resize(ec ? std::size_t{1} << 16 : static_cast<std::size_t>(hint) + 1);
  std::size_t used = 0;
  for (;;) {
    used += std::fread(data.data() + used, 1, data.size() - used, f.get());
    if (used < data.size()) break;
    data.resize(data.size() * 2);
  }
  if (std::ferror(f.get())) io::fail(path, io::cat("cannot read file: ", std::strerror(errno)));
  data.resize(used);
  return data;
}

}  // namespace

Scene read_scene_bytes(std::string_view bytes, const std::string& name, const std::string& format,
                       const ReadLimits& limits) {
  const Reader reader = reader_for(lowercase(format));
  if (!reader) io::fail(name, io::cat("unknown format ", io::quote(format), "; expected off, obj, stl or ply"));
  Scene scene;
  scene.file = name;
  reader(bytes, name, limits, scene);
  return scene;
}

Scene read_scene(const std::string& path, const ReadLimits& limits) {
  // Check the extension before touching the file: a wrong name fails fast.
  const std::string ext = lowercase(std::filesystem::path(path).extension().string());
  if (ext.empty() || !reader_for(ext.substr(1))) {
    io::fail(path, ext.empty() ? std::string("no file extension; expected .off, .obj, .stl or .ply")
                               : io::cat("unknown file extension ", io::quote(ext),
                                         "; expected .off, .obj, .stl or .ply"));
  }
  return read_scene_bytes(read_file(path), path, ext.substr(1), limits);
}

}  // namespace vismap
