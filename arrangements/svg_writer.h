// The map as an SVG drawing (arrangements/drawing.h): regions filled with a
// flat shade from their face's normal (in the styles that fill), then one
// Inkscape layer per line class, each chain of lines one <path>. On a page the
// units are mm (width="210mm", viewBox in mm): printers and plotters draw it at
// true size. Coordinates are rounded to doubles only here.
#pragma once
#include <string>

#include "arrangements/drawing.h"
#include "arrangements/visibility_map.h"
#include "engine/camera.h"
#include "engine/scene.h"
#include "engine/visibility.h"

namespace vismap {

struct SvgOptions {
  bool lines_only = false;     // no fills, whatever the style
  bool provenance = false;     // data-kind and data-faces on each path (chains then keep one kind and faces)
  bool optimize_travel = false;
  DrawingStyle style = shaded_style();
  PageOptions page;
};

std::string to_svg(const VisibilityMap& map, const Scene& scene, const View& view, const SvgOptions& opt);
// The same from a drawing already made (make_drawing with opt.page, opt.provenance).
std::string to_svg(const VisibilityMap& map, const Drawing& drawing, const Scene& scene, const View& view,
                   const SvgOptions& opt);

// The pieces of a document, for pages that hold several drawings (sheet.h):
// the <svg> element of a page (its closing tag is the caller's), and one
// drawing's layers, their ids prefixed (unique on the page).
std::string svg_header(const Placement& at);
std::string svg_layers(const VisibilityMap& map, const Drawing& drawing, const Scene& scene, const View& view,
                       const SvgOptions& opt, const std::string& id_prefix);

// Newell's painter's drawing: the fragments filled one after another in drawing
// order (back to front), each with its face's shade, on the same page as
// to_svg's drawing of `map` (so the two can be laid over each other).
std::string to_painter_svg(const std::vector<PaintedFragment>& fragments, const VisibilityMap& map,
                           const Scene& scene, const View& view, const SvgOptions& opt);

}  // namespace vismap
