#include "arrangements/drawing.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <map>
#include <unordered_map>
#include <utility>

namespace vismap {

// ---- classes and styles -------------------------------------------------------------

const char* class_name(LineClass c) {
  static const char* const kNames[kLineClasses] = {"hidden", "smooth", "intersection", "crease", "outline"};
  return kNames[static_cast<std::size_t>(c)];
}

bool parse_line_class(std::string_view name, LineClass& out) {
  for (std::size_t i = 0; i < kLineClasses; ++i)
    if (name == class_name(static_cast<LineClass>(i))) {
      out = static_cast<LineClass>(i);
      return true;
    }
  return false;
}

LineClass class_of(EdgeKind kind, bool hidden) {
  if (hidden) return LineClass::Hidden;
  switch (kind) {
    case EdgeKind::Crease: return LineClass::Crease;
    case EdgeKind::Smooth: return LineClass::Smooth;
    case EdgeKind::Intersection: return LineClass::Intersection;
    default: return LineClass::Outline;
  }
}

namespace {

LineStyle& of(DrawingStyle& s, LineClass c) { return s.line[static_cast<std::size_t>(c)]; }

void all_visible(DrawingStyle& s, double width, const std::string& color) {
  for (LineClass c : {LineClass::Smooth, LineClass::Intersection, LineClass::Crease, LineClass::Outline})
    of(s, c) = LineStyle{width, color, {}};
}

bool parse_number(std::string_view t, double& v) {
  const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
  return r.ec == std::errc() && r.ptr == t.data() + t.size() && std::isfinite(v);
}

}  // namespace

bool preset_style(std::string_view name, DrawingStyle& out) {
  DrawingStyle s;
  s.name = std::string(name);
  if (name == "technical") {   // ISO 128: thick 0.5 continuous, thin 0.25 dashed (dash 12d, gap 3d)
    s.fills = false;
    all_visible(s, 0.5, "black");
    of(s, LineClass::Hidden) = LineStyle{0.25, "black", {3, 0.75}};
  } else if (name == "shaded") {
    s.fills = true;
    all_visible(s, 0.25, "black");
    of(s, LineClass::Hidden) = LineStyle{0.125, "black", {1, 0.5}};
  } else if (name == "plotter") {   // one pen per layer
    s.fills = false;
    s.cut_dashes = true;
    of(s, LineClass::Outline) = LineStyle{0.3, "black", {}};
    of(s, LineClass::Crease) = LineStyle{0.3, "blue", {}};
    of(s, LineClass::Intersection) = LineStyle{0.3, "red", {}};
    of(s, LineClass::Smooth) = LineStyle{0.3, "green", {}};
    of(s, LineClass::Hidden) = LineStyle{0.3, "gray", {2, 1}};
  } else {
    return false;
  }
  out = std::move(s);
  return true;
}

DrawingStyle shaded_style() {
  DrawingStyle s;
  preset_style("shaded", s);
  return s;
}

bool override_line_style(std::string_view spec, DrawingStyle& style, std::string& error) {
  const auto colon = spec.find(':');
  LineClass c;
  if (colon == std::string_view::npos || !parse_line_class(spec.substr(0, colon), c)) {
    error = "expects CLASS:width=W,color=C,dash=A/B with CLASS one of hidden, smooth, intersection, crease, outline";
    return false;
  }
  LineStyle& ls = of(style, c);
  std::string_view rest = spec.substr(colon + 1);
  while (!rest.empty()) {
    const auto comma = rest.find(',');
    const std::string_view item = rest.substr(0, comma);
    rest = comma == std::string_view::npos ? std::string_view{} : rest.substr(comma + 1);
    const auto eq = item.find('=');
    const std::string_view key = item.substr(0, eq), value = eq == std::string_view::npos ? "" : item.substr(eq + 1);
    if (key == "width" && parse_number(value, ls.width) && ls.width > 0) continue;
    if (key == "color" && !value.empty() && value.find_first_of("\"<>&'") == std::string_view::npos) {
      ls.color = std::string(value);
      continue;
    }
    if (key == "dash") {
      ls.dash.clear();
      bool ok = value != "none";
      for (std::string_view v = value; ok && !v.empty();) {
        const auto slash = v.find('/');
        double d;
        ok = parse_number(v.substr(0, slash), d) && d > 0;
        if (ok) ls.dash.push_back(d);
        v = slash == std::string_view::npos ? std::string_view{} : v.substr(slash + 1);
      }
      if (value == "none" || (ok && ls.dash.size() % 2 == 0)) continue;
    }
    error = "cannot read '" + std::string(item) + "' (width=MM, color=NAME or #RRGGBB, dash=ON/OFF[/ON/OFF...] or none)";
    return false;
  }
  return true;
}

// ---- shading --------------------------------------------------------------------------

bool parse_shading(std::string_view text, Shading& out) {
  std::vector<double> v;
  while (!text.empty()) {
    const auto comma = text.find(',');
    double x;
    if (!parse_number(text.substr(0, comma), x)) return false;
    v.push_back(x);
    text = comma == std::string_view::npos ? std::string_view{} : text.substr(comma + 1);
  }
  if (v.size() != 3 && v.size() != 5) return false;
  if (std::any_of(v.begin(), v.end(), [](double x) { return x < 0; })) return false;
  out.r = v[0];
  out.n = v[1];
  out.b = v[2];
  if (v.size() == 5) {
    out.s = v[3];
    out.m = v[4];
  }
  return true;
}

std::array<int, 3> face_rgb(const Scene& scene, const View& view, int face, const Shading& sh) {
  const auto& f = scene.faces[static_cast<std::size_t>(face)];
  double nx = 0, ny = 0, nz = 0, cx = 0, cy = 0, cz = 0;
  for (std::size_t i = 0; i < f.size(); ++i) {   // Newell's normal
    const Vec3 &p = scene.vertices[f[i]], &q = scene.vertices[f[(i + 1) % f.size()]];
    nx += (p.y - q.y) * (p.z + q.z);
    ny += (p.z - q.z) * (p.x + q.x);
    nz += (p.x - q.x) * (p.y + q.y);
    cx += p.x; cy += p.y; cz += p.z;
  }
  double dx = view.m[2][0], dy = view.m[2][1], dz = view.m[2][2];   // the light at the eye
  if (sh.light_given) {
    dx = sh.light[0]; dy = sh.light[1]; dz = sh.light[2];
  } else if (view.perspective) {
    const double k = static_cast<double>(f.size());
    dx = cx / k - view.eye.x; dy = cy / k - view.eye.y; dz = cz / k - view.eye.z;
  }
  const double nn = std::sqrt(nx * nx + ny * ny + nz * nz), dd = std::sqrt(dx * dx + dy * dy + dz * dz);
  const double c = (nn > 0 && dd > 0) ? std::min(1.0, std::abs(nx * dx + ny * dy + nz * dz) / (nn * dd)) : 0;
  const double sine = std::sqrt(std::max(0.0, 1 - c * c));
  const double i = std::clamp(sh.r * std::pow(c, sh.n) + sh.b + sh.s * std::pow(sine, sh.m), 0.0, 1.0);
  const int g = static_cast<int>(std::lround(255 * i));
  return {g, g, std::min(255, g + 12)};
}

// ---- the page -----------------------------------------------------------------------

bool parse_page(std::string_view text, PageOptions& page) {
  static const std::pair<const char*, std::array<double, 2>> kSizes[] = {
      {"a4", {210, 297}}, {"a3", {297, 420}}, {"letter", {215.9, 279.4}}};
  for (const auto& [name, wh] : kSizes)
    if (text == name) {
      page.width = wh[0];
      page.height = wh[1];
      page.named = true;
      return true;
    }
  if (text.size() < 5 || text.substr(text.size() - 2) != "mm") return false;
  const std::string_view dims = text.substr(0, text.size() - 2);
  const auto x = dims.find('x');
  double w, h;
  if (x == std::string_view::npos || !parse_number(dims.substr(0, x), w) || !parse_number(dims.substr(x + 1), h) ||
      !(w > 0 && h > 0))
    return false;
  page.width = w;
  page.height = h;
  page.named = false;
  return true;
}

bool parse_scale(std::string_view text, double& scale) {
  double n;
  if (text.rfind("1:", 0) == 0) {
    if (!parse_number(text.substr(2), n) || !(n > 0)) return false;
    scale = 1 / n;
    return true;
  }
  if (!parse_number(text, n) || !(n > 0)) return false;
  scale = n;
  return true;
}

Placement place(const VisibilityMap& map, const PageOptions& page) {
  double xa = HUGE_VAL, ya = HUGE_VAL, xb = -HUGE_VAL, yb = -HUGE_VAL;
  auto grow = [&](const Point2& p) {
    const double x = p.x.get_d(), y = p.y.get_d();
    xa = std::min(xa, x); xb = std::max(xb, x);
    ya = std::min(ya, y); yb = std::max(yb, y);
  };
  for (const Point2& p : map.vertices) grow(p);   // (every vertex is on an outer ring or a segment)
  for (const HiddenSegment& h : map.hidden) { grow(h.from); grow(h.to); }
  if (xa > xb) { xa = ya = 0; xb = yb = 1; }
  const double ew = xb - xa, eh = yb - ya, extent = std::max({ew, eh, 1e-300});
  Placement pl;
  pl.x0 = xa;
  pl.y0 = ya;
  if (page.width == 0) {   // a canvas around the drawing, in px
    const double margin = 0.03 * page.size;
    pl.k = (page.size - 2 * margin) / extent;
    pl.left = pl.bottom = margin;
    pl.width = ew * pl.k + 2 * margin;
    pl.height = eh * pl.k + 2 * margin;
    return pl;
  }
  pl.mm = true;
  pl.width = page.width;
  pl.height = page.height;
  if (page.named && (ew > eh) != (pl.width > pl.height)) std::swap(pl.width, pl.height);
  const double room_w = std::max(pl.width - 2 * page.margin, 1e-9), room_h = std::max(pl.height - 2 * page.margin, 1e-9);
  pl.k = page.scale > 0 ? page.scale : std::min(room_w / std::max(ew, 1e-300), room_h / std::max(eh, 1e-300));
  pl.left = (pl.width - ew * pl.k) / 2;
  pl.bottom = (pl.height - eh * pl.k) / 2;
  return pl;
}

// ---- chains -------------------------------------------------------------------------

namespace {

// The drawing's lines: end points as ids (the map's vertices, then the hidden
// lines' distinct end points), and the group a line chains within.
struct Line {
  std::uint32_t a, b;
  int group;
  LineClass cls;
  EdgeKind kind;
  const std::vector<int>* faces;
};

struct LineSet {
  std::vector<Line> lines;
  std::vector<const Point2*> point;   // by id
};

LineSet lines_of(const VisibilityMap& map, bool by_provenance) {
  LineSet ls;
  for (const Point2& p : map.vertices) ls.point.push_back(&p);
  // Hidden end points: ids by exact value.
  std::vector<const Point2*> ends;
  for (const HiddenSegment& h : map.hidden) { ends.push_back(&h.from); ends.push_back(&h.to); }
  auto less = [](const Point2* a, const Point2* b) { return *a < *b; };
  std::sort(ends.begin(), ends.end(), less);
  ends.erase(std::unique(ends.begin(), ends.end(), [](const Point2* a, const Point2* b) { return *a == *b; }), ends.end());
  const auto first_hidden = static_cast<std::uint32_t>(ls.point.size());
  ls.point.insert(ls.point.end(), ends.begin(), ends.end());
  auto hidden_id = [&](const Point2& p) {
    return first_hidden + static_cast<std::uint32_t>(std::lower_bound(ends.begin(), ends.end(), &p, less) - ends.begin());
  };
  std::map<std::tuple<LineClass, EdgeKind, std::vector<int>>, int> groups;
  auto group = [&](LineClass c, EdgeKind k, const std::vector<int>& f) {
    if (!by_provenance) return static_cast<int>(c);
    return groups.emplace(std::tuple(c, k, f), static_cast<int>(groups.size())).first->second;
  };
  for (const Segment& s : map.segments) {
    const LineClass c = class_of(s.kind, false);
    ls.lines.push_back(Line{s.from, s.to, group(c, s.kind, s.faces), c, s.kind, &s.faces});
  }
  for (const HiddenSegment& h : map.hidden)
    ls.lines.push_back(Line{hidden_id(h.from), hidden_id(h.to), group(LineClass::Hidden, h.kind, h.faces),
                            LineClass::Hidden, h.kind, &h.faces});
  return ls;
}

}  // namespace

std::vector<Chain> chains_of(const VisibilityMap& map, bool by_provenance) {
  const LineSet ls = lines_of(map, by_provenance);
  const std::vector<Line>& lines = ls.lines;
  // The lines of each group at each point.
  std::unordered_map<std::uint64_t, std::vector<int>> star;
  auto key = [](int group, std::uint32_t p) { return (static_cast<std::uint64_t>(group) << 32) | p; };
  for (std::size_t i = 0; i < lines.size(); ++i)
    for (std::uint32_t p : {lines[i].a, lines[i].b}) star[key(lines[i].group, p)].push_back(static_cast<int>(i));
  auto through = [&](int group, std::uint32_t p) { return star[key(group, p)].size() == 2; };
  std::vector<char> used(lines.size(), 0);
  std::vector<std::vector<std::uint32_t>> paths;
  std::vector<int> first_line;
  auto walk = [&](int e, std::uint32_t from) {
    std::vector<std::uint32_t> path{from};
    for (std::uint32_t p = from;;) {
      used[static_cast<std::size_t>(e)] = 1;
      const Line& l = lines[static_cast<std::size_t>(e)];
      p = l.a == p ? l.b : l.a;
      path.push_back(p);
      if (!through(l.group, p)) break;
      const std::vector<int>& two = star[key(l.group, p)];
      e = two[0] == e ? two[1] : two[0];
      if (used[static_cast<std::size_t>(e)]) break;   // round a cycle
    }
    return path;
  };
  // Open chains from their ends, in the order of their first line; then cycles.
  std::vector<std::pair<int, std::vector<std::uint32_t>>> found;
  for (int pass = 0; pass < 2; ++pass)
    for (std::size_t i = 0; i < lines.size(); ++i) {
      if (used[i]) continue;
      const Line& l = lines[i];
      if (pass == 0 && through(l.group, l.a) && through(l.group, l.b)) continue;
      const std::uint32_t from = pass == 1 || !through(l.group, l.a) ? l.a : l.b;
      found.emplace_back(static_cast<int>(i), walk(static_cast<int>(i), from));
    }
  std::stable_sort(found.begin(), found.end(), [&](const auto& x, const auto& y) {
    const Line &a = lines[static_cast<std::size_t>(x.first)], &b = lines[static_cast<std::size_t>(y.first)];
    return a.cls != b.cls ? a.cls < b.cls : x.first < y.first;
  });
  std::vector<Chain> out;
  out.reserve(found.size());
  for (auto& [first, path] : found) {
    const Line& l = lines[static_cast<std::size_t>(first)];
    Chain c;
    c.cls = l.cls;
    c.kind = l.kind;
    c.faces = *l.faces;
    c.closed = path.size() > 2 && path.front() == path.back();
    if (c.closed) path.pop_back();
    for (std::uint32_t p : path) c.screen.push_back({ls.point[p]->x.get_d(), ls.point[p]->y.get_d()});
    out.push_back(std::move(c));
  }
  return out;
}

// ---- pen travel -----------------------------------------------------------------------

namespace {

double distance(const std::array<double, 2>& a, const std::array<double, 2>& b) {
  return std::hypot(a[0] - b[0], a[1] - b[1]);
}

// Where the pen starts and ends a chain, on the page.
std::array<double, 2> start(const Chain& c, const Placement& at) { return at.at(c.screen.front()); }
std::array<double, 2> finish(const Chain& c, const Placement& at) { return at.at(c.closed ? c.screen.front() : c.screen.back()); }

// Nearest-neighbour order of chains [begin, end) from pen position `pen`, over a
// uniform grid of their end points (rings of cells searched outwards).
void order_nearest(std::vector<Chain>& chains, std::size_t begin, std::size_t end, const Placement& at,
                   std::array<double, 2>& pen) {
  const std::size_t n = end - begin;
  if (n == 0) return;
  double xa = HUGE_VAL, ya = HUGE_VAL, xb = -HUGE_VAL, yb = -HUGE_VAL;
  for (std::size_t i = begin; i < end; ++i)
    for (const auto& p : {at.at(chains[i].screen.front()), at.at(chains[i].screen.back())}) {
      xa = std::min(xa, p[0]); xb = std::max(xb, p[0]);
      ya = std::min(ya, p[1]); yb = std::max(yb, p[1]);
    }
  const int side = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(n))));
  const double cw = std::max((xb - xa) / side, 1e-12), ch = std::max((yb - ya) / side, 1e-12);
  auto cell_of = [&](const std::array<double, 2>& p) {
    return std::array<int, 2>{std::clamp(static_cast<int>((p[0] - xa) / cw), 0, side - 1),
                              std::clamp(static_cast<int>((p[1] - ya) / ch), 0, side - 1)};
  };
  std::vector<std::vector<std::pair<std::size_t, bool>>> cells(static_cast<std::size_t>(side) * side);   // (chain, at its end)
  for (std::size_t i = begin; i < end; ++i)
    for (bool at_end : {false, true}) {
      const auto c = cell_of(at.at(at_end ? chains[i].screen.back() : chains[i].screen.front()));
      cells[static_cast<std::size_t>(c[1]) * side + c[0]].emplace_back(i, at_end);
    }
  std::vector<char> done(chains.size(), 0);
  std::vector<Chain> ordered;
  ordered.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    const auto c = cell_of(pen);
    std::size_t best = end;
    bool best_end = false;
    double best_d = HUGE_VAL;
    for (int r = 0; r < 2 * side; ++r) {
      // Cells at ring r are at least (r - 1) cells away: stop once that exceeds the best.
      if (best != end && (r - 1) * std::min(cw, ch) > best_d) break;
      for (int iy = c[1] - r; iy <= c[1] + r; ++iy)
        for (int ix = c[0] - r; ix <= c[0] + r; ++ix) {
          if (ix < 0 || iy < 0 || ix >= side || iy >= side) continue;
          if (std::max(std::abs(ix - c[0]), std::abs(iy - c[1])) != r) continue;
          for (const auto& [i, at_end] : cells[static_cast<std::size_t>(iy) * side + ix]) {
            if (done[i]) continue;
            const double d = distance(pen, at.at(at_end ? chains[i].screen.back() : chains[i].screen.front()));
            if (d < best_d || (d == best_d && i < best)) { best_d = d; best = i; best_end = at_end; }
          }
        }
    }
    done[best] = 1;
    Chain next = std::move(chains[best]);
    if (best_end && !next.closed) std::reverse(next.screen.begin(), next.screen.end());
    pen = finish(next, at);
    ordered.push_back(std::move(next));
  }
  std::move(ordered.begin(), ordered.end(), chains.begin() + static_cast<std::ptrdiff_t>(begin));
}

}  // namespace

