// Catmull's depth buffer: every piece is scan-converted into a buffer of depths
// and labels; a pixel takes the piece when it is nearer than what is there, or
// as near with a lower face index (the exact engine's tie rule). Each piece is
// filled row by row: on a row its pixel centres form one span, bounded by the
// crossings of its (counter-clockwise) edges.
#include <algorithm>
#include <cmath>
#include <limits>

#include "bench/raster/raster.h"

namespace vismap::raster {
namespace {

// First pixel index whose centre is >= t (in pixel units, centre i at i + 0.5),
// clamped to [0, R]; and the last one <= t, clamped to [-1, R - 1].
int first_at_or_after(double t, int R) {
  const double v = std::ceil(t - 0.5);
  return v <= 0 ? 0 : v >= R ? R : static_cast<int>(v);
}
int last_at_or_before(double t, int R) {
  const double v = std::floor(t - 0.5);
  return v < 0 ? -1 : v >= R - 1 ? R - 1 : static_cast<int>(v);
}

}  // namespace

Image zbuffer(const ScreenScene& s, const Window& w) {
  const int R = w.R;
  const std::size_t n = static_cast<std::size_t>(R) * R;
  Image img{R, std::vector<std::int32_t>(n, -1)};
  std::vector<double> z(n, std::numeric_limits<double>::infinity());
  const double inv = 1 / w.pixel;
  std::vector<double> cx(static_cast<std::size_t>(R));   // the pixel centres' x, w.cx(i)
  for (int i = 0; i < R; ++i) cx[static_cast<std::size_t>(i)] = w.cx(i);

  struct EdgeSpan {
    double xk, yk, slope;   // x on the edge at height y: xk + (y - yk) * slope
    int kind;               // +1 right bound (edge goes up), -1 left bound, 0 horizontal
    double dx;              // horizontal edges: inside needs dx * (y - yk) >= 0
  };
  std::vector<EdgeSpan> edges;

  for (const Piece& p : s.pieces) {
    const int j0 = first_at_or_after((p.ymin - w.y0) * inv, R);
    const int j1 = last_at_or_before((p.ymax - w.y0) * inv, R);
    if (j0 > j1) continue;
    edges.clear();
    for (std::uint32_t k = 0; k < p.count; ++k) {
      const std::uint32_t a = p.first + k, b = p.first + (k + 1) % p.count;
      const double dx = s.x[b] - s.x[a], dy = s.y[b] - s.y[a];
      if (dy > 0)
        edges.push_back({s.x[a], s.y[a], dx / dy, +1, dx});
      else if (dy < 0)
        edges.push_back({s.x[a], s.y[a], dx / dy, -1, dx});
      else
        edges.push_back({s.x[a], s.y[a], 0, 0, dx});
    }
    for (int j = j0; j <= j1; ++j) {
      const double y = w.cy(j);
      double xl = -std::numeric_limits<double>::infinity(), xr = -xl;
      bool empty = false;
      for (const EdgeSpan& e : edges) {
        if (e.kind > 0)
          xr = std::min(xr, e.xk + (y - e.yk) * e.slope);
        else if (e.kind < 0)
          xl = std::max(xl, e.xk + (y - e.yk) * e.slope);
        else if (e.dx * (y - e.yk) < 0)
          empty = true;
      }
      if (empty) continue;
      const int i0 = first_at_or_after((xl - w.x0) * inv, R);
      const int i1 = last_at_or_before((xr - w.x0) * inv, R);
      if (i0 > i1) continue;
      const double row = p.b * y + p.c;
      const std::size_t base = static_cast<std::size_t>(j) * R;
      std::int32_t* lab = img.label.data() + base;
      double* zr = z.data() + base;
      for (int i = i0; i <= i1; ++i) {
        const double d = p.a * cx[static_cast<std::size_t>(i)] + row;
        if (d < zr[i] || (d == zr[i] && p.face < lab[i])) {
          zr[i] = d;
          lab[i] = p.face;
        }
      }
    }
  }
  return img;
}

}  // namespace vismap::raster
