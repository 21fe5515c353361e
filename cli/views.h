// Many views in one run (vismap SCENE --views SPEC): the cameras a spec names,
// and each view's output file names. The scene is read once; each view is
// computed and written as a single run with its camera would be.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

#include "vismap/vismap.h"

namespace vismap::cli {

struct NamedView {
  Camera camera;
  std::string options;   // the camera as command-line options ("--dir 1,-2,0.5"), for messages
  std::string label;     // on a sheet: "FRONT", "TOP", "RIGHT", "ISOMETRIC"
  int row = -1, col = -1;   // on a sheet: its cell, from the top left; -1: no sheet
};

// SPEC is "sheet[:first|:third]" (a drawing sheet: front, looking along +y;
// top, along -z; right, along -x; and an isometric view from (1,-1,1), laid out
// in first-angle projection, the default, or third-angle), "orbit:N[,ELEVATION]" (N orthographic views around the scene's z
// axis, looking down at ELEVATION degrees, default 30: view k looks along
// -(cos e cos a, cos e sin a, sin e) with a = 360 k / N degrees), or a file of
// one camera per line in the command line's options (--dir, or --eye with
// --target and --fov; --up), '#' starting a comment. Throws
// std::invalid_argument (a spec) or InputError (the file, naming its line).
std::vector<NamedView> parse_views(const std::string& spec);

// What a sheet says of its projection ("FIRST-ANGLE PROJECTION"); empty when
// SPEC is not a sheet.
std::string sheet_note(const std::string& spec);

// The output name for view k: "%d" (or "%0Nd", zero-padded to N digits) in
// `pattern` replaced by k; false when the pattern has no such field.
bool has_view_field(const std::string& pattern);
std::string view_file_name(const std::string& pattern, std::size_t k);

// How many views run side by side, each on its share of `threads`: for a scene
// of fewer than engine::kFewFaces faces, whose single view gains little from
// threads of its own (they wait for each other between short loops; one
// thread by default), while views are independent. At most `threads`, `views`
// and 16, and as many as `max_memory` holds at kBytesPerFace per face each
// (more than twice the most a view was measured to take: 6 KB per face, on
// random squares). 1 (one view at a time, on every thread) for larger scenes:
// there two threads inside each view did better than two views side by side
// (20^3 boxes, 48 000 faces, 8 views on 2 cores: 35 s against 46 s wall; the
// views side by side each took longer, sharing the caches and memory).
constexpr std::uint64_t kBytesPerFace = 16384;
int views_side_by_side(std::size_t views, int threads, std::size_t faces, std::uint64_t max_memory);

// body(k) for k in [0, count), each on a thread of its own (k = 0 on the
// caller's), returning when all are done. body must not throw.
template <class Body>
void side_by_side(std::size_t count, Body&& body) {
  std::vector<std::thread> others;
  for (std::size_t k = 1; k < count; ++k) others.emplace_back([&body, k] { body(k); });
  if (count > 0) body(0);
  for (std::thread& t : others) t.join();
}

}  // namespace vismap::cli
