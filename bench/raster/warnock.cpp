// Warnock's area subdivision (1968), down to the pixel. A window is a block of
// pixels; what matters of it is the rectangle spanned by its pixel centres.
// Each piece is, with respect to that rectangle, "out" (disjoint), "enclosing"
// (the rectangle is inside it) or "involved" (anything else). As in the paper,
// enclosing and out are kept by every sub-window, so only the involved pieces
// are classified again, and the depths of the pieces' planes at the rectangle's
// four corners decide:
//   - nothing enclosing or involved: background;
//   - the enclosing piece B whose farthest corner depth is least is in front
//     of every other piece over the whole window (their nearest corner depth is
//     farther, or as far with a higher face index): the window is B. Pieces
//     behind B over the window are dropped from the lists in any case;
//   - one involved piece and nothing enclosing: it is scan-converted into the
//     window (the polygon-inside-window trivial case);
//   - a single pixel: the nearest piece containing its centre, in the order
//     (depth, face);
//   - otherwise the window is split in four (in two when one side is one pixel)
//     and each part is examined in turn.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "bench/raster/raster.h"

namespace vismap::raster {
namespace {

enum class Rel { Out, Enclosing, Involved };

class Subdivider {
 public:
  Subdivider(const ScreenScene& s, const Window& w, Image& img) : s_(s), w_(w), img_(img) {
    // Each level halves both sides (or the one that is longer than a pixel):
    // at most ceil(log2 R) + 1 levels. Allocated once, so references into the
    // levels stay valid during the recursion.
    std::size_t depth = 2;
    for (int r = 1; r < w.R; r *= 2) ++depth;
    levels_.resize(depth + 1);
  }

  void run() {
    std::vector<int> all(s_.pieces.size());
    for (std::size_t k = 0; k < all.size(); ++k) all[k] = static_cast<int>(k);
    level(0).enc.clear();
    window(0, w_.R, 0, w_.R, 0, all);
  }

 private:
  struct Lists {
    std::vector<int> enc, inv;   // this window's enclosing and involved pieces
  };

  Lists& level(std::size_t L) { return levels_.at(L); }

  Rel classify(const Piece& p, double xa, double xb, double ya, double yb) const {
    if (p.xmax < xa || p.xmin > xb || p.ymax < ya || p.ymin > yb) return Rel::Out;
    bool enclosing = true;
    for (std::uint32_t k = p.first; k < p.first + p.count; ++k) {
      const double ex = s_.ex[k], ey = s_.ey[k], e0 = s_.e0[k];
      const double e1 = ex * xa + ey * ya + e0, e2 = ex * xb + ey * ya + e0;
      const double e3 = ex * xa + ey * yb + e0, e4 = ex * xb + ey * yb + e0;
      if (e1 < 0 && e2 < 0 && e3 < 0 && e4 < 0) return Rel::Out;
      if (e1 < 0 || e2 < 0 || e3 < 0 || e4 < 0) enclosing = false;
    }
    return enclosing ? Rel::Enclosing : Rel::Involved;
  }

  void fill(int i0, int i1, int j0, int j1, std::int32_t face) {
    for (int j = j0; j < j1; ++j) {
      std::int32_t* row = img_.label.data() + static_cast<std::size_t>(j) * w_.R;
      std::fill(row + i0, row + i1, face);
    }
  }

