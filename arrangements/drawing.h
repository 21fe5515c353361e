// The map as a drawing: its lines sorted into classes (one layer each), chained
// into maximal polylines, placed on a page, styled. The writers (SVG, DXF) draw
// from this; coordinates are rounded to doubles only here. No CGAL.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "arrangements/visibility_map.h"
#include "engine/camera.h"
#include "engine/scene.h"

namespace vismap {

// Line classes, drawn in this order (hidden lines under the visible ones).
enum class LineClass : std::uint8_t { Hidden, Smooth, Intersection, Crease, Outline };
constexpr std::size_t kLineClasses = 5;
const char* class_name(LineClass c);   // "hidden", "smooth", "intersection", "crease", "outline"
bool parse_line_class(std::string_view name, LineClass& out);
// Silhouettes and borders are the outline; every hidden line is hidden.
LineClass class_of(EdgeKind kind, bool hidden);

// The shade of a face's regions: Newell's intensity function (the seed paper's
// I = r cos^n(a) + b, with the streak s sin^m(a)), a the angle between the face's
// normal and the direction of the light, which is at the eye unless given (a
// direction towards the light, in the world). Clamped to [0, 1]. The defaults
// are a flat shade, brighter the more a face faces the light.
struct Shading {
  double r = 0.65, n = 1, b = 0.3, s = 0, m = 20;
  bool light_given = false;
  double light[3] = {0, 0, 0};
};
// "R,N,B" or "R,N,B,S,M"; false otherwise.
bool parse_shading(std::string_view text, Shading& out);
// The grey of face `face` (0-255 per channel, a little blue), seen through `view`.
std::array<int, 3> face_rgb(const Scene& scene, const View& view, int face, const Shading& shading);

// How one class is stroked. Lengths in mm on a page (on a pixel canvas, 1 mm is
// 96/25.4 px, the CSS inch).
struct LineStyle {
  double width = 0.35;
  std::string color = "black";
  std::vector<double> dash;   // on, off, ...; empty: continuous
};

struct DrawingStyle {
  std::string name = "shaded";
  bool fills = true;          // regions filled with their face's shade
  bool cut_dashes = false;    // dashes drawn as real sub-paths (plotters and cutters ignore dash arrays)
  Shading shading;
  std::array<LineStyle, kLineClasses> line;
};
// The default: "shaded".
DrawingStyle shaded_style();
// "technical" (ISO 128-like: visible 0.5 mm continuous, hidden 0.25 mm dashed,
// no fills), "shaded" (regions filled, thin lines), "plotter" (a colour per
// layer, dashes cut, no fills). False for another name.
bool preset_style(std::string_view name, DrawingStyle& out);
// Applies "CLASS:width=W,color=C,dash=A/B/..." (any of the three); false with
// a message in `error` when it is not that.
bool override_line_style(std::string_view spec, DrawingStyle& style, std::string& error);

// Where the drawing goes. Without a page: a canvas `size` px on its longer side
// around the drawing (the drawing fills it). With one: width x height mm, the
// drawing at `scale` (paper mm per screen unit; 0: fitted within the margins),
// centred; a named paper size is turned landscape when the drawing is wider
// than tall.
struct PageOptions {
  double width = 0, height = 0;   // mm; 0: no page
  bool named = false;             // a named size (may be turned)
  double scale = 0;               // 1:N is 1/N
  double margin = 10;             // mm
  double size = 800;              // px, without a page
};
// "a4", "a3", "letter" or "WxHmm" (e.g. "300x200mm"); false otherwise.
bool parse_page(std::string_view text, PageOptions& page);
// "1:N" (N > 0) or a plain positive factor; false otherwise.
bool parse_scale(std::string_view text, double& scale);

// The map's screen coordinates on the page (y down on the page, up on the screen).
struct Placement {
  bool mm = false;                // page units: mm, or px without a page
  double width = 0, height = 0;   // the page
  double x0 = 0, y0 = 0;          // the drawing's lower left, on the screen
  double k = 1;                   // page units per screen unit
  double left = 0, bottom = 0;    // where (x0, y0) goes, from the page's left and bottom
  std::array<double, 2> at(double x, double y) const { return {left + (x - x0) * k, height - bottom - (y - y0) * k}; }
  std::array<double, 2> at(const std::array<double, 2>& screen) const { return at(screen[0], screen[1]); }
  double per_mm() const { return mm ? 1 : 96 / 25.4; }   // page units per mm
};
Placement place(const VisibilityMap& map, const PageOptions& page);

// A maximal polyline of one class, through vertices where exactly two of the
// class's lines meet (with provenance: of one kind and faces list too).
struct Chain {
  LineClass cls = LineClass::Outline;
  std::vector<std::array<double, 2>> screen;   // its points on the screen (on the page: Placement::at)
  bool closed = false;                         // (the last point is not repeated)
  EdgeKind kind = EdgeKind::Border;            // with provenance: its lines' kind and faces
  std::vector<int> faces;
};
// Each line exactly once; chains by class, in the order of their first line.
std::vector<Chain> chains_of(const VisibilityMap& map, bool by_provenance);
// A chain's points on the page.
std::vector<std::array<double, 2>> page_points(const Chain& c, const Placement& at);

// Pen-up travel (page units): from the page's origin through the chains in order.
double travel(const std::vector<Chain>& chains, const Placement& at);
// Reorders (and reverses) the chains of each class, nearest next start first.
void optimize_travel(std::vector<Chain>& chains, const Placement& at);

// The drawing of a map: where it goes, and its chains (in pen order with
// `optimize`; travel before and after, page units).
struct Drawing {
  Placement at;
  std::vector<Chain> chains;
  double travel_before = 0, travel_after = 0;
};
Drawing make_drawing(const VisibilityMap& map, const PageOptions& page, bool by_provenance, bool optimize);

// The drawing's format from its file name: "svg" (also standard output, "-",
// and names without an extension), "dxf", "pdf", "eps", "png", or "" for another.
std::string drawing_format(const std::string& path);

// A polyline's dashes as sub-polylines (page units, closed: back to its first
// point), for cut dashes.
std::vector<std::vector<std::array<double, 2>>> dashed(const std::vector<std::array<double, 2>>& points, bool closed,
                                                       const std::vector<double>& dash);

}  // namespace vismap