std::vector<std::array<double, 2>> page_points(const Chain& c, const Placement& at) {
  std::vector<std::array<double, 2>> out;
  out.reserve(c.screen.size());
  for (const auto& p : c.screen) out.push_back(at.at(p));
  return out;
}

double travel(const std::vector<Chain>& chains, const Placement& at) {
  double t = 0;
  std::array<double, 2> pen{0, 0};
  for (const Chain& c : chains) {
    t += distance(pen, start(c, at));
    pen = finish(c, at);
  }
  return t;
}

void optimize_travel(std::vector<Chain>& chains, const Placement& at) {
  std::array<double, 2> pen{0, 0};
  for (std::size_t i = 0; i < chains.size();) {   // each class (a layer: one pen) on its own
    std::size_t j = i;
    while (j < chains.size() && chains[j].cls == chains[i].cls) ++j;
    order_nearest(chains, i, j, at, pen);
    i = j;
  }
}

Drawing make_drawing(const VisibilityMap& map, const PageOptions& page, bool by_provenance, bool optimize) {
  Drawing d;
  d.at = place(map, page);
  d.chains = chains_of(map, by_provenance);
  d.travel_before = d.travel_after = travel(d.chains, d.at);
  if (optimize) {
    optimize_travel(d.chains, d.at);
    d.travel_after = travel(d.chains, d.at);
  }
  return d;
}

