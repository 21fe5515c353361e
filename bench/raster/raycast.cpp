// Ray casting: one ray per pixel centre, parallel to the view (screen space
// makes every ray a vertical line through (x, y)). Acceleration: a uniform grid
// of G x G cells over the window (G about sqrt(pieces), cells aligned to whole
// pixels); each cell lists the pieces whose box meets it, sorted front to back
// by their nearest vertex depth. A ray walks its cell's list and stops at the
// first piece that starts behind the nearest hit so far: nothing later can be
// nearer (depth ties go on, for the face-index rule).
#include <algorithm>
#include <cmath>
#include <limits>

#include "bench/raster/raster.h"

namespace vismap::raster {

Image raycast(const ScreenScene& s, const Window& w) {
  const int R = w.R;
  Image img{R, std::vector<std::int32_t>(static_cast<std::size_t>(R) * R, -1)};
  const double inv = 1 / w.pixel;
  const std::size_t n = s.pieces.size();
  if (n == 0) return img;

  // Cells of cs x cs pixels.
  const int g = std::clamp(static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n)))), 1, R);
  const int cs = (R + g - 1) / g;
  const int G = (R + cs - 1) / cs;

  // The pixel-centre range of each piece's box, clamped to the window.
  struct Range {
    int i0, i1, j0, j1;
  };
  auto range = [&](const Piece& p) {
    auto first = [&](double t) {
      const double v = std::ceil(t - 0.5);
      return v <= 0 ? 0 : v >= R ? R : static_cast<int>(v);
    };
    auto last = [&](double t) {
      const double v = std::floor(t - 0.5);
      return v < 0 ? -1 : v >= R - 1 ? R - 1 : static_cast<int>(v);
    };
    return Range{first((p.xmin - w.x0) * inv), last((p.xmax - w.x0) * inv), first((p.ymin - w.y0) * inv),
                 last((p.ymax - w.y0) * inv)};
  };

  // The grid as compressed lists (count, prefix sum, fill).
  std::vector<std::uint32_t> start(static_cast<std::size_t>(G) * G + 1, 0);
  for (const Piece& p : s.pieces) {
    const Range r = range(p);
    if (r.i0 > r.i1 || r.j0 > r.j1) continue;
    for (int cj = r.j0 / cs; cj <= r.j1 / cs; ++cj)
      for (int ci = r.i0 / cs; ci <= r.i1 / cs; ++ci) ++start[static_cast<std::size_t>(cj) * G + ci + 1];
  }
  for (std::size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
  struct Entry {
    double dmin;
    std::uint32_t piece;
  };
  std::vector<Entry> cells(start.back());
  {
    std::vector<std::uint32_t> at(start.begin(), start.end() - 1);
    for (std::size_t pi = 0; pi < n; ++pi) {
      const Range r = range(s.pieces[pi]);
      if (r.i0 > r.i1 || r.j0 > r.j1) continue;
      for (int cj = r.j0 / cs; cj <= r.j1 / cs; ++cj)
        for (int ci = r.i0 / cs; ci <= r.i1 / cs; ++ci)
          cells[at[static_cast<std::size_t>(cj) * G + ci]++] = {s.pieces[pi].dmin, static_cast<std::uint32_t>(pi)};
    }
  }
  for (std::size_t c = 0; c + 1 < start.size(); ++c)
    std::sort(cells.begin() + start[c], cells.begin() + start[c + 1], [](const Entry& a, const Entry& b) {
      return a.dmin < b.dmin || (a.dmin == b.dmin && a.piece < b.piece);
    });

  for (int cj = 0; cj < G; ++cj)
    for (int ci = 0; ci < G; ++ci) {
      const std::size_t c = static_cast<std::size_t>(cj) * G + ci;
      const Entry* first = cells.data() + start[c];
      const Entry* last = cells.data() + start[c + 1];
      if (first == last) continue;
      const int jend = std::min(R, (cj + 1) * cs), iend = std::min(R, (ci + 1) * cs);
      for (int j = cj * cs; j < jend; ++j) {
        const double y = w.cy(j);
        std::int32_t* row = img.label.data() + static_cast<std::size_t>(j) * R;
        for (int i = ci * cs; i < iend; ++i) {
          const double x = w.cx(i);
          int best = -1;
          double bd = std::numeric_limits<double>::infinity();
          for (const Entry* e = first; e != last; ++e) {
            if (e->dmin > bd) break;
            const Piece& p = s.pieces[e->piece];
            if (x < p.xmin || x > p.xmax || y < p.ymin || y > p.ymax || !s.inside(p, x, y)) continue;
            const double d = p.depth(x, y);
            if (d < bd || (d == bd && p.face < best)) {
              bd = d;
              best = p.face;
            }
          }
          row[i] = best;
        }
      }
    }
  return img;
}

}  // namespace vismap::raster
