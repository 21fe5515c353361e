// The scene as read from a mesh file: vertices and polygons in file order (the
// types and readers are the library's, include/vismap/vismap.h), and what the
// readers share: memory estimates and format sniffing. No CGAL.
#pragma once
#include <cstdint>
#include <string>
#include <string_view>

#include "vismap/vismap.h"

namespace vismap {

// Coordinate k of p (0: x, 1: y, 2: z).
inline double coordinate(const Vec3& p, int k) { return k == 0 ? p.x : k == 1 ? p.y : p.z; }

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

// The format that bytes are in, judged by their start: "off" (an OFF header),
// "ply" ("ply" line), "stl" ("solid", or a binary STL whose size matches its
// triangle count), "obj" (the first record is an OBJ keyword such as v, f, o, g,
// vn, mtllib, or a comment followed by one); "" when none of these.
std::string sniff_format(std::string_view bytes);

}  // namespace vismap
