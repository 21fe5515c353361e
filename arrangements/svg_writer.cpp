#include "arrangements/svg_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

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

}  // namespace

std::string to_svg(const VisibilityMap& map, const Scene& scene, const View& view, const SvgOptions& opt) {
  double x0 = HUGE_VAL, y0 = HUGE_VAL, x1 = -HUGE_VAL, y1 = -HUGE_VAL;
  auto grow = [&](const Point2& p) {
    double x = p.x.get_d(), y = p.y.get_d();
    x0 = std::min(x0, x); x1 = std::max(x1, x);
    y0 = std::min(y0, y); y1 = std::max(y1, y);
  };
  for (const auto& r : map.regions) for (const auto& p : r.outer) grow(p);
  for (const auto& s : map.segments) { grow(s.from); grow(s.to); }
  if (x0 > x1) { x0 = y0 = 0; x1 = y1 = 1; }
  const double extent = std::max({x1 - x0, y1 - y0, 1e-300});
  const double margin = 0.03 * opt.size, k = (opt.size - 2 * margin) / extent;
  const double w = (x1 - x0) * k + 2 * margin, h = (y1 - y0) * k + 2 * margin;
  char buf[128];
  auto xy = [&](const Point2& p) {
    std::snprintf(buf, sizeof buf, "%.3f %.3f", margin + (p.x.get_d() - x0) * k, h - margin - (p.y.get_d() - y0) * k);
    return std::string(buf);
  };
  std::string out;
  std::snprintf(buf, sizeof buf,
                "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" viewBox=\"0 0 %.3f %.3f\">\n",
                std::ceil(w), std::ceil(h), w, h);
  out += buf;
  out += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  if (!opt.lines_only) {
    out += "<g stroke=\"none\" fill-rule=\"evenodd\">\n";
    for (const auto& r : map.regions) {
      int g = static_cast<int>(std::lround(255 * shade(scene, view, r.face)));
      std::snprintf(buf, sizeof buf, "<path fill=\"rgb(%d,%d,%d)\" d=\"", g, g, std::min(255, g + 12));
      out += buf;
      auto ring = [&](const std::vector<Point2>& pts) {
        for (std::size_t i = 0; i < pts.size(); ++i) out += (i ? " L" : "M") + xy(pts[i]);
        out += " Z";
      };
      ring(r.outer);
      for (const auto& hole : r.holes) { out += ' '; ring(hole); }
      out += "\"/>\n";
    }
    out += "</g>\n";
  }
  std::snprintf(buf, sizeof buf, "<g stroke=\"black\" stroke-width=\"%.3f\" stroke-linecap=\"round\" fill=\"none\">\n",
                std::max(0.5, opt.size / 1000));
  out += buf;
  for (const auto& s : map.segments) out += "<path d=\"M" + xy(s.from) + " L" + xy(s.to) + "\"/>\n";
  out += "</g>\n</svg>\n";
  return out;
}

}  // namespace vismap
