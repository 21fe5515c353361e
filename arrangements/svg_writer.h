// The map as an SVG drawing: regions filled with a flat shade from their face's
// normal, visible lines stroked. Coordinates are rounded to doubles only here.
#pragma once
#include <string>

#include "arrangements/visibility_map.h"
#include "engine/camera.h"
#include "engine/scene.h"

namespace vismap {

struct SvgOptions {
  bool lines_only = false;   // a pure hidden-line drawing
  double size = 800;         // the longer side of the page, in px
};

std::string to_svg(const VisibilityMap& map, const Scene& scene, const View& view, const SvgOptions& opt);

}  // namespace vismap
