#include "arrangements/cairo_writer.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#ifdef VISMAP_HAVE_CAIRO
#include <cairo-pdf.h>
#include <cairo-ps.h>
#include <cairo.h>
#endif

namespace vismap {

#ifndef VISMAP_HAVE_CAIRO
bool cairo_available() { return false; }
std::string to_cairo(const VisibilityMap&, const Drawing&, const Scene&, const View&, const SvgOptions&,
                     const std::string& format) {
  throw std::runtime_error("this build has no cairo: " + format + " cannot be written (install libcairo2-dev and rebuild)");
}
std::string to_sheet_cairo(const std::vector<SheetView>&, const Scene&, const SvgOptions&, const std::string&,
                           const std::string& format) {
  throw std::runtime_error("this build has no cairo: " + format + " cannot be written (install libcairo2-dev and rebuild)");
}
#else
bool cairo_available() { return true; }

namespace {

cairo_status_t append(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

// CSS-like colour names and #rrggbb, as the styles use them; black otherwise.
void set_colour(cairo_t* cr, const std::string& c) {
  static const std::pair<const char*, std::array<double, 3>> kNamed[] = {
      {"black", {0, 0, 0}}, {"white", {1, 1, 1}}, {"red", {1, 0, 0}}, {"green", {0, 0.5, 0}},
      {"blue", {0, 0, 1}},  {"gray", {0.5, 0.5, 0.5}}, {"grey", {0.5, 0.5, 0.5}}};
  for (const auto& [name, rgb] : kNamed)
    if (c == name) return cairo_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
  unsigned v = 0;
  if (c.size() == 7 && c[0] == '#' && std::sscanf(c.c_str() + 1, "%6x", &v) == 1)
    return cairo_set_source_rgb(cr, ((v >> 16) & 255) / 255.0, ((v >> 8) & 255) / 255.0, (v & 255) / 255.0);
  cairo_set_source_rgb(cr, 0, 0, 0);
}

void regions(cairo_t* cr, const VisibilityMap& map, const Placement& at, const Scene& scene, const View& view,
             const Shading& shading) {
  cairo_set_fill_rule(cr, CAIRO_FILL_RULE_EVEN_ODD);
  for (const Region& r : map.regions) {
    auto ring = [&](const Ring& ring) {
      for (std::size_t i = 0; i < ring.size(); ++i) {
        const auto p = at.at(map.at(ring[i]).x.get_d(), map.at(ring[i]).y.get_d());
        (i ? cairo_line_to : cairo_move_to)(cr, p[0], p[1]);
      }
      cairo_close_path(cr);
    };
    ring(r.outer);
    for (const Ring& h : r.holes) ring(h);
    const std::array<int, 3> c = face_rgb(scene, view, r.face, shading);
    cairo_set_source_rgb(cr, c[0] / 255.0, c[1] / 255.0, c[2] / 255.0);
    cairo_fill(cr);
  }
}

void chains(cairo_t* cr, const Drawing& d, const DrawingStyle& style) {
  const Placement& at = d.at;
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  for (const Chain& c : d.chains) {
    const LineStyle& ls = style.line[static_cast<std::size_t>(c.cls)];
    set_colour(cr, ls.color);
    cairo_set_line_width(cr, ls.width * at.per_mm());
    std::vector<double> dash;
    for (double v : ls.dash) dash.push_back(v * at.per_mm());
    const bool cut = style.cut_dashes && !dash.empty();
    cairo_set_dash(cr, dash.data(), cut ? 0 : static_cast<int>(dash.size()), 0);
    const std::vector<std::array<double, 2>> points = page_points(c, at);
    if (cut) {
      for (const auto& piece : dashed(points, c.closed, dash))
        for (std::size_t i = 0; i < piece.size(); ++i) (i ? cairo_line_to : cairo_move_to)(cr, piece[i][0], piece[i][1]);
    } else {
      for (std::size_t i = 0; i < points.size(); ++i) (i ? cairo_line_to : cairo_move_to)(cr, points[i][0], points[i][1]);
      if (c.closed) cairo_close_path(cr);
    }
    cairo_stroke(cr);
  }
}

// A page of the placement's size on a surface for `format`, drawn by `draw`
// (page units), written out.
template <class Draw>
std::string render(const Placement& at, const std::string& format, Draw&& draw) {
  // Page units to the surface's: points (PDF, EPS) or pixels (PNG), 96 px per inch.
  const double inch = at.mm ? 25.4 : 96;
  const double k = (format == "png" ? 96 : 72) / inch;
  const double w = at.width * k, h = at.height * k;
  std::string out;
  cairo_surface_t* surface = nullptr;
  if (format == "pdf") surface = cairo_pdf_surface_create_for_stream(append, &out, w, h);
  else if (format == "eps") {
    surface = cairo_ps_surface_create_for_stream(append, &out, w, h);
    cairo_ps_surface_set_eps(surface, 1);
  } else if (format == "png") {
    surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, static_cast<int>(std::ceil(w)), static_cast<int>(std::ceil(h)));
  } else {
    throw std::runtime_error("cairo cannot write '" + format + "'");
  }
  cairo_t* cr = cairo_create(surface);
  cairo_scale(cr, k, k);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  draw(cr);
  cairo_destroy(cr);
  cairo_surface_flush(surface);
  if (format == "png") cairo_surface_write_to_png_stream(surface, append, &out);
  cairo_surface_finish(surface);
  const cairo_status_t status = cairo_surface_status(surface);
  cairo_surface_destroy(surface);
  if (status != CAIRO_STATUS_SUCCESS) throw std::runtime_error(std::string("cairo: ") + cairo_status_to_string(status));
  return out;
}

void text(cairo_t* cr, const SheetText& t) {
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, t.size);
  cairo_text_extents_t e;
  cairo_text_extents(cr, t.text.c_str(), &e);
  cairo_move_to(cr, t.x - (t.end ? e.x_advance : e.x_advance / 2), t.y);
  cairo_show_text(cr, t.text.c_str());
}

}  // namespace

std::string to_cairo(const VisibilityMap& map, const Drawing& d, const Scene& scene, const View& view,
                     const SvgOptions& opt, const std::string& format) {
  return render(d.at, format, [&](cairo_t* cr) {
    if (opt.style.fills && !opt.lines_only) regions(cr, map, d.at, scene, view, opt.style.shading);
    chains(cr, d, opt.style);
  });
}

std::string to_sheet_cairo(const std::vector<SheetView>& views, const Scene& scene, const SvgOptions& opt,
                           const std::string& note, const std::string& format) {
  const SheetLayout layout = sheet_layout(views, opt, note);
  return render(layout.page, format, [&](cairo_t* cr) {
    for (std::size_t i = 0; i < views.size(); ++i) {
      const Drawing& d = layout.drawings[i];
      if (opt.style.fills && !opt.lines_only) regions(cr, *views[i].map, d.at, scene, *views[i].view, opt.style.shading);
      chains(cr, d, opt.style);
    }
    for (const SheetText& t : layout.texts) text(cr, t);
  });
}
#endif

}  // namespace vismap
