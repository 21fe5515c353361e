#include "arrangements/sheet.h"

#include <algorithm>
#include <cmath>
#include <cctype>

#include "arrangements/rational.h"

namespace vismap {
namespace {

struct Extent {
  double xa = HUGE_VAL, ya = HUGE_VAL, xb = -HUGE_VAL, yb = -HUGE_VAL;
  void grow(const Point2& p) {
    const double x = p.x.get_d(), y = p.y.get_d();
    xa = std::min(xa, x), xb = std::max(xb, x), ya = std::min(ya, y), yb = std::max(yb, y);
  }
};

Extent extent_of(const VisibilityMap& map) {
  Extent e;
  for (const Point2& p : map.vertices) e.grow(p);
  for (const HiddenSegment& h : map.hidden) { e.grow(h.from); e.grow(h.to); }
  if (e.xa > e.xb) e = Extent{0, 0, 1, 1};
  return e;
}

std::string num(double v) { return fixed_text(v, 3); }

// Each column's and row's origin (the least x, y of its views) and size (the
// largest extent past it), in screen units.
struct Grid {
  std::vector<double> x0, w, y0, h;
};

Grid grid_of(const std::vector<SheetView>& views, const std::vector<Extent>& ext) {
  Grid g;
  int cols = 0, rows = 0;
  for (const SheetView& v : views) cols = std::max(cols, v.col + 1), rows = std::max(rows, v.row + 1);
  g.x0.assign(cols, HUGE_VAL), g.w.assign(cols, 0), g.y0.assign(rows, HUGE_VAL), g.h.assign(rows, 0);
  for (std::size_t i = 0; i < views.size(); ++i) {
    g.x0[views[i].col] = std::min(g.x0[views[i].col], ext[i].xa);
    g.y0[views[i].row] = std::min(g.y0[views[i].row], ext[i].ya);
  }
  for (std::size_t i = 0; i < views.size(); ++i) {
    g.w[views[i].col] = std::max(g.w[views[i].col], ext[i].xb - g.x0[views[i].col]);
    g.h[views[i].row] = std::max(g.h[views[i].row], ext[i].yb - g.y0[views[i].row]);
  }
  return g;
}

}  // namespace

SheetLayout sheet_layout(const std::vector<SheetView>& views, const SvgOptions& opt, const std::string& note) {
  std::vector<Extent> ext;
  for (const SheetView& v : views) ext.push_back(extent_of(*v.map));
  const Grid g = grid_of(views, ext);
  double sum_w = 0, sum_h = 0;
  for (double w : g.w) sum_w += w;
  for (double h : g.h) sum_h += h;
  sum_w = std::max(sum_w, 1e-300), sum_h = std::max(sum_h, 1e-300);
  // The page, its units (mm on paper, px on a canvas), the gap between cells and
  // the room a label takes under each row.
  SheetLayout out;
  Placement& page = out.page;
  page.mm = opt.page.width > 0;
  const double unit = page.mm ? 1 : 96 / 25.4;   // page units per mm
  const double margin = page.mm ? opt.page.margin : 0.03 * opt.page.size, gap = 12 * unit, label = 8 * unit;
  const double gaps_w = gap * static_cast<double>(g.w.size() - 1), gaps_h = (gap + label) * static_cast<double>(g.h.size());
  double k = opt.page.scale;
  if (page.mm) {
    page.width = opt.page.width, page.height = opt.page.height;
    if (opt.page.named && (sum_w > sum_h) != (page.width > page.height)) std::swap(page.width, page.height);
    if (k <= 0)
      k = std::min(std::max(page.width - 2 * margin - gaps_w, 1e-9) / sum_w,
                   std::max(page.height - 2 * margin - gaps_h, 1e-9) / sum_h);
  } else {
    k = (opt.page.size - 2 * margin - std::max(gaps_w, gaps_h)) / std::max(sum_w, sum_h);
    page.width = sum_w * k + gaps_w + 2 * margin, page.height = sum_h * k + gaps_h + 2 * margin;
  }
  // The block of cells, centred on the page; row 0 at the top.
  const double left0 = (page.width - sum_w * k - gaps_w) / 2, top0 = (page.height - sum_h * k - gaps_h) / 2;
  std::vector<double> left(g.w.size()), bottom(g.h.size());
  double x = left0;
  for (std::size_t c = 0; c < g.w.size(); ++c) left[c] = x, x += g.w[c] * k + gap;
  double y = top0;   // from the top, down
  for (std::size_t r = 0; r < g.h.size(); ++r) y += g.h[r] * k, bottom[r] = page.height - y, y += label + gap;

  const double text = 3.5 * unit;
  for (const SheetView& v : views) {
    Drawing d = make_drawing(*v.map, opt.page, opt.provenance, opt.optimize_travel);
    d.at = page;
    d.at.k = k;
    d.at.x0 = g.x0[v.col], d.at.y0 = g.y0[v.row];
    d.at.left = left[v.col], d.at.bottom = bottom[v.row];
    out.drawings.push_back(std::move(d));
    std::string id;
    for (char c : v.label) id += static_cast<char>(c == ' ' ? '-' : std::tolower(static_cast<unsigned char>(c)));
    out.ids.push_back(id);
    out.texts.push_back({left[v.col] + g.w[v.col] * k / 2, page.height - bottom[v.row] + label * 0.75, text, false, v.label});
  }
  if (!note.empty()) out.texts.push_back({page.width - margin, page.height - margin / 2, text * 0.8, true, note});
  return out;
}

std::string to_sheet_svg(const std::vector<SheetView>& views, const Scene& scene, const SvgOptions& opt,
                         const std::string& note) {
  const SheetLayout layout = sheet_layout(views, opt, note);
  auto text = [](const SheetText& t) {
    return "<text x=\"" + num(t.x) + "\" y=\"" + num(t.y) + "\" font-family=\"sans-serif\" font-size=\"" + num(t.size) +
           "\" text-anchor=\"" + (t.end ? "end" : "middle") + "\">" + t.text + "</text>\n";
  };
  std::string out = svg_header(layout.page);
  for (std::size_t i = 0; i < views.size(); ++i) {
    const SheetView& v = views[i];
    out += "<g id=\"" + layout.ids[i] + "\">\n" +
           svg_layers(*v.map, layout.drawings[i], scene, *v.view, opt, layout.ids[i] + "-");
    out += text(layout.texts[i]) + "</g>\n";
  }
  for (std::size_t i = views.size(); i < layout.texts.size(); ++i) out += text(layout.texts[i]);
  return out + "</svg>\n";
}

}  // namespace vismap
