// What a vismap::Map holds: the engine's exact map, the scene and view it was
// computed from (the drawings shade faces from them), and the nearest doubles
// handed to callers. Internal: the library's own sources only.
#pragma once
#include <vector>

#include "arrangements/visibility_map.h"
#include "engine/camera.h"
#include "vismap/vismap.h"

namespace vismap {

struct Map::Impl {
  Scene scene;
  View view;
  VisibilityMap map;               // exact; its stats without timings (a reproducible JSON)
  int threads = 1;                 // for writing the JSON
  std::vector<Point> vertices;     // map.vertices, nearest doubles
  std::vector<HiddenLine> hidden;  // map.hidden, nearest doubles
};

}  // namespace vismap
