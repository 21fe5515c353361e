// Exact labels at pixel centres, and the pixel and line errors of an image
// (see exact_error.h).
#include "bench/raster/exact_error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>

#include "verify/json.h"

namespace vismap::raster {
namespace {

constexpr double kEps = 0x1.0p-53;   // unit roundoff

// Compares the double a with the rational q whose truncated double is qd:
// decided in doubles when a is clearly apart (|q - qd| < 2^-52 |qd|), else
// exactly.
int cmp_dq(double a, const mpq_class& q, double qd) {
  const double margin = 4 * kEps * std::abs(qd) + 1e-300;
  if (a < qd - margin) return -1;
  if (a > qd + margin) return 1;
  return cmp(mpq_class(a), q);
}

struct Crossing {
  int row;
  int q;        // first pixel index whose centre is right of the crossing
  int region;
};

class ExactRaster {
 public:
  ExactRaster(const VisibilityMap& map, const Window& w)
      : map_(map), w_(w), R_(w.R), tol_(1e-9 * w.pixel * w.R) {}

  // Places every crossing and boundary centre, then calls row(j, labels) for
  // j = 0 .. R-1 in order, with the R labels of row j (valid during the call).
  template <class RowFn>
  ExactLabels run(RowFn&& row) {
    for (std::size_t r = 0; r < map_.regions.size(); ++r) {
      const Region& reg = map_.regions[r];
      ring(map_.points(reg.outer), static_cast<int>(r));
      for (const auto& h : reg.holes) ring(map_.points(h), static_cast<int>(r));
    }
    return sweep(row);
  }

 private:
  // First row j in [0, R] with cy(j) >= y, exactly.
  int first_row_ge(const mpq_class& y, double yd) const {
    const double t = std::ceil((yd - w_.y0) / w_.pixel - 0.5);
    int j = t <= 0 ? 0 : t >= R_ ? R_ : static_cast<int>(t);
    while (j < R_ && cmp_dq(w_.cy(j), y, yd) < 0) ++j;
    while (j > 0 && cmp_dq(w_.cy(j - 1), y, yd) >= 0) --j;
    return j;
  }
  // First column i in [0, R] with cx(i) >= x (or > x when strict), exactly.
  int first_col(const mpq_class& x, double xd, bool strict) const {
    const double t = std::ceil((xd - w_.x0) / w_.pixel - 0.5);
    int i = t <= 0 ? 0 : t >= R_ ? R_ : static_cast<int>(t);
    auto right_of = [&](int k) {
      const int c = cmp_dq(w_.cx(k), x, xd);
      return strict ? c > 0 : c >= 0;
    };
    while (i < R_ && !right_of(i)) ++i;
    while (i > 0 && right_of(i - 1)) --i;
    return i;
  }
  // First column i in [0, R] with cx(i) > v, in doubles.
  int first_col_gt(double v) const {
    const double t = std::floor((v - w_.x0) / w_.pixel - 0.5) + 1;
    int i = t <= 0 ? 0 : t >= R_ ? R_ : static_cast<int>(t);
    while (i < R_ && !(w_.cx(i) > v)) ++i;
    while (i > 0 && w_.cx(i - 1) > v) --i;
    return i;
  }

  void mark(int i, int j) { on_.push_back({j, i}); }   // may repeat: made unique in sweep

  void ring(const std::vector<Point2>& pts, int region) {
    const std::size_t n = pts.size();
    std::vector<double> xd(n), yd(n);
    for (std::size_t k = 0; k < n; ++k) {
      xd[k] = pts[k].x.get_d();
      yd[k] = pts[k].y.get_d();
    }
    for (std::size_t k = 0; k < n; ++k) {
      vertex(pts[k], xd[k], yd[k]);
      const std::size_t l = (k + 1) % n;
      edge(pts[k], xd[k], yd[k], pts[l], xd[l], yd[l], region);
    }
  }

