#include "arrangements/svg_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "arrangements/rational.h"

namespace vismap {
namespace {

std::string num(double v) { return fixed_text(v, 3); }

std::string xy(const std::array<double, 2>& p) { return num(p[0]) + " " + num(p[1]); }
std::string xy(const Placement& at, const Point2& p) { return xy(at.at(p.x.get_d(), p.y.get_d())); }

}  // namespace

std::string svg_header(const Placement& at) {
  const std::string unit = at.mm ? "mm" : "";
  const std::string w = at.mm ? num(at.width) : num(std::ceil(at.width)), h = at.mm ? num(at.height) : num(std::ceil(at.height));
  return "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:inkscape=\"http://www.inkscape.org/namespaces/inkscape\" "
         "width=\"" + w + unit + "\" height=\"" + h + unit + "\" viewBox=\"0 0 " + num(at.width) + " " + num(at.height) +
         "\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
}

namespace {

std::string layer(const std::string& id, const std::string& label, const std::string& attributes) {
  return "<g inkscape:groupmode=\"layer\" id=\"" + id + "\" inkscape:label=\"" + label + "\" " + attributes + ">\n";
}

// The fill of a face's regions (and of its painter's fragments).
std::string fill_of(const Scene& scene, const View& view, int face, const Shading& shading) {
  const std::array<int, 3> c = face_rgb(scene, view, face, shading);
  char buf[48];
  std::snprintf(buf, sizeof buf, "rgb(%d,%d,%d)", c[0], c[1], c[2]);
  return buf;
}

}  // namespace

namespace {

std::string regions_layer(const VisibilityMap& map, const Placement& at, const Scene& scene, const View& view,
                          const Shading& shading, const std::string& id_prefix) {
  std::string out = layer(id_prefix + "vismap-regions", "regions", "stroke=\"none\" fill-rule=\"evenodd\"");
  for (const auto& r : map.regions) {
    out += "<path fill=\"" + fill_of(scene, view, r.face, shading) + "\" d=\"";
    auto ring = [&](const Ring& r) {
      for (std::size_t i = 0; i < r.size(); ++i) out += (i ? " L" : "M") + xy(at, map.at(r[i]));
      out += " Z";
    };
    ring(r.outer);
    for (const auto& hole : r.holes) { out += ' '; ring(hole); }
    out += "\"/>\n";
  }
  return out + "</g>\n";
}

// A chain's path data: one polyline, or its dashes as sub-paths.
std::string path_data(const Chain& c, const LineStyle& ls, const Placement& at, bool cut) {
  std::string d;
  const std::vector<std::array<double, 2>> points = page_points(c, at);
  if (cut && !ls.dash.empty()) {
    std::vector<double> dash;
    for (double v : ls.dash) dash.push_back(v * at.per_mm());
    for (const auto& piece : dashed(points, c.closed, dash))
      for (std::size_t i = 0; i < piece.size(); ++i) d += (d.empty() ? "M" : i ? " L" : " M") + xy(piece[i]);
    return d;
  }
  for (std::size_t i = 0; i < points.size(); ++i) d += (i ? " L" : "M") + xy(points[i]);
  if (c.closed) d += " Z";
  return d;
}

std::string stroke(const LineStyle& ls, const Placement& at, bool cut) {
  std::string s = "stroke=\"" + ls.color + "\" stroke-width=\"" + num(ls.width * at.per_mm()) +
                  "\" stroke-linecap=\"round\" stroke-linejoin=\"round\" fill=\"none\"";
  if (!ls.dash.empty() && !cut) {
    s += " stroke-dasharray=\"";
    for (std::size_t i = 0; i < ls.dash.size(); ++i) s += (i ? " " : "") + num(ls.dash[i] * at.per_mm());
    s += "\"";
  }
  return s;
}

std::string faces_text(const std::vector<int>& faces) {
  std::string s;
  for (std::size_t i = 0; i < faces.size(); ++i) s += (i ? " " : "") + std::to_string(faces[i]);
  return s;
}

}  // namespace

std::string to_svg(const VisibilityMap& map, const Scene& scene, const View& view, const SvgOptions& opt) {
  return to_svg(map, make_drawing(map, opt.page, opt.provenance, opt.optimize_travel), scene, view, opt);
}

std::string to_svg(const VisibilityMap& map, const Drawing& drawing, const Scene& scene, const View& view,
                   const SvgOptions& opt) {
  return svg_header(drawing.at) + svg_layers(map, drawing, scene, view, opt, "") + "</svg>\n";
}

std::string svg_layers(const VisibilityMap& map, const Drawing& drawing, const Scene& scene, const View& view,
                       const SvgOptions& opt, const std::string& id_prefix) {
  const Placement& at = drawing.at;
  std::string out;
  if (opt.style.fills && !opt.lines_only) out += regions_layer(map, at, scene, view, opt.style.shading, id_prefix);
  // One layer per class that has lines, in drawing order (hidden first, under the rest).
  for (std::size_t k = 0; k < kLineClasses; ++k) {
    const auto cls = static_cast<LineClass>(k);
    const LineStyle& ls = opt.style.line[k];
    bool any = false;
    for (const Chain& c : drawing.chains) {
      if (c.cls != cls) continue;
      if (!any) out += layer(id_prefix + "vismap-" + class_name(cls), class_name(cls), stroke(ls, at, opt.style.cut_dashes));
      any = true;
      out += "<path d=\"" + path_data(c, ls, at, opt.style.cut_dashes) + "\"";
      if (opt.provenance) out += std::string(" data-kind=\"") + to_string(c.kind) + "\" data-faces=\"" + faces_text(c.faces) + "\"";
      out += "/>\n";
    }
    if (any) out += "</g>\n";
  }
  return out;
}

std::string to_painter_svg(const std::vector<PaintedFragment>& fragments, const VisibilityMap& map,
                           const Scene& scene, const View& view, const SvgOptions& opt) {
  const Placement at = place(map, opt.page);
  std::string out = svg_header(at);
  out += "<g stroke=\"none\">\n";
  for (const PaintedFragment& f : fragments) {   // in drawing order: later ones paint over
    out += "<path fill=\"" + fill_of(scene, view, f.face, opt.style.shading) + "\" d=\"";
    for (std::size_t i = 0; i < f.polygon.size(); ++i) out += (i ? " L" : "M") + xy(at, f.polygon[i]);
    out += " Z\"/>\n";
  }
  out += "</g>\n</svg>\n";
  return out;
}

}  // namespace vismap
