// The map as an SVG drawing: regions filled with a flat shade from their face's
// normal, visible lines stroked. Coordinates are rounded to doubles only here.
#pragma once
#include <string>

#include "arrangements/visibility_map.h"
#include "engine/camera.h"
#include "engine/scene.h"
#include "engine/visibility.h"

namespace vismap {

struct SvgOptions {
  bool lines_only = false;   // a pure hidden-line drawing
  double size = 800;         // the longer side of the page, in px
};

std::string to_svg(const VisibilityMap& map, const Scene& scene, const View& view, const SvgOptions& opt);

// Newell's painter's drawing: the fragments filled one after another in drawing
// order (back to front), each with its face's shade, on the same page as
// to_svg's drawing of `map` (so the two can be laid over each other).
std::string to_painter_svg(const std::vector<PaintedFragment>& fragments, const VisibilityMap& map,
                           const Scene& scene, const View& view, const SvgOptions& opt);

}  // namespace vismap
