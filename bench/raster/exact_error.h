// The error of a label image against the exact visibility map (issue 4).
//
//   exact_labels()  the exact map's label at every pixel centre: its regions
//                   (outer rings counter-clockwise, holes clockwise, exact
//                   rationals) filled row by row with the crossing-parity rule.
//                   A crossing is placed among the pixel centres in doubles only
//                   when no pixel centre lies within tol + err of the double
//                   crossing, where tol = 1e-9 * window side and err is a proven
//                   bound on the double crossing's error (so every centre decided
//                   in doubles is more than 1e-9 * side away from the edge along
//                   the row, and on the correct side); otherwise the crossing is
//                   computed and compared with GMP rationals. Pixel centres that
//                   lie exactly on a region boundary (an edge, a vertex, a
//                   horizontal edge) have no label in the map: they get
//                   kOnBoundary and are left out of the pixel error.
//   pixel_error()   the fraction of (labelled) pixel centres whose label differs.
//   area_error()    the fraction of the window painted wrongly when each pixel's
//                   square takes its centre label (k x k exact samples a pixel).
//   line_error()    for lines: the image's drawing is its label changes between
//                   neighbouring pixels (a pixel-side long line, at the side
//                   between the two centres; outside the window counts as
//                   background) that LineRule (raster.h) calls a line: not
//                   within one smooth patch of the mesh where the depth is
//                   continuous, which the exact drawing does not show either. An exact visible segment point is "missed"
//                   when no drawn pixel side has its midpoint within `tol`
//                   pixels of it; a drawn pixel side is "hidden line drawn" when
//                   no exact visible segment passes within `tol` pixels of its
//                   midpoint. Both are lengths (screen units) and fractions of
//                   the exact visible length. Segments are measured in doubles
//                   (this is a pixel-scale measure). With tol = 1.25 an image
//                   with the right label at every centre misses nothing and
//                   draws nothing false except where a region is thinner than a
//                   pixel: a straight boundary through the square of four
//                   neighbouring centres separates two of them that share a
//                   side, whose midpoint is within sqrt(1.25) < 1.12 pixels of
//                   every point of that boundary inside the square, and the
//                   boundary crosses the segment between two centres that it
//                   separates, within 0.5 pixel of its midpoint.
//
// GMP, no CGAL: links the raster baselines and vismap_verify's JSON parser.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "arrangements/visibility_map.h"
#include "bench/raster/raster.h"

namespace vismap::raster {

inline constexpr std::int32_t kOnBoundary = -2;

struct ExactLabels {
  Image image;                     // face, -1 background, kOnBoundary
  std::size_t boundary = 0;        // pixel centres exactly on a region boundary
  std::size_t crossings = 0;       // edge-row crossings placed
  std::size_t exact_crossings = 0; // of which decided with rationals
};
// Throws std::logic_error if two regions claim one pixel centre (a broken map).
ExactLabels exact_labels(const VisibilityMap& map, const Window& w);

struct PixelError {
  std::size_t compared = 0;   // pixel centres with a label in the exact map
  std::size_t wrong = 0;      // of which the image labels differently
  std::size_t boundary = 0;   // left out: exactly on a region boundary
  double fraction() const { return compared ? static_cast<double>(wrong) / static_cast<double>(compared) : 0; }
};
PixelError pixel_error(const Image& exact, const Image& image);

// The area error: the picture paints each pixel's whole square with the label
// of its centre; the fraction of the window where that is not the exact label,
// estimated with k x k stratified samples per pixel (the centres of a k-times
// finer grid, labelled exactly like exact_labels). This is the error that
// resolution itself causes: it falls like 1/R, also for the exact centre
// labels, where pixel_error is 0 by definition. One pass serves all images.
struct AreaError {
  std::size_t samples = 0, wrong = 0;
  double fraction() const { return samples ? static_cast<double>(wrong) / static_cast<double>(samples) : 0; }
};
std::vector<AreaError> area_error(const VisibilityMap& map, const std::vector<const Image*>& images, const Window& w,
                                  int k = 4);

struct LineError {
  double exact_length = 0;     // total length of the exact visible segments
  double missed = 0;           // of which no drawn pixel side is near
  double false_drawn = 0;      // drawn pixel sides with no exact segment near
  double missed_fraction() const { return exact_length > 0 ? missed / exact_length : 0; }
  double false_fraction() const { return exact_length > 0 ? false_drawn / exact_length : 0; }
};
LineError line_error(const VisibilityMap& map, const Image& image, const Window& w, const LineRule& rule,
                     double tol_pixels = 1.25);

// The map from its JSON text (docs/format.md): projection, view
// matrix, regions and segments (stats are ignored). Throws std::runtime_error on
// anything it cannot read.
VisibilityMap read_map_json(std::string_view text);

// The View the map was made with: its matrix (doubles taken as exact rationals,
// so converting back is exact) and, for a perspective view, the eye (the point
// where X = Y = W = 0).
View view_of(const VisibilityMap& map);

}  // namespace vismap::raster
