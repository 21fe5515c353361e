// vismap: exact visibility maps from mesh files.
//   read scene -> camera -> engine -> JSON / SVG, each output written whole or not at all.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "arrangements/atomic_file.h"
#include "arrangements/json_writer.h"
#include "arrangements/svg_writer.h"
#include "engine/camera.h"
#include "engine/scene.h"
#include "engine/visibility.h"

namespace {

const char* kHelp = R"(usage: vismap SCENE [options]

Computes the exact visibility map of a polygon scene (OFF, OBJ, STL, PLY) and
writes it as exact JSON and/or an SVG drawing.

outputs (files are written whole or not at all; "-" is standard output):
  -o, --svg FILE       SVG drawing: visible regions shaded, visible lines stroked
  --lines-only         SVG without filled regions (a hidden-line drawing)
  --json FILE          the exact map (format: shared/spec/vismap-json.md)
camera (default: orthographic, the whole scene seen obliquely):
  --dir X,Y,Z          orthographic, looking along this direction
  --eye X,Y,Z          perspective eye point
  --target X,Y,Z       perspective target (default: the scene's centre)
  --fov DEG            perspective vertical field of view (default 40)
  --up X,Y,Z           up direction (default 0,0,1; 0,1,0 when parallel)
lines:
  --crease DEG         dihedral angle making a shared edge a crease (default 30)
  --smooth             also draw smooth edges
engine:
  --grid-c C           Franklin's grid constant c, B = c*min(sqrt(N),1/L) (default 4)
  --stats              print statistics on stderr and add phase timings to the
                       JSON (without it the JSON is byte-for-byte reproducible)
  -h, --help           this text

exit status: 0 success, 1 bad input or output error, 2 bad usage
)";

struct Usage : std::runtime_error {
  using std::runtime_error::runtime_error;
};

double parse_double(const std::string& opt, const std::string& s) {
  char* end = nullptr;
  double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end != '\0' || !std::isfinite(v)) throw Usage(opt + " expects a finite number, got '" + s + "'");
  return v;
}

vismap::Vec3 parse_vec(const std::string& opt, const std::string& s) {
  std::vector<double> v;
  std::size_t start = 0;
  while (true) {
    std::size_t comma = s.find(',', start);
    v.push_back(parse_double(opt, s.substr(start, comma - start)));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (v.size() != 3) throw Usage(opt + " expects X,Y,Z, got '" + s + "'");
  return {v[0], v[1], v[2]};
}

}  // namespace

int main(int argc, char** argv) {
  std::string scene_path, svg_path, json_path;
  vismap::CameraSpec cam;
  vismap::EngineOptions eng;
  vismap::SvgOptions svg;
  bool stats = false;
  try {
    std::vector<std::string> args(argv + 1, argv + argc);
    for (std::size_t i = 0; i < args.size(); ++i) {
      const std::string& a = args[i];
      auto value = [&]() -> const std::string& {
        if (i + 1 >= args.size()) throw Usage(a + " needs a value");
        return args[++i];
      };
      if (a == "-h" || a == "--help") { std::fputs(kHelp, stdout); return 0; }
      else if (a == "-o" || a == "--svg") svg_path = value();
      else if (a == "--json") json_path = value();
      else if (a == "--lines-only") svg.lines_only = true;
      else if (a == "--dir") cam.dir = parse_vec(a, value());
      else if (a == "--eye") cam.eye = parse_vec(a, value());
      else if (a == "--target") cam.target = parse_vec(a, value());
      else if (a == "--fov") cam.fov_deg = parse_double(a, value());
      else if (a == "--up") cam.up = parse_vec(a, value());
      else if (a == "--crease") {
        eng.crease_deg = parse_double(a, value());
        if (eng.crease_deg < 0 || eng.crease_deg > 180) throw Usage("--crease must be between 0 and 180");
      } else if (a == "--grid-c") {
        eng.grid_c = parse_double(a, value());
        if (!(eng.grid_c > 0 && eng.grid_c <= 64)) throw Usage("--grid-c must be in (0, 64]");
      } else if (a == "--smooth") eng.smooth = true;
      else if (a == "--stats") stats = true;
      else if (a.size() > 1 && a[0] == '-') throw Usage("unknown option " + a);
      else if (scene_path.empty()) scene_path = a;
      else throw Usage("more than one scene given: " + scene_path + ", " + a);
    }
    if (scene_path.empty()) throw Usage("no scene file given");
    if (!svg_path.empty() && svg_path == json_path) throw Usage("--json and -o name the same file");
  } catch (const Usage& e) {
    std::fprintf(stderr, "vismap: %s\n(run 'vismap --help' for usage)\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vismap: %s\n", e.what());
    return 2;
  }

  try {
    vismap::Scene scene = vismap::read_scene(scene_path);
    vismap::View view;
    try {
      view = vismap::make_view(cam, scene);
    } catch (const std::invalid_argument& e) {
      std::fprintf(stderr, "vismap: %s\n", e.what());
      return 2;
    }
    vismap::VisibilityMap map = vismap::visibility_franklin(scene, view, eng);
    if (stats) {
      for (const auto& [k, v] : map.stats.counts) std::fprintf(stderr, "  %-36s %lld\n", k.c_str(), static_cast<long long>(v));
      for (const auto& [k, v] : map.stats.seconds) std::fprintf(stderr, "  %-36s %.3f s\n", k.c_str(), v);
    } else {
      map.stats.seconds.clear();   // keep the JSON reproducible
    }
    // Render everything first, then write: a failure leaves no half-written output.
    std::string json = json_path.empty() ? "" : vismap::to_json(map);
    std::string drawing = svg_path.empty() ? "" : vismap::to_svg(map, scene, view, svg);
    if (!json_path.empty()) vismap::write_file_atomically(json_path, json);
    if (!svg_path.empty()) vismap::write_file_atomically(svg_path, drawing);
    if (json_path.empty() && svg_path.empty())
      std::fprintf(stderr, "vismap: %s: %zu regions, %zu segments (no output asked for: use -o or --json)\n",
                   scene_path.c_str(), map.regions.size(), map.segments.size());
    return 0;
  } catch (const vismap::InputError& e) {
    std::fprintf(stderr, "vismap: %s\n", e.what());
    return 1;
  } catch (const std::logic_error& e) {
    std::fprintf(stderr, "vismap: internal error: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vismap: %s\n", e.what());
    return 1;
  }
}
