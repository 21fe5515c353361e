// What the fuzz targets run, shared with the regression test so that every
// finding and every seed is replayed by the ordinary test suite (no clang
// needed). Each function aborts (after printing why) when a property fails;
// bad input that is reported as such is fine.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#include "engine/camera.h"
#include "engine/scene.h"
#include "engine/visibility.h"

namespace vismap_fuzz {

// A finding: prints why on stderr and aborts (libFuzzer keeps the input).
[[noreturn]] void die(const std::string& why);

// A reader on arbitrary bytes: InputError, or a Scene that is consistent
// (finite coordinates, every face with >= 3 corners, all indices in range).
void check_reader(const std::uint8_t* data, std::size_t size, const std::string& format);

// A tiny scene and a camera decoded from bytes: at most 12 faces of 3 to 5
// corners, picked from a pool of at most 16 vertices whose coordinates come
// from a small set of integers and halves, so that shared edges, coplanar
// faces, T-junctions, collinear and repeated corners are common. Some scenes
// start with a seam (two squares sharing the edge x = 1) and put many vertices
// in the plane x = 1 (faces standing on the seam, lines under it); some are
// scaled by 2^k, k in -1000..1000.
struct TinyCase {
  vismap::Scene scene;
  vismap::Camera camera;
  vismap::Options options;
  std::string args;            // the vismap command-line options for the camera and lines
};
TinyCase decode_tiny(const std::uint8_t* data, std::size_t size);

// The scene as an OFF file (a reproducer: vismap scene.off <args>).
std::string to_off(const vismap::Scene& scene);

// Runs the whole pipeline (camera, engine, JSON) on decode_tiny(data) and has
// the independent checker verify the map; aborts, printing the scene as OFF and
// the command line, when the engine fails or the checker rejects its map. With
// several engines, their maps must also be identical (the spec's canonical form).
enum class Engines { Franklin, Newell, Bsp, Both, All };   // Both: Franklin and Newell; All: the three
void check_pipeline(const std::uint8_t* data, std::size_t size, Engines engines);

// VISMAP_FUZZ_ENGINE=franklin (default), newell, bsp, both (Franklin and Newell) or all.
Engines engines_from_env();

}  // namespace vismap_fuzz