  // A pixel centre exactly at a vertex is on the boundary.
  void vertex(const Point2& v, double vx, double vy) {
    const int j = first_row_ge(v.y, vy);
    if (j >= R_ || cmp(mpq_class(w_.cy(j)), v.y) != 0) return;
    const int i = first_col(v.x, vx, false);
    if (i < R_ && cmp(mpq_class(w_.cx(i)), v.x) == 0) mark(i, j);
  }

  void edge(const Point2& a, double ax, double ay, const Point2& b, double bx, double by, int region) {
    const int c = cmp(a.y, b.y);
    if (c == 0) {   // horizontal: the centres on it are on the boundary
      const int j = first_row_ge(a.y, ay);
      if (j >= R_ || cmp(mpq_class(w_.cy(j)), a.y) != 0) return;
      const bool a_left = cmp(a.x, b.x) < 0;
      const Point2& l = a_left ? a : b;
      const Point2& r = a_left ? b : a;
      const int i0 = first_col(l.x, a_left ? ax : bx, false), i1 = first_col(r.x, a_left ? bx : ax, true);
      for (int i = i0; i < i1; ++i) mark(i, j);
      return;
    }
    // Rows with lo.y <= cy(j) < hi.y cross the edge (the half-open rule).
    const bool a_low = c < 0;
    const Point2& lo = a_low ? a : b;
    const Point2& hi = a_low ? b : a;
    const double lx = a_low ? ax : bx, ly = a_low ? ay : by, hx = a_low ? bx : ax, hy = a_low ? by : ay;
    const int j0 = first_row_ge(lo.y, ly), j1 = first_row_ge(hi.y, hy);
    const double dx = hx - lx, dy = hy - ly;
    const double slope = dx / dy;
    const double big = std::max({std::abs(lx), std::abs(ly), std::abs(hx), std::abs(hy)});
    bool have_exact_slope = false;
    mpq_class qslope;
    for (int j = j0; j < j1; ++j) {
      const double y = w_.cy(j);
      const double x = lx + (y - ly) * slope;
      // Error of x against the true crossing: endpoints truncated to doubles
      // (2^-52 relative) and five roundings. To first order in eps it is at most
      // eps * (11 m (1 + |slope|) + 6 |x|); the bound below has room to spare
      // for the second-order terms, which stay small while dy is far above the
      // endpoints' errors (the first condition).
      const double m = std::max(big, std::abs(y));
      const double err = 16 * kEps * (m * (1 + std::abs(slope)) + std::abs(x));
      ++crossings_;
      if (dy > 4096 * kEps * m && err <= tol_ && std::isfinite(x)) {
        const double h = tol_ + err;
        const int q0 = first_col_gt(x - h), q1 = first_col_gt(x + h);
        if (q0 == q1) {   // no centre within h of x: every side is certain
          cross_.push_back({j, q0, region});
          continue;
        }
      }
      ++exact_crossings_;
      if (!have_exact_slope) {
        qslope = (hi.x - lo.x) / (hi.y - lo.y);
        have_exact_slope = true;
      }
      const mpq_class X = lo.x + (mpq_class(y) - lo.y) * qslope;
      const int q = first_col(X, X.get_d(), true);
      if (q > 0 && cmp(mpq_class(w_.cx(q - 1)), X) == 0) mark(q - 1, j);
      cross_.push_back({j, q, region});
    }
  }

