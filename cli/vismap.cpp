// vismap: exact visibility maps from mesh files.
//   read scene -> camera -> engine -> JSON / SVG, each output written whole or not at all.
#include <CGAL/version.h>
#include <gmp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <new>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "arrangements/atomic_file.h"
#include "arrangements/cairo_writer.h"
#include "arrangements/dxf_writer.h"
#include "arrangements/json_writer.h"
#include "arrangements/sheet.h"
#include "arrangements/svg_writer.h"
#include "cli/camera_options.h"
#include "cli/views.h"
#include "engine/camera.h"
#include "engine/scene.h"
#include "engine/threads.h"
#include "engine/visibility.h"
#include "verify/verify_cli.h"

namespace {

const char* kHelp = R"(usage: vismap SCENE [options]
       vismap verify SCENE MAP.json [options]   (see 'vismap verify --help')

Computes the exact visibility map of a polygon scene (OFF, OBJ, STL, PLY, or a
.vmscene.json, whose faces may have holes) and writes it as exact JSON and/or a
drawing (SVG, DXF, PDF, EPS, PNG). SCENE "-" is standard input.

outputs (files are written whole or not at all; "-" is standard output):
  -o, --svg FILE       the drawing, by FILE's extension: .svg (the default;
                       regions shaded, lines stroked), .dxf (CAD), .pdf, .eps,
                       .png (through cairo)
  --lines-only         SVG without filled regions (a hidden-line drawing)
  --style S            shaded (default: regions filled), technical (ISO 128:
                       visible 0.5 mm, hidden 0.25 mm dashed, no fills) or
                       plotter (a colour per layer, dashes cut into sub-paths)
  --line CLASS:SPEC    restyle one class (hidden, smooth, intersection, crease,
                       outline): SPEC is width=MM,color=C,dash=ON/OFF or dash=none
  --page P             a4, a3, letter or WxHmm: the SVG in mm at true size
  --scale 1:N          paper mm per screen unit 1/N (default: fit the page)
  --margin MM          page margin when fitting (default 10)
  --optimize-travel    order the paths to shorten pen-up travel (reported)
  --svg-data           data-kind and data-faces on every path
  --shading R,N,B[,S,M]
                       fills by Newell's I = R cos^N(a) + B + S sin^M(a), a the
                       angle between a face's normal and the light (default
                       0.65,1,0.3: a flat shade)
  --light X,Y,Z        direction towards the light (default: at the eye)
  --json FILE          the exact map (format: docs/format.md)
  --no-regions         the JSON without its "regions" (only the segments: what a
                       lines-only drawing needs, computed faster)