// ---- dashes as geometry --------------------------------------------------------------

std::vector<std::vector<std::array<double, 2>>> dashed(const std::vector<std::array<double, 2>>& points, bool closed,
                                                       const std::vector<double>& dash) {
  std::vector<std::vector<std::array<double, 2>>> out;
  std::vector<std::array<double, 2>> pts = points;
  if (closed) pts.push_back(pts.front());
  if (dash.empty()) {
    out.push_back(pts);
    return out;
  }
  std::size_t k = 0;          // the dash pattern's current entry (even: drawn)
  double left = dash[0];      // of it
  std::vector<std::array<double, 2>> cur{pts[0]};
  for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
    std::array<double, 2> p = pts[i];
    const std::array<double, 2> q = pts[i + 1];
    double len = distance(p, q);
    while (len > left) {
      const double t = left / len;
      const std::array<double, 2> m{p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])};
      if (k % 2 == 0) {
        cur.push_back(m);
        out.push_back(std::move(cur));
        cur.clear();
      } else {
        cur = {m};
      }
      len -= left;
      p = m;
      k = (k + 1) % dash.size();
      left = dash[k];
    }
    left -= len;
    if (k % 2 == 0) cur.push_back(q);
  }
  if (k % 2 == 0 && cur.size() >= 2) out.push_back(std::move(cur));
  return out;
}

std::string drawing_format(const std::string& path) {
  const auto slash = path.find_last_of('/');
  const auto dot = path.find_last_of('.');
  if (path == "-" || dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "svg";
  std::string ext = path.substr(dot + 1);
  for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return ext == "svg" || ext == "dxf" || ext == "pdf" || ext == "eps" || ext == "png" ? ext : "";
}

}  // namespace vismap