  template <class RowFn>
  ExactLabels sweep(RowFn&& emit) {
    ExactLabels out;
    std::sort(on_.begin(), on_.end());
    on_.erase(std::unique(on_.begin(), on_.end()), on_.end());
    // Crossings by row (counting sort), then by column within a row.
    std::vector<std::size_t> start(static_cast<std::size_t>(R_) + 1, 0);
    for (const Crossing& c : cross_) ++start[static_cast<std::size_t>(c.row) + 1];
    for (std::size_t j = 1; j < start.size(); ++j) start[j] += start[j - 1];
    std::vector<Crossing> by_row(cross_.size());
    {
      std::vector<std::size_t> at(start.begin(), start.end() - 1);
      for (const Crossing& c : cross_) by_row[at[static_cast<std::size_t>(c.row)]++] = c;
    }
    cross_ = {};
    std::vector<int> odd;                                  // regions with odd parity
    std::vector<int> slot(map_.regions.size(), -1);        // position in odd
    auto toggle = [&](int r) {
      if (slot[r] < 0) {
        slot[r] = static_cast<int>(odd.size());
        odd.push_back(r);
      } else {
        const int at = slot[r];
        odd[at] = odd.back();
        slot[odd[at]] = at;
        odd.pop_back();
        slot[r] = -1;
      }
    };
    std::vector<std::int32_t> row(static_cast<std::size_t>(R_));
    auto on = on_.begin();
    for (int j = 0; j < R_; ++j) {
      auto first = by_row.begin() + static_cast<std::ptrdiff_t>(start[j]);
      auto last = by_row.begin() + static_cast<std::ptrdiff_t>(start[j + 1]);
      std::sort(first, last, [](const Crossing& a, const Crossing& b) { return a.q < b.q; });
      auto it = first;
      for (int i = 0; i < R_;) {
        while (it != last && it->q <= i) toggle((it++)->region);
        // Constant up to the next crossing.
        const int next = it != last ? std::min(it->q, R_) : R_;
        std::int32_t label = -1;
        if (odd.size() == 1) {
          label = map_.regions[static_cast<std::size_t>(odd[0])].face;
        } else if (odd.size() > 1) {
          throw std::logic_error("exact_labels: regions overlap at pixel (" + std::to_string(i) + ", " +
                                 std::to_string(j) + ")");
        }
        std::fill(row.begin() + i, row.begin() + next, label);
        i = next;
      }
      while (it != last) toggle((it++)->region);
      if (!odd.empty()) throw std::logic_error("exact_labels: a ring is not closed on row " + std::to_string(j));
      for (; on != on_.end() && on->first == j; ++on) row[static_cast<std::size_t>(on->second)] = kOnBoundary;
      emit(j, row.data());
    }
    out.boundary = on_.size();
    out.crossings = crossings_;
    out.exact_crossings = exact_crossings_;
    return out;
  }

