// The scene as read from a mesh file: vertices and polygons in file order.
// Header kept free of CGAL so every stage can include it cheaply.
#pragma once
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace vismap {

struct Vec3 {
  double x = 0, y = 0, z = 0;
};

struct Scene {
  std::string file;                                 // path as given (messages, JSON)
  std::vector<Vec3> vertices;                       // finite doubles: the exact input
  std::vector<std::vector<std::uint32_t>> faces;    // face index = position (file order)
};

// Bad input. what() is the whole message and already names the file, and the
// line (or byte offset for binary formats) where there is one: "a.off:12: ...".
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Refuse counts that cannot be real before allocating for them.
struct ReadLimits {
  std::uint64_t max_vertices = 50'000'000;
  std::uint64_t max_faces = 50'000'000;
  std::uint64_t max_face_degree = 1'000'000;
  // Bytes a whole run may use (0: no limit). A file larger than this, or a scene
  // whose estimated need (estimate_memory) is larger, is refused before anything
  // is allocated for it, as soon as its counts are known (header formats: from
  // the header; OBJ and ASCII STL: while reading).
  std::uint64_t max_memory = 0;
};

// --- Memory -------------------------------------------------------------------------
// Estimated peak memory of a run on a scene: the file's bytes plus the engine's
// working set per vertex, face and face corner. Measured peaks (docs/cli.md, "Limits"):
// 10-11 KB per face on terrains, 24-35 KB per face on random squares, for 10^4
// to 10^5 faces; the model stays at or below them (about 9-10 KB per face on
// both), so that it refuses up front what could never fit without refusing what
// might.
struct MemoryModel {
  static constexpr std::uint64_t kBase = 64ull << 20;
  static constexpr std::uint64_t kPerVertex = 200;
  static constexpr std::uint64_t kPerFace = 8000;
  static constexpr std::uint64_t kPerCorner = 400;
};
std::uint64_t estimate_memory(std::uint64_t file_bytes, std::uint64_t vertices, std::uint64_t faces,
                              std::uint64_t corners);

// The default --max-memory: physical memory, or less where a cgroup limit or
// RLIMIT_AS says so.
std::uint64_t default_max_memory();

// "8G", "512M", "1.5G", "100000" (bytes), "64K", "1T" (powers of 1024; an
// optional trailing 'B' or 'iB'); false when the text is not such a size or is 0.
bool parse_memory_size(std::string_view text, std::uint64_t& bytes);

// "1.9 TiB", "512 MiB", "812 bytes".
std::string format_bytes(std::uint64_t bytes);

// --- Reading --------------------------------------------------------------------------
// Reads OFF, OBJ, STL (ASCII/binary) or PLY (ASCII/binary). `format` ("off",
// "obj", "stl", "ply", any case) forces one; when empty, a file's format comes
// from its extension (case-insensitive), and standard input's (path "-") from
// its content (sniff_format). Throws InputError on any malformed input.
Scene read_scene(const std::string& path, const ReadLimits& limits = {}, const std::string& format = "");

// Same, from bytes already in memory; `format` is "off", "obj", "stl" or "ply".
Scene read_scene_bytes(std::string_view bytes, const std::string& name,
                       const std::string& format, const ReadLimits& limits = {});

// The format that bytes are in, judged by their start: "off" (an OFF header),
// "ply" ("ply" line), "stl" ("solid", or a binary STL whose size matches its
// triangle count), "obj" (the first record is an OBJ keyword such as v, f, o, g,
// vn, mtllib, or a comment followed by one); "" when none of these.
std::string sniff_format(std::string_view bytes);

}  // namespace vismap