  // Window [i0, i1) x [j0, j1). The enclosing list of the parent is level(L).enc
  // on entry (the caller put it there); `cand` are the parent's involved pieces.
  void window(int i0, int i1, int j0, int j1, std::size_t L, const std::vector<int>& cand) {
    const double xa = w_.cx(i0), xb = w_.cx(i1 - 1), ya = w_.cy(j0), yb = w_.cy(j1 - 1);
    Lists& here = level(L);
    here.inv.clear();
    for (int pi : cand) {
      switch (classify(s_.pieces[pi], xa, xb, ya, yb)) {
        case Rel::Out: break;
        case Rel::Enclosing: here.enc.push_back(pi); break;
        case Rel::Involved: here.inv.push_back(pi); break;
      }
    }
    if (here.enc.empty() && here.inv.empty()) return;   // background

    auto lo_hi = [&](const Piece& p, double& lo, double& hi) {
      const double d1 = p.depth(xa, ya), d2 = p.depth(xb, ya), d3 = p.depth(xa, yb), d4 = p.depth(xb, yb);
      lo = std::min(std::min(d1, d2), std::min(d3, d4));
      hi = std::max(std::max(d1, d2), std::max(d3, d4));
    };
    if (!here.enc.empty()) {
      // The enclosing piece whose far corner is nearest, and what it hides.
      int best = -1;
      double bhi = std::numeric_limits<double>::infinity();
      for (int pi : here.enc) {
        double lo, hi;
        lo_hi(s_.pieces[pi], lo, hi);
        if (best < 0 || hi < bhi || (hi == bhi && s_.pieces[pi].face < s_.pieces[best].face)) {
          best = pi;
          bhi = hi;
        }
      }
      const int bface = s_.pieces[best].face;
      auto hidden = [&](int pi) {
        if (pi == best) return false;
        double lo, hi;
        lo_hi(s_.pieces[pi], lo, hi);
        return lo > bhi || (lo == bhi && s_.pieces[pi].face > bface);
      };
      here.enc.erase(std::remove_if(here.enc.begin(), here.enc.end(), hidden), here.enc.end());
      here.inv.erase(std::remove_if(here.inv.begin(), here.inv.end(), hidden), here.inv.end());
      if (here.enc.size() == 1 && here.inv.empty()) {
        fill(i0, i1, j0, j1, bface);
        return;
      }
    } else if (here.inv.size() == 1) {
      const Piece& p = s_.pieces[here.inv[0]];
      for (int j = j0; j < j1; ++j) {
        const double y = w_.cy(j);
        std::int32_t* row = img_.label.data() + static_cast<std::size_t>(j) * w_.R;
        for (int i = i0; i < i1; ++i)
          if (s_.inside(p, w_.cx(i), y)) row[i] = p.face;
      }
      return;
    }
    if (i1 - i0 == 1 && j1 - j0 == 1) {
      int best = -1;
      double bd = std::numeric_limits<double>::infinity();
      auto consider = [&](int pi, bool test) {
        const Piece& p = s_.pieces[pi];
        if (test && !s_.inside(p, xa, ya)) return;
        const double d = p.depth(xa, ya);
        if (best < 0 || d < bd || (d == bd && p.face < s_.pieces[best].face)) {
          best = pi;
          bd = d;
        }
      };
      for (int pi : here.enc) consider(pi, false);
      for (int pi : here.inv) consider(pi, true);
      if (best >= 0) fill(i0, i1, j0, j1, s_.pieces[best].face);
      return;
    }
    // Subdivide. Children classify this window's involved pieces and inherit
    // its enclosing ones (copied into the next level before each child).
    const int im = i1 - i0 >= 2 ? i0 + (i1 - i0) / 2 : i1;
    const int jm = j1 - j0 >= 2 ? j0 + (j1 - j0) / 2 : j1;
    const int xs[3] = {i0, im, i1}, ys[3] = {j0, jm, j1};
    for (int b = 0; b < 2; ++b)
      for (int a = 0; a < 2; ++a) {
        if (xs[a] >= xs[a + 1] || ys[b] >= ys[b + 1]) continue;
        level(L + 1).enc = here.enc;
        window(xs[a], xs[a + 1], ys[b], ys[b + 1], L + 1, here.inv);
      }
  }

  const ScreenScene& s_;
  const Window& w_;
  Image& img_;
  std::vector<Lists> levels_;
};

}  // namespace

Image warnock(const ScreenScene& s, const Window& w) {
  Image img{w.R, std::vector<std::int32_t>(static_cast<std::size_t>(w.R) * w.R, -1)};
  Subdivider(s, w, img).run();
  return img;
}

}  // namespace vismap::raster