  const VisibilityMap& map_;
  const Window& w_;
  const int R_;
  const double tol_;
  std::vector<std::pair<int, int>> on_;   // (row, column) of centres exactly on a boundary
  std::vector<Crossing> cross_;
  std::size_t boundary_ = 0, crossings_ = 0, exact_crossings_ = 0;
};

}  // namespace

ExactLabels exact_labels(const VisibilityMap& map, const Window& w) {
  Image img{w.R, std::vector<std::int32_t>(static_cast<std::size_t>(w.R) * w.R)};
  ExactLabels out = ExactRaster(map, w).run([&](int j, const std::int32_t* row) {
    std::copy(row, row + w.R, img.label.begin() + static_cast<std::ptrdiff_t>(j) * w.R);
  });
  out.image = std::move(img);
  return out;
}

std::vector<AreaError> area_error(const VisibilityMap& map, const std::vector<const Image*>& images, const Window& w,
                                  int k) {
  if (k < 1) throw std::invalid_argument("area_error: need k >= 1");
  for (const Image* img : images)
    if (img->R != w.R) throw std::invalid_argument("area_error: image and window of different sizes");
  // The fine grid: each pixel split into k x k; pixel / k is exact for k a power
  // of two, and in any case the fine centres are the points where the labels
  // are compared.
  Window fine;
  fine.R = w.R * k;
  fine.x0 = w.x0;
  fine.y0 = w.y0;
  fine.pixel = w.pixel / k;
  std::vector<AreaError> out(images.size());
  ExactRaster(map, fine).run([&](int jf, const std::int32_t* row) {
    const std::size_t base = static_cast<std::size_t>(jf / k) * w.R;
    for (std::size_t m = 0; m < images.size(); ++m) {
      const std::int32_t* coarse = images[m]->label.data() + base;
      AreaError& e = out[m];
      for (int i = 0; i < fine.R; ++i) {
        if (row[i] == kOnBoundary) continue;
        ++e.samples;
        if (row[i] != coarse[i / k]) ++e.wrong;
      }
    }
  });
  return out;
}

PixelError pixel_error(const Image& exact, const Image& image) {
  if (exact.R != image.R) throw std::invalid_argument("pixel_error: images of different sizes");
  PixelError e;
  for (std::size_t k = 0; k < exact.label.size(); ++k) {
    if (exact.label[k] == kOnBoundary) {
      ++e.boundary;
      continue;
    }
    ++e.compared;
    if (exact.label[k] != image.label[k]) ++e.wrong;
  }
  return e;
}

LineError line_error(const VisibilityMap& map, const Image& image, const Window& w, const LineRule& rule,
                     double tol) {
  const int R = image.R;
  const std::size_t n = static_cast<std::size_t>(R) * (R + 1);
  // Pixel sides, outside the window counting as background: vside[j*(R+1) + i]
  // (0 <= i <= R) between pixels (i-1, j) and (i, j), midpoint (i, j + 0.5) in
  // pixel units; hside[j*R + i] (0 <= j <= R) between (i, j-1) and (i, j),
  // midpoint (i + 0.5, j). Bit 0: drawn; bit 1: an exact segment passes within tol.
  std::vector<std::uint8_t> vside(n, 0), hside(n, 0);
  auto label = [&](int i, int j) { return i < 0 || j < 0 || i >= R || j >= R ? -1 : image.at(i, j); };
  for (int j = 0; j <= R; ++j)
    for (int i = 0; i <= R; ++i) {
      if (j < R) {
        const std::int32_t f = label(i - 1, j), g = label(i, j);
        if (f != g && rule.drawn(f, g, w.x0 + i * w.pixel, w.cy(j), w.pixel))
          vside[static_cast<std::size_t>(j) * (R + 1) + i] = 1;
      }
      if (i < R) {
        const std::int32_t f = label(i, j - 1), g = label(i, j);
        if (f != g && rule.drawn(f, g, w.cx(i), w.y0 + j * w.pixel, w.pixel))
          hside[static_cast<std::size_t>(j) * R + i] = 1;
      }
    }

  LineError e;
  const double inv = 1 / w.pixel;
  const double tol2 = tol * tol;
  // Calls fn(side array, index, midpoint u, v) for every pixel side whose
  // midpoint is within `reach` pixels of (u, v) (box test; fn measures).
  auto near_sides = [&](double u, double v, double reach, auto&& fn) {
    // vertical sides: midpoint (i, j + 0.5)
    const int vi0 = std::max(0, static_cast<int>(std::ceil(u - reach))),
              vi1 = std::min(R, static_cast<int>(std::floor(u + reach)));
    const int vj0 = std::max(0, static_cast<int>(std::ceil(v - reach - 0.5))),
              vj1 = std::min(R - 1, static_cast<int>(std::floor(v + reach - 0.5)));
    for (int j = vj0; j <= vj1; ++j)
      for (int i = vi0; i <= vi1; ++i) fn(vside, static_cast<std::size_t>(j) * (R + 1) + i, i + 0.0, j + 0.5);
    // horizontal sides: midpoint (i + 0.5, j)
    const int hi0 = std::max(0, static_cast<int>(std::ceil(u - reach - 0.5))),
              hi1 = std::min(R - 1, static_cast<int>(std::floor(u + reach - 0.5)));
    const int hj0 = std::max(0, static_cast<int>(std::ceil(v - reach))),
              hj1 = std::min(R, static_cast<int>(std::floor(v + reach)));
    for (int j = hj0; j <= hj1; ++j)
      for (int i = hi0; i <= hi1; ++i) fn(hside, static_cast<std::size_t>(j) * R + i, i + 0.5, j + 0.0);
  };

  for (const Segment& s : map.segments) {
    const Point2 &from = map.at(s.from), &to = map.at(s.to);
    const double au = (from.x.get_d() - w.x0) * inv, av = (from.y.get_d() - w.y0) * inv;
    const double bu = (to.x.get_d() - w.x0) * inv, bv = (to.y.get_d() - w.y0) * inv;
    const double du = bu - au, dv = bv - av;
    const double len = std::sqrt(du * du + dv * dv);   // pixels
    e.exact_length += len * w.pixel;
    if (!(len > 0)) continue;
    // Sides within tol of the segment: look around points 1 pixel apart.
    auto dist2 = [&](double mu, double mv) {
      double t = ((mu - au) * du + (mv - av) * dv) / (len * len);
      t = std::clamp(t, 0.0, 1.0);
      const double pu = au + t * du - mu, pv = av + t * dv - mv;
      return pu * pu + pv * pv;
    };
    const int steps = static_cast<int>(std::ceil(len));
    for (int k = 0; k <= steps; ++k) {
      const double t = static_cast<double>(k) / steps;
      near_sides(au + t * du, av + t * dv, tol + 0.5, [&](std::vector<std::uint8_t>& side, std::size_t at, double mu,
                                                          double mv) {
        if (!(side[at] & 2) && dist2(mu, mv) <= tol2) side[at] |= 2;
      });
    }
    // Missed: samples at most half a pixel apart, each standing for its share.
    const int samples = std::max(1, static_cast<int>(std::ceil(2 * len)));
    for (int k = 0; k < samples; ++k) {
      const double t = (k + 0.5) / samples;
      const double u = au + t * du, v = av + t * dv;
      bool found = false;
      near_sides(u, v, tol, [&](std::vector<std::uint8_t>& side, std::size_t at, double mu, double mv) {
        if (!found && (side[at] & 1) && (mu - u) * (mu - u) + (mv - v) * (mv - v) <= tol2) found = true;
      });
      if (!found) e.missed += len * w.pixel / samples;
    }
  }
  std::size_t false_sides = 0;
  for (std::size_t k = 0; k < n; ++k) {
    if (vside[k] == 1) ++false_sides;
    if (hside[k] == 1) ++false_sides;
  }
  e.false_drawn = static_cast<double>(false_sides) * w.pixel;
  return e;
}

namespace {

using vismap_check::Json;

const Json& need(const Json& j, std::string_view key, Json::Type type) {
  const Json* v = j.get(key);
  if (!v || !v->is(type)) throw std::runtime_error("map JSON: missing or mistyped \"" + std::string(key) + "\"");
  return *v;
}

mpq_class rational(const Json& j) {
  if (!j.is(Json::Type::String)) throw std::runtime_error("map JSON: a number must be a string \"p/q\"");
  mpq_class q;
  if (q.set_str(j.text, 10) != 0) throw std::runtime_error("map JSON: bad rational \"" + j.text + "\"");
  q.canonicalize();
  return q;
}

Point2 point(const Json& j) {
  if (!j.is(Json::Type::Array) || j.items.size() != 2) throw std::runtime_error("map JSON: a point is [x, y]");
  return {rational(j.items[0]), rational(j.items[1])};
}

// The map's vertices as read, each once; numbered in lexicographic order at the end.
struct VertexTable {
  struct Less {   // lexicographic
    bool operator()(const Point2& a, const Point2& b) const {
      const int c = cmp(a.x, b.x);
      return c ? c < 0 : a.y < b.y;
    }
  };
  std::map<Point2, std::uint32_t, Less> id;
  std::uint32_t of(const Json& j) { return id.emplace(point(j), static_cast<std::uint32_t>(id.size())).first->second; }
  Ring ring(const Json& j) {
    if (!j.is(Json::Type::Array)) throw std::runtime_error("map JSON: a ring is an array of points");
    Ring out;
    for (const Json& p : j.items) out.push_back(of(p));
    return out;
  }
  void finish(VisibilityMap& map) {
    std::vector<std::uint32_t> rank(id.size());
    for (auto& [p, i] : id) {
      rank[i] = static_cast<std::uint32_t>(map.vertices.size());
      map.vertices.push_back(p);
    }
    for (Region& r : map.regions) {
      for (auto& v : r.outer) v = rank[v];
      for (auto& h : r.holes) for (auto& v : h) v = rank[v];
    }
    for (Segment& s : map.segments) { s.from = rank[s.from]; s.to = rank[s.to]; }
  }
};

int integer(const Json& j) {
  if (!j.is(Json::Type::Number)) throw std::runtime_error("map JSON: expected an integer");
  return std::stoi(j.text);
}

}  // namespace

VisibilityMap read_map_json(std::string_view text) {
  Json doc;
  try {
    doc = vismap_check::parse_json(text);
  } catch (const vismap_check::JsonError& e) {
    throw std::runtime_error(std::string("map JSON: ") + e.what());
  }
  VisibilityMap map;
  map.perspective = need(doc, "projection", Json::Type::String).text == "perspective";
  const Json& m = need(doc, "view_matrix", Json::Type::Array);
  if (m.items.size() != 4) throw std::runtime_error("map JSON: view_matrix must be 4x4");
  for (int r = 0; r < 4; ++r) {
    if (!m.items[r].is(Json::Type::Array) || m.items[r].items.size() != 4)
      throw std::runtime_error("map JSON: view_matrix must be 4x4");
    for (int c = 0; c < 4; ++c) map.view[r][c] = rational(m.items[r].items[c]);
  }
  VertexTable vertices;
  for (const Json& r : need(doc, "regions", Json::Type::Array).items) {
    Region reg;
    reg.face = integer(need(r, "face", Json::Type::Number));
    reg.outer = vertices.ring(need(r, "outer", Json::Type::Array));
    if (const Json* h = r.get("holes"))
      for (const Json& ring : h->items) reg.holes.push_back(vertices.ring(ring));
    map.regions.push_back(std::move(reg));
  }
  for (const Json& s : need(doc, "segments", Json::Type::Array).items) {
    Segment seg;
    seg.from = vertices.of(need(s, "from", Json::Type::Array));
    seg.to = vertices.of(need(s, "to", Json::Type::Array));
    const std::string& k = need(s, "kind", Json::Type::String).text;
    seg.kind = k == "border"        ? EdgeKind::Border
               : k == "silhouette"  ? EdgeKind::Silhouette
               : k == "crease"      ? EdgeKind::Crease
               : k == "smooth"      ? EdgeKind::Smooth
               : k == "intersection" ? EdgeKind::Intersection
                                     : throw std::runtime_error("map JSON: unknown segment kind \"" + k + "\"");
    for (const Json& f : need(s, "faces", Json::Type::Array).items) seg.faces.push_back(integer(f));
    map.segments.push_back(std::move(seg));
  }
  vertices.finish(map);
  return map;
}

View view_of(const VisibilityMap& map) {
  View v;
  v.perspective = map.perspective;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) v.m[r][c] = map.view[r][c].get_d();
  if (v.perspective) {
    // Solve rows 0, 1, 3 of m * (e, 1) = 0 for the eye e (Cramer's rule).
    const auto& m = v.m;
    const double a[3][3] = {{m[0][0], m[0][1], m[0][2]}, {m[1][0], m[1][1], m[1][2]}, {m[3][0], m[3][1], m[3][2]}};
    const double rhs[3] = {-m[0][3], -m[1][3], -m[3][3]};
    auto det3 = [](const double q[3][3]) {
      return q[0][0] * (q[1][1] * q[2][2] - q[1][2] * q[2][1]) - q[0][1] * (q[1][0] * q[2][2] - q[1][2] * q[2][0]) +
             q[0][2] * (q[1][0] * q[2][1] - q[1][1] * q[2][0]);
    };
    const double d = det3(a);
    double e[3];
    for (int k = 0; k < 3; ++k) {
      double b[3][3];
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) b[r][c] = c == k ? rhs[r] : a[r][c];
      e[k] = det3(b) / d;
    }
    v.eye = {e[0], e[1], e[2]};
  }
  return v;
}

}  // namespace vismap::raster
