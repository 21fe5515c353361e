#include "arrangements/svg_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace vismap {
namespace {

// Grey level of a face: brighter the more it faces the viewer.
double shade(const Scene& scene, const View& view, int face) {
  const auto& f = scene.faces[face];
  double nx = 0, ny = 0, nz = 0, cx = 0, cy = 0, cz = 0;
  for (std::size_t i = 0; i < f.size(); ++i) {   // Newell's normal
    const Vec3 &p = scene.vertices[f[i]], &q = scene.vertices[f[(i + 1) % f.size()]];
    nx += (p.y - q.y) * (p.z + q.z);
    ny += (p.z - q.z) * (p.x + q.x);
    nz += (p.x - q.x) * (p.y + q.y);
    cx += p.x; cy += p.y; cz += p.z;
  }
  double dx = view.m[2][0], dy = view.m[2][1], dz = view.m[2][2];
  if (view.perspective) {
    double k = static_cast<double>(f.size());
    dx = cx / k - view.eye.x; dy = cy / k - view.eye.y; dz = cz / k - view.eye.z;
  }
  double nn = std::sqrt(nx * nx + ny * ny + nz * nz), dd = std::sqrt(dx * dx + dy * dy + dz * dz);
  double c = (nn > 0 && dd > 0) ? std::abs(nx * dx + ny * dy + nz * dz) / (nn * dd) : 0;
  return 0.3 + 0.65 * c;
}

// The page: the map's extent scaled to opt.size, with a margin; y up on the screen.
struct Frame {
  double x0 = 0, y0 = 0, k = 1, margin = 0, w = 0, h = 0;
  explicit Frame(const VisibilityMap& map, const SvgOptions& opt) {
    double xa = HUGE_VAL, ya = HUGE_VAL, xb = -HUGE_VAL, yb = -HUGE_VAL;
    auto grow = [&](const Point2& p) {
      double x = p.x.get_d(), y = p.y.get_d();
      xa = std::min(xa, x); xb = std::max(xb, x);
      ya = std::min(ya, y); yb = std::max(yb, y);
    };
    for (const auto& p : map.vertices) grow(p);   // (every vertex is on an outer ring or a segment)
    for (const auto& h : map.hidden) { grow(h.from); grow(h.to); }   // (may lie outside them)
    if (xa > xb) { xa = ya = 0; xb = yb = 1; }
    const double extent = std::max({xb - xa, yb - ya, 1e-300});
    x0 = xa;
    y0 = ya;
    margin = 0.03 * opt.size;
    k = (opt.size - 2 * margin) / extent;
    w = (xb - xa) * k + 2 * margin;
    h = (yb - ya) * k + 2 * margin;
  }
  std::string xy(const Point2& p) const {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.3f %.3f", margin + (p.x.get_d() - x0) * k, h - margin - (p.y.get_d() - y0) * k);
    return buf;
  }
  std::string header() const {
    char buf[160];
    std::snprintf(buf, sizeof buf,
                  "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" viewBox=\"0 0 %.3f %.3f\">\n",
                  std::ceil(w), std::ceil(h), w, h);
    return std::string(buf) + "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  }
};

// The fill of a face's regions (and of its painter's fragments).
std::string fill_of(const Scene& scene, const View& view, int face) {
  int g = static_cast<int>(std::lround(255 * shade(scene, view, face)));
  char buf[48];
  std::snprintf(buf, sizeof buf, "rgb(%d,%d,%d)", g, g, std::min(255, g + 12));
  return buf;
}

}  // namespace

std::string to_svg(const VisibilityMap& map, const Scene& scene, const View& view, const SvgOptions& opt) {
  const Frame frame(map, opt);
  std::string out = frame.header();
  if (!opt.lines_only) {
    out += "<g stroke=\"none\" fill-rule=\"evenodd\">\n";
    for (const auto& r : map.regions) {
      out += "<path fill=\"" + fill_of(scene, view, r.face) + "\" d=\"";
      auto ring = [&](const Ring& r) {
        for (std::size_t i = 0; i < r.size(); ++i) out += (i ? " L" : "M") + frame.xy(map.at(r[i]));
        out += " Z";
      };
      ring(r.outer);
      for (const auto& hole : r.holes) { out += ' '; ring(hole); }
      out += "\"/>\n";
    }
    out += "</g>\n";
  }
  char buf[200];
  const double width = std::max(0.5, opt.size / 1000);
  if (!map.hidden.empty()) {   // under the visible lines: thin, dashed
    std::snprintf(buf, sizeof buf,
                  "<g stroke=\"black\" stroke-width=\"%.3f\" stroke-dasharray=\"%.3f %.3f\" fill=\"none\">\n",
                  width / 2, 4 * width, 2 * width);
    out += buf;
    for (const auto& h : map.hidden) out += "<path d=\"M" + frame.xy(h.from) + " L" + frame.xy(h.to) + "\"/>\n";
    out += "</g>\n";
  }
  std::snprintf(buf, sizeof buf, "<g stroke=\"black\" stroke-width=\"%.3f\" stroke-linecap=\"round\" fill=\"none\">\n",
                width);
  out += buf;
  for (const auto& s : map.segments)
    out += "<path d=\"M" + frame.xy(map.at(s.from)) + " L" + frame.xy(map.at(s.to)) + "\"/>\n";
  out += "</g>\n</svg>\n";
  return out;
}

std::string to_painter_svg(const std::vector<PaintedFragment>& fragments, const VisibilityMap& map,
                           const Scene& scene, const View& view, const SvgOptions& opt) {
  const Frame frame(map, opt);
  std::string out = frame.header();
  out += "<g stroke=\"none\">\n";
  for (const PaintedFragment& f : fragments) {   // in drawing order: later ones paint over
    out += "<path fill=\"" + fill_of(scene, view, f.face) + "\" d=\"";
    for (std::size_t i = 0; i < f.polygon.size(); ++i) out += (i ? " L" : "M") + frame.xy(f.polygon[i]);
    out += " Z\"/>\n";
  }
  out += "</g>\n</svg>\n";
  return out;
}

}  // namespace vismap
