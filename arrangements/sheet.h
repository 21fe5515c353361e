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

// Where everything goes on the page: opt.page's paper (or a canvas of
// opt.page.size px), the views at opt.page.scale or the largest common scale
// that fits the cells within the margins; each view's drawing placed in its
// cell, its label under it; `note` (e.g. "FIRST-ANGLE PROJECTION") at the foot.
struct SheetText {
  double x = 0, y = 0;   // the anchor, page units from the top left
  double size = 0;
  bool end = false;      // anchored at its end (else its middle)
  std::string text;
};
struct SheetLayout {
  Placement page;
  std::vector<Drawing> drawings;   // one per view, placed
  std::vector<std::string> ids;    // one per view: its label as an SVG id
  std::vector<SheetText> texts;    // the labels, then the note
};
SheetLayout sheet_layout(const std::vector<SheetView>& views, const SvgOptions& opt, const std::string& note);

// The page as SVG.
std::string to_sheet_svg(const std::vector<SheetView>& views, const Scene& scene, const SvgOptions& opt,
                         const std::string& note);

}  // namespace vismap