camera (default: orthographic, the whole scene seen obliquely):
  --dir X,Y,Z          orthographic, looking along this direction
  --eye X,Y,Z          perspective eye point
  --target X,Y,Z       perspective target (default: the scene's centre)
  --fov DEG            perspective vertical field of view (default 40)
  --up X,Y,Z           up direction (default 0,0,1; 0,1,0 when parallel)
  --views SPEC         many views in one run, the scene read once: orbit:N[,E]
                       (N orthographic views around the z axis, E degrees
                       above the horizon, default 30), a file of one camera
                       per line (e.g. '--dir -1,-2,-3' or '--eye 4,3,1.6
                       --target 0,0,1 --fov 60'; '#' comments), or
                       sheet[:first|:third] (front, top, right and isometric
                       views on one page, -o NAME.svg, .pdf, .eps or .png);
                       each other output is named with %d (or %03d), the
                       view's number from 0
lines:
  --crease DEG         dihedral angle making a shared edge a crease (default 30)
  --smooth             also draw smooth edges
  --hidden             also the hidden lines: the JSON's "hidden" list, drawn
                       thin and dashed in the SVG
engine:
  --algorithm A        franklin (default: Franklin's variable grid), newell
                       (Newell, Newell & Sancha's depth sort with plane
                       splitting) or bsp (a BSP tree per group of objects,
                       ordered by Tomlinson's priority, built once per scene,
                       then Newell's overlay; with --views, one forest for
                       all views); all give the same map
  --threads N          threads for reading a large OFF file, Franklin's
                       engine and the JSON, and for --views of a scene under
                       8192 faces side by side (default: every usable core,
                       one for a single view of such a scene); the map is the
                       same for every N
  --grid-c C           Franklin's grid constant c, B = c*min(sqrt(N),1/L) (default 2.5)
  --painter FILE       with --algorithm newell or bsp: SVG of the ordered, split
                       fragments filled back to front (the painter's drawing)
  --stats              print statistics on stderr and add phase timings to the
                       JSON (without it the JSON is byte-for-byte reproducible)
input:
  --format F           off, obj, stl, ply or vmscene: SCENE's format (default:
                       by its extension, .json for a vmscene; for standard
                       input, by its content)
  --max-memory SIZE    refuse, before reading it, a scene that would need more
                       memory than SIZE (e.g. 512M, 8G; default: the physical
                       memory, or a lower cgroup or ulimit -v limit)
  -h, --help           this text
  --version            vismap's version and the exact arithmetic it was built with

exit status: 0 success, 1 bad input or output error, 2 bad usage,
3 internal error; killed by SIGINT/SIGTERM, it leaves no partial output
)";

struct Usage : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The shared parsers' refusals as usage errors.
template <class Parse>
auto as_usage(Parse&& parse) {
  try {
    return parse();
  } catch (const std::invalid_argument& e) {
    throw Usage(e.what());
  }
}
double parse_double(const std::string& opt, const std::string& s) {
  return as_usage([&] { return vismap::cli::parse_number(opt, s); });
}
vismap::Vec3 parse_vec(const std::string& opt, const std::string& s) {
  return as_usage([&] { return vismap::cli::parse_vec3(opt, s); });
}

// The library's messages name no option; where one is the remedy, the command
// line says which on a line of its own.
const char* option_hint(std::string_view message) {
  if (message.find("the memory limit of") != std::string_view::npos) return "(--max-memory sets the limit)\n";
  if (message.find("name the format") != std::string_view::npos || message.find("name it: off") != std::string_view::npos)
    return "(--format names it)\n";
  return "";
}

// vismap's version, and the exact arithmetic behind the maps (a bug report's first line).
void print_version() {
  std::printf("vismap %s (CGAL %s, GMP %s)\n", VISMAP_VERSION, CGAL_VERSION_STR, gmp_version);
}

}  // namespace

int main(int argc, char** argv) {
  vismap::install_output_cleanup_handlers();
  if (argc >= 2 && std::string(argv[1]) == "verify")
    return vismap_check::verify_command(std::vector<std::string>(argv + 2, argv + argc));
  std::string scene_path, svg_path, json_path, painter_path, format;
  vismap::ReadLimits limits;
  limits.max_memory = vismap::default_max_memory();
  bool have_scene = false;
  vismap::Camera cam;
  vismap::Options eng;
  vismap::SvgOptions svg;
  bool stats = false, no_regions = false, style_given = false, shading_given = false;
  vismap::Shading shading;   // --shading, --light: applied over the style
  std::vector<std::string> line_specs;   // --line, applied over the style
  std::string views_spec;                // --views: many cameras, one run
  try {
    std::vector<std::string> args(argv + 1, argv + argc);
    for (std::size_t i = 0; i < args.size(); ++i) {
      const std::string& a = args[i];
      auto value = [&]() -> const std::string& {
        if (i + 1 >= args.size()) throw Usage(a + " needs a value");
        return args[++i];
      };
      if (a == "-h" || a == "--help") { std::fputs(kHelp, stdout); return 0; }
      else if (a == "--version") { print_version(); return 0; }
      else if (a == "-o" || a == "--svg") svg_path = value();
      else if (a == "--painter") painter_path = value();
      else if (a == "--algorithm") {
        const std::string& v = value();
        if (v == "franklin") eng.algorithm = vismap::Algorithm::Franklin;
        else if (v == "newell") eng.algorithm = vismap::Algorithm::Newell;
        else if (v == "bsp") eng.algorithm = vismap::Algorithm::Bsp;
        else throw Usage("--algorithm expects franklin, newell or bsp, got '" + v + "'");
      }
      else if (a == "--json") json_path = value();
      else if (a == "--lines-only") svg.lines_only = true;
      else if (a == "--style") {
        const std::string& v = value();
        if (!vismap::preset_style(v, svg.style)) throw Usage("--style expects shaded, technical or plotter, got '" + v + "'");
        style_given = true;
      } else if (a == "--line") line_specs.push_back(value());
      else if (a == "--page") {
        const std::string& v = value();
        if (!vismap::parse_page(v, svg.page)) throw Usage("--page expects a4, a3, letter or WxHmm (e.g. 300x200mm), got '" + v + "'");
      } else if (a == "--scale") {
        const std::string& v = value();
        if (!vismap::parse_scale(v, svg.page.scale)) throw Usage("--scale expects 1:N with N > 0, got '" + v + "'");
      } else if (a == "--margin") {
        svg.page.margin = parse_double(a, value());
        if (!(svg.page.margin >= 0)) throw Usage("--margin must be 0 or more (mm)");
      } else if (a == "--optimize-travel") svg.optimize_travel = true;
      else if (a == "--svg-data") svg.provenance = true;
      else if (a == "--shading") {
        const std::string& v = value();
        if (!vismap::parse_shading(v, shading)) throw Usage("--shading expects R,N,B or R,N,B,S,M (non-negative numbers), got '" + v + "'");
        shading_given = true;
      } else if (a == "--light") {
        const vismap::Vec3 l = parse_vec(a, value());
        if (l.x == 0 && l.y == 0 && l.z == 0) throw Usage("--light must not be 0,0,0");
        shading.light_given = shading_given = true;
        shading.light[0] = l.x;
        shading.light[1] = l.y;
        shading.light[2] = l.z;
      }
      else if (a == "--no-regions") no_regions = true;
      else if (vismap::cli::is_camera_option(a)) {
        const std::string& v = value();
        as_usage([&] { vismap::cli::set_camera_option(cam, a, v); });
      }
      else if (a == "--views") views_spec = value();
      else if (a == "--crease") {
        eng.crease_deg = parse_double(a, value());
        if (eng.crease_deg < 0 || eng.crease_deg > 180) throw Usage("--crease must be between 0 and 180");
      } else if (a == "--grid-c") {
        eng.grid_c = parse_double(a, value());
        if (!(eng.grid_c > 0 && eng.grid_c <= 64)) throw Usage("--grid-c must be in (0, 64]");
      } else if (a == "--threads") {
        const std::string& v = value();
        const double n = parse_double(a, v);
        if (!(n >= 1 && n <= 1024 && n == std::floor(n))) throw Usage("--threads expects a whole number from 1 to 1024, got '" + v + "'");
        eng.threads = static_cast<int>(n);
      } else if (a == "--smooth") eng.smooth = true;
      else if (a == "--hidden") eng.hidden = true;
      else if (a == "--stats") stats = true;
      else if (a == "--format") {
        format = value();
        if (format != "off" && format != "obj" && format != "stl" && format != "ply" && format != "vmscene")
          throw Usage("--format expects off, obj, stl, ply or vmscene, got '" + format + "'");
      } else if (a == "--max-memory") {
        const std::string& v = value();
        if (!vismap::parse_memory_size(v, limits.max_memory))
          throw Usage("--max-memory expects a size such as 512M or 8G, got '" + v + "'");
      }
      else if (a.size() > 1 && a[0] == '-') throw Usage("unknown option " + a);
      else if (!have_scene) { scene_path = a; have_scene = true; }
      else throw Usage("more than one scene given: " + scene_path + ", " + a);
    }
    if (scene_path.empty()) throw Usage("no scene file given");
    for (const std::string& spec : line_specs) {
      std::string error;
      if (!vismap::override_line_style(spec, svg.style, error)) throw Usage("--line " + error + ", got '" + spec + "'");
    }
    svg.style.shading = shading;
    const bool drawing_options = style_given || !line_specs.empty() || svg.page.width > 0 || svg.page.scale > 0 ||
                                 svg.optimize_travel || svg.provenance || shading_given;
    if (drawing_options && svg_path.empty())
      throw Usage("--style, --line, --page, --scale, --optimize-travel, --svg-data, --shading and --light apply to -o, which is not given");
    if (svg.page.scale > 0 && svg.page.width == 0) throw Usage("--scale needs --page (the drawing's size on paper)");
    if (!svg_path.empty() && vismap::drawing_format(svg_path).empty())
      throw Usage("-o " + svg_path + ": the drawing is written as .svg, .dxf, .pdf, .eps or .png");
    const std::string fmt = svg_path.empty() ? "" : vismap::drawing_format(svg_path);
    if ((fmt == "pdf" || fmt == "eps" || fmt == "png") && !vismap::cairo_available())
      throw Usage("-o " + svg_path + ": this build has no cairo (install libcairo2-dev and rebuild); use .svg or .dxf");
    if (no_regions && json_path.empty()) throw Usage("--no-regions applies to --json, which is not given");
    if (!svg_path.empty() && svg_path == json_path) throw Usage("--json and -o name the same file");
    if (!painter_path.empty() && eng.algorithm == vismap::Algorithm::Franklin)
      throw Usage("--painter needs --algorithm newell or bsp (the fragments are theirs)");
    if (!painter_path.empty() && (painter_path == json_path || painter_path == svg_path))
      throw Usage("--painter names the same file as another output");
    if (!views_spec.empty()) {
      if (cam.dir || cam.eye || cam.target || cam.fov_deg || cam.up)
        throw Usage("--views gives the cameras: --dir, --eye, --target, --fov and --up go in its file");
      if (json_path.empty() && svg_path.empty() && painter_path.empty())
        throw Usage("--views needs an output (--json, -o or --painter, each named with %d)");
      const bool sheet = !vismap::cli::sheet_note(views_spec).empty();
      if (sheet && !svg_path.empty() && vismap::drawing_format(svg_path) == "dxf")
        throw Usage("--views sheet draws one page as .svg, .pdf, .eps or .png, got '" + svg_path + "'");
      for (const std::string* out : {&json_path, &svg_path, &painter_path})
        if (!out->empty() && !(sheet && out == &svg_path) && (*out == "-" || !vismap::cli::has_view_field(*out)))
          throw Usage("with --views, each output is a file named with %d for the view's number, got '" + *out + "'");
    }
  } catch (const Usage& e) {
    std::fprintf(stderr, "vismap: %s\n(run 'vismap --help' for usage)\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vismap: %s\n", e.what());
    return 2;
  }

  std::vector<vismap::cli::NamedView> cameras(1);
  cameras[0].camera = cam;
  try {
    if (!views_spec.empty()) cameras = vismap::cli::parse_views(views_spec);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "vismap: --views: %s\n(run 'vismap --help' for usage)\n", e.what());
    return 2;
  } catch (const vismap::InputError& e) {
    std::fprintf(stderr, "vismap: %s\n", e.what());
    return 1;
  }

  try {
    limits.threads = eng.threads > 0 ? eng.threads : vismap::engine::usable_cores();
    vismap::Scene scene = vismap::read_scene(scene_path, limits, format);
    // Every camera first: an impossible one stops the run before any output.
    std::vector<vismap::View> views;
    for (const vismap::cli::NamedView& c : cameras) {
      try {
        views.push_back(vismap::make_view(c.camera, scene));
      } catch (const std::invalid_argument& e) {
        std::fprintf(stderr, "vismap: %s%s\n", c.options.empty() ? "" : (c.options + ": ").c_str(), e.what());
        return 2;
      }
    }
    // Regions are computed only where an output shows them: a lines-only drawing
    // and a JSON without regions need the segments alone (the same segments).
    eng.regions = (!json_path.empty() && !no_regions) || (!svg_path.empty() && !svg.lines_only && svg.style.fills) ||
                  !painter_path.empty() ||
                  (json_path.empty() && svg_path.empty());
    // A sheet: the views' maps kept for the one page drawn after them.
    const std::string note = vismap::cli::sheet_note(views_spec), sheet_path = note.empty() ? "" : svg_path;
    std::vector<vismap::VisibilityMap> sheet_maps(sheet_path.empty() ? 0 : views.size());
    // Views side by side where the scene is small (cli/views.h), each on its
    // share of the threads; else one at a time on all of them.
    const int budget = eng.threads > 0 ? eng.threads : vismap::engine::usable_cores();
    const int side = vismap::cli::views_side_by_side(views.size(), budget, scene.faces.size(), limits.max_memory);
    if (side > 1) {
      eng.threads = std::max(1, budget / side);
      std::fprintf(stderr, "vismap: %d views at a time, %d thread%s each\n", side, eng.threads, eng.threads > 1 ? "s" : "");
    }
    vismap::ViewSeries series(scene, eng, views.size());   // (what no camera changes, made once for every view)
    const std::string json_pattern = json_path, svg_pattern = note.empty() ? svg_path : "", painter_pattern = painter_path;
    // View n: its map, its outputs written (all or none); returns its --stats lines.
    auto draw_view = [&](std::size_t n) {
      const vismap::View& view = views[n];
      std::string json_path = json_pattern, svg_path = svg_pattern, painter_path = painter_pattern;
      if (!views_spec.empty()) {
        json_path = json_pattern.empty() ? "" : vismap::cli::view_file_name(json_pattern, n);
        svg_path = svg_pattern.empty() ? "" : vismap::cli::view_file_name(svg_pattern, n);
        painter_path = painter_pattern.empty() ? "" : vismap::cli::view_file_name(painter_pattern, n);
      }
      std::vector<vismap::PaintedFragment> fragments;
      vismap::VisibilityMap map = series.map(view, painter_path.empty() ? nullptr : &fragments);
      std::string stats_lines;
      if (stats) {
        char line[128];
        for (const auto& [k, v] : map.stats.counts) {
          std::snprintf(line, sizeof line, "  %-36s %lld\n", k.c_str(), static_cast<long long>(v));
          stats_lines += line;
        }
        for (const auto& [k, v] : map.stats.seconds) {
          std::snprintf(line, sizeof line, "  %-36s %.3f s\n", k.c_str(), v);
          stats_lines += line;
        }
      } else {
        map.stats.seconds.clear();   // keep the JSON reproducible
      }
      // Each output into its temporary (the JSON streamed in pieces: a 10^6-face
      // map's is about a GB), then all renamed together: a failure leaves no
      // half-written output.
      std::vector<vismap::StreamedOutput> outputs;
      const int threads = vismap::engine::thread_count(eng.threads, scene.faces.size());
      if (!json_path.empty()) outputs.push_back({json_path, [&](const auto& write) { vismap::write_json(map, write, threads); }});
      vismap::Drawing drawing;
      if (!svg_path.empty()) {
        drawing = vismap::make_drawing(map, svg.page, svg.provenance, svg.optimize_travel);
        if (svg.optimize_travel) {
          const char* unit = drawing.at.mm ? "mm" : "px";
          char line[160];
          std::snprintf(line, sizeof line, "vismap: pen-up travel %.1f %s -> %.1f %s (%zu paths)\n",
                        drawing.travel_before, unit, drawing.travel_after, unit, drawing.chains.size());
          stats_lines = line + stats_lines;
        }
        const std::string fmt = vismap::drawing_format(svg_path);
        outputs.push_back({svg_path, [&, fmt](const auto& write) {
                             if (fmt == "dxf") write(vismap::to_dxf(drawing));
                             else if (fmt == "svg") write(vismap::to_svg(map, drawing, scene, view, svg));
                             else write(vismap::to_cairo(map, drawing, scene, view, svg, fmt));
                           }});
      }
      if (!painter_path.empty())
        outputs.push_back({painter_path, [&](const auto& write) { write(vismap::to_painter_svg(fragments, map, scene, view, svg)); }});
      // All or none (the JSON's threads write it while they format the rest).
      vismap::write_outputs_atomically(outputs);
      if (json_path.empty() && svg_path.empty() && painter_path.empty() && views_spec.empty())
        std::fprintf(stderr, "vismap: %s: %zu regions, %zu segments (no output asked for: use -o or --json)\n",
                     scene_path.c_str(), map.regions.size(), map.segments.size());
      if (!sheet_path.empty()) sheet_maps[n] = std::move(map);
      return stats_lines;
    };
    // The first view alone (it makes what the views share), then the others
    // `side` at a time; progress, statistics and errors in the views' order.
    for (std::size_t first = 0; first < views.size();) {
      const std::size_t count = first == 0 ? 1 : std::min<std::size_t>(static_cast<std::size_t>(side), views.size() - first);
      if (!views_spec.empty())
        for (std::size_t n = first; n < first + count; ++n)
          std::fprintf(stderr, "vismap: view %zu of %zu (%s)\n", n + 1, views.size(), cameras[n].options.c_str());
      std::vector<std::string> stats_lines(count);
      std::vector<std::exception_ptr> errors(count);
      vismap::cli::side_by_side(count, [&](std::size_t k) {
        try {
          stats_lines[k] = draw_view(first + k);
        } catch (...) {
          errors[k] = std::current_exception();
        }
      });
      for (std::size_t k = 0; k < count; ++k) {
        // (Side by side, the progress lines came first: each view's block is named.)
        if (count > 1 && !stats_lines[k].empty()) std::fprintf(stderr, "vismap: statistics of view %zu:\n", first + k + 1);
        std::fputs(stats_lines[k].c_str(), stderr);
        if (errors[k]) std::rethrow_exception(errors[k]);
      }
      first += count;
    }
    if (!sheet_path.empty()) {
      std::vector<vismap::SheetView> sheet;
      for (std::size_t n = 0; n < views.size(); ++n)
        sheet.push_back({&sheet_maps[n], &views[n], cameras[n].label, cameras[n].row, cameras[n].col});
      const std::string fmt = vismap::drawing_format(sheet_path);
      vismap::write_file_atomically(sheet_path, fmt == "svg" ? vismap::to_sheet_svg(sheet, scene, svg, note)
                                                             : vismap::to_sheet_cairo(sheet, scene, svg, note, fmt));
    }
    return 0;
  } catch (const vismap::InputError& e) {
    std::fprintf(stderr, "vismap: %s\n%s", e.what(), option_hint(e.what()));
    return 1;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "vismap: %s: out of memory (the scene needs more than this machine has; see --max-memory)\n",
                 scene_path.c_str());
    return 1;
  } catch (const std::logic_error& e) {
    std::fprintf(stderr, "vismap: internal error: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vismap: %s\n", e.what());
    return 1;
  }
}
