// The hidden lines (docs/format.md, "hidden"), made once either
// engine has made the visible map: every edge piece and intersection line of
// the scene (back faces and faces hidden everywhere included), less where it is
// visible and where a visible segment lies over it on the screen.
#pragma once
#include "arrangements/visibility_map.h"
#include "engine/camera.h"
#include "engine/scene.h"
#include "engine/visibility.h"

namespace vismap::engine {

// Fills map.hidden (and sets map.has_hidden) from the finished map's segments,
// in the spec's screen coordinates. Runs without hidden lines never call it, so
// they cost what they cost without it.
void add_hidden_lines(const Scene& scene, const View& view, const Options& options, VisibilityMap& map);

}  // namespace vismap::engine
