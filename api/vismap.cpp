// The library's entry points (include/vismap/vismap.h): compute a map, read it,
// write it. Everything here is a thin layer over the engine and the writers.
#include <cctype>
#include <stdexcept>
#include <string>
#include <utility>

#include "api/map_impl.h"
#include "arrangements/atomic_file.h"
#include "arrangements/cairo_writer.h"
#include "arrangements/drawing.h"
#include "arrangements/dxf_writer.h"
#include "arrangements/json_writer.h"
#include "arrangements/rational.h"
#include "arrangements/svg_writer.h"
#include "engine/threads.h"
#include "engine/visibility.h"

namespace vismap {
namespace {

Point nearest(const Point2& p) { return {nearest_double(p.x), nearest_double(p.y)}; }
ExactPoint exact_text(const Point2& p) { return {canonical(p.x), canonical(p.y)}; }

// The drawing's options as the writers take them; each refusal says which
// option and what it expects.
SvgOptions svg_options(const DrawingOptions& d) {
  SvgOptions svg;
  if (!preset_style(d.style, svg.style))
    throw std::invalid_argument("the drawing style is shaded, technical or plotter, got '" + d.style + "'");
  for (const std::string& spec : d.lines) {
    std::string error;
    if (!override_line_style(spec, svg.style, error))
      throw std::invalid_argument("line style " + error + ", got '" + spec + "'");
  }
  if (!d.page.empty() && !parse_page(d.page, svg.page))
    throw std::invalid_argument("the page is a4, a3, letter or WxHmm (e.g. 300x200mm), got '" + d.page + "'");
  if (!d.scale.empty() && !parse_scale(d.scale, svg.page.scale))
    throw std::invalid_argument("the scale is 1:N with N > 0, got '" + d.scale + "'");
  if (svg.page.scale > 0 && svg.page.width == 0)
    throw std::invalid_argument("a scale needs a page (the drawing's size on paper)");
  if (!(d.margin >= 0)) throw std::invalid_argument("the page margin must be 0 or more (mm)");
  svg.page.margin = d.margin;
  svg.lines_only = d.lines_only;
  svg.optimize_travel = d.optimize_travel;
  svg.provenance = d.svg_data;
  Shading shading;
  if (!d.shading.empty() && !parse_shading(d.shading, shading))
    throw std::invalid_argument("the shading is R,N,B or R,N,B,S,M (non-negative numbers), got '" + d.shading + "'");
  if (d.light) {
    if (d.light->x == 0 && d.light->y == 0 && d.light->z == 0)
      throw std::invalid_argument("the direction towards the light must not be 0,0,0");
    shading.light_given = true;
    shading.light[0] = d.light->x;
    shading.light[1] = d.light->y;
    shading.light[2] = d.light->z;
  }
  svg.style.shading = shading;
  return svg;
}

}  // namespace

Map compute(Scene scene, const Camera& camera, const Options& options) {
  auto impl = std::make_shared<Map::Impl>();
  impl->view = make_view(camera, scene);
  impl->map = compute_map(scene, impl->view, options);
  impl->map.stats.seconds.clear();   // the command line's JSON without --stats
  impl->threads = engine::thread_count(options.threads, scene.faces.size());
  impl->vertices.reserve(impl->map.vertices.size());
  for (const Point2& p : impl->map.vertices) impl->vertices.push_back(nearest(p));
  for (const HiddenSegment& h : impl->map.hidden)
    impl->hidden.push_back({nearest(h.from), nearest(h.to), h.kind, h.faces});
  impl->scene = std::move(scene);
  return Map(std::move(impl));
}

Map::Map(std::shared_ptr<const Impl> impl) : impl_(std::move(impl)) {}

const std::vector<Point>& Map::vertices() const { return impl_->vertices; }
ExactPoint Map::exact(std::uint32_t vertex) const { return exact_text(impl_->map.vertices.at(vertex)); }
bool Map::has_regions() const { return impl_->map.has_regions; }
const std::vector<Region>& Map::regions() const { return impl_->map.regions; }
const std::vector<Segment>& Map::segments() const { return impl_->map.segments; }
bool Map::has_hidden() const { return impl_->map.has_hidden; }
const std::vector<HiddenLine>& Map::hidden() const { return impl_->hidden; }
std::array<ExactPoint, 2> Map::exact_hidden(std::size_t i) const {
  const HiddenSegment& h = impl_->map.hidden.at(i);
  return {exact_text(h.from), exact_text(h.to)};
}
bool Map::perspective() const { return impl_->map.perspective; }
std::size_t Map::scene_faces() const { return impl_->map.scene_faces; }

std::string Map::to_json() const { return vismap::to_json(impl_->map, impl_->threads); }

std::string Map::drawing(const DrawingOptions& options, const std::string& format) const {
  const SvgOptions svg = svg_options(options);
  if (format != "svg" && format != "dxf" && format != "pdf" && format != "eps" && format != "png")
    throw std::invalid_argument("a drawing is svg, dxf, pdf, eps or png, got '" + format + "'");
  if (format != "svg" && format != "dxf" && !cairo_available())
    throw std::invalid_argument("this build has no cairo: " + format + " drawings are not written (svg and dxf are)");
  const Drawing drawing = make_drawing(impl_->map, svg.page, svg.provenance, svg.optimize_travel);
  if (format == "svg") return to_svg(impl_->map, drawing, impl_->scene, impl_->view, svg);
  if (format == "dxf") return to_dxf(drawing);
  return to_cairo(impl_->map, drawing, impl_->scene, impl_->view, svg, format);
}

void Map::write(const std::string& path, const DrawingOptions& options) const {
  const auto dot = path.find_last_of('.');
  std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
  for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  if (ext == "json") {
    write_outputs_atomically({{path, [&](const auto& sink) { write_json(impl_->map, sink, impl_->threads); }}});
    return;
  }
  const std::string format = drawing_format(path);
  if (format.empty())
    throw std::invalid_argument(path + ": a map is written as .json, .svg, .dxf, .pdf, .eps or .png");
  write_file_atomically(path, drawing(options, format));
}

}  // namespace vismap
