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
};

// Reads OFF, OBJ, STL (ASCII/binary) or PLY (ASCII/binary), chosen by extension
// (case-insensitive). Throws InputError on any malformed input.
Scene read_scene(const std::string& path, const ReadLimits& limits = {});

// Same, from bytes already in memory; `format` is "off", "obj", "stl" or "ply".
Scene read_scene_bytes(std::string_view bytes, const std::string& name,
                       const std::string& format, const ReadLimits& limits = {});

}  // namespace vismap
