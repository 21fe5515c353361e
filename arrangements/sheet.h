// A drawing sheet: several views of one scene on one SVG page, as a draftsman
// lays them out (front, top, right and an isometric view; first- or
// third-angle). The orthographic views share one scale and line up: views in
// one column share their screen x origin, views in one row their y origin, so
// the front and top views (both x across) and the front and right views (both
// z up) align exactly. Each view is labelled under it.
#pragma once
#include <string>
#include <vector>

#include "arrangements/svg_writer.h"
#include "arrangements/visibility_map.h"
#include "engine/camera.h"

namespace vismap {

struct SheetView {
  const VisibilityMap* map = nullptr;
  const View* view = nullptr;
  std::string label;   // "FRONT", "TOP", ...
  int row = 0, col = 0;   // its cell, from the top left
};

// The page: opt.page's paper (or a canvas of opt.page.size px), the views at
// opt.page.scale or the largest common scale that fits the cells within the
// margins; `note` written at the foot (e.g. "FIRST-ANGLE PROJECTION").
std::string to_sheet_svg(const std::vector<SheetView>& views, const Scene& scene, const SvgOptions& opt,
                         const std::string& note);

}  // namespace vismap
