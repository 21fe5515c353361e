// Run time against error (issue 4): the image-precision baselines (z-buffer,
// scan line, Warnock, ray casting; bench/raster) at R x R pixels next to the
// exact engine (visibility_franklin, error 0), on Franklin's random squares
// (N = 10^4 and 10^5 at depth complexity D = 10, seen from +z), a cube array
// and a sphere (default oblique view), and the 10^4 squares put on 8 planes
// and seen obliquely (coplanar overlaps everywhere: z-fighting).
//
// Times are CPU time of the process (CLOCK_PROCESS_CPUTIME_ID), the best of a
// few runs for short ones; a baseline's time includes the projection of the
// scene to screen space (shown separately too), not the error measurement.
// Errors (bench/raster/exact_error.h): the fraction of pixel centres labelled
// differently from the exact map ("centre error"); the fraction of the window's
// area painted with a wrong label when each pixel's square takes its centre's
// label ("area error", 16 exact samples per pixel up to R = 4096, 4 at 8192;
// the exact centre labels' own area error is the floor for R x R pixels); and
// for the drawing derived from the label
// changes, the exact visible line length missed and the length of lines drawn
// where the exact drawing has none, both as fractions of the exact visible
// length (tolerance 1.25 pixel; the exact labels' own line error is the
// resolution floor). The crossover is the resolution at which a baseline
// becomes as costly as the exact engine (log-log interpolation between the
// measured resolutions).
//
//   bench_raster                       all scenes, R = 256 .. 4096 (8192 with --big)
//   bench_raster --scenes squares1e4,cubes --R 256,1024 --no-lines
//   bench_raster --scene FILE --map MAP.json --R 1024
//                                      a map made by `vismap FILE --json MAP.json`
//                                      with the same camera (errors only; the
//                                      view comes from the map's matrix)
//   --csv FILE                         also write the rows as CSV
//   --squares N,N,... [--depth D]      instead of the named scenes: random squares
//                                      (random_squares_depth(N, D, 1980), D = 10 by
//                                      default) seen from +z, one scene per N
//   --no-errors                        times only: no exact labels, no errors (the
//                                      exact engine is still timed for the crossover)
//   --no-exact                         do not run the exact engine (implies --no-errors)
//
// Run it under `nice` on a shared machine and compare ratios within one run.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "bench/raster/exact_error.h"
#include "bench/raster/raster.h"
#include "bench/cpu_time.h"
#include "bench/scene_gen.h"
#include "engine/camera.h"
#include "engine/scene.h"
#include "engine/visibility.h"

namespace {

using namespace vismap;

using vismap::bench::cpu_now;

// Best CPU time of fn over runs, at least one run, more while the total stays
// under `budget` seconds (at most `max_runs`).
double best_time(const std::function<void()>& fn, double budget = 1.0, int max_runs = 5) {
  double best = 1e300, total = 0;
  for (int k = 0; k < max_runs && (k == 0 || total + best < budget); ++k) {
    const double t0 = cpu_now();
    fn();
    const double t = cpu_now() - t0;
    best = std::min(best, t);
    total += t;
  }
  return best;
}

struct SceneCase {
  std::string name;
  std::function<Scene()> make;
  Camera camera;
};

std::vector<SceneCase> all_cases() {
  Camera down;
  down.dir = Vec3{0, 0, -1};
  Camera across;
  across.eye = Vec3{0.5, -0.6, 1.6};
  across.target = Vec3{0.5, 0.5, 0.3};
  across.fov_deg = 60;
  return {
      {"squares1e4", [] { return gen::random_squares_depth(10000, 10, 1980); }, down},
      {"squares1e5", [] { return gen::random_squares_depth(100000, 10, 1980); }, down},
      // Perspective variant: far squares are smaller (eye above one side, looking across).
      {"perspective1e4", [] { return gen::random_squares_depth(10000, 10, 1980); }, across},
      {"terrain", [] { return gen::terrain(100, 1980); }, Camera{}},   // 20000 triangles, self-occluding
      {"cubes", [] { return gen::cube_array(12); }, Camera{}},      // 1728 cubes, 10368 quads
      {"sphere", [] { return gen::sphere(256, 128); }, Camera{}},   // 32768 faces
      // Z-fighting: the squares of squares1e4 on 8 planes (z rounded to eighths),
      // seen obliquely, so that coplanar overlaps are everywhere and tilted: the
      // exact rule (lowest index) against depths rounded differently per face.
      {"coplanar1e4",
       [] {
         Scene s = gen::random_squares_depth(10000, 10, 1980);
         for (Vec3& p : s.vertices) p.z = std::floor(p.z * 8) / 8;
         s.file = "random_squares(n=10000,D=10,seed=1980), z rounded down to 1/8";
         return s;
       },
       Camera{}},
  };
}

struct Row {
  std::string scene, method;
  int R = 0;
  double seconds = 0;       // raster only
  double total = 0;         // with the projection
  double pixel_error = 0, area_error = 0, missed = 0, false_drawn = 0;
  bool lines = false;
  bool errors = true;       // the error columns were measured
  double exact = -1;        // the exact engine's CPU time on this scene (< 0: not run)
};

std::string pct(double f) {
  char buf[32];
  if (f == 0)
    std::snprintf(buf, sizeof buf, "0");
  else if (f < 1e-4)
    std::snprintf(buf, sizeof buf, "%.2e%%", 100 * f);
  else
    std::snprintf(buf, sizeof buf, "%.3f%%", 100 * f);
  return buf;
}

std::vector<int> parse_ints(const std::string& s) {
  std::vector<int> out;
  std::stringstream in(s);
  std::string tok;
  while (std::getline(in, tok, ',')) out.push_back(std::stoi(tok));
  return out;
}

std::vector<std::string> parse_names(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  std::string tok;
  while (std::getline(in, tok, ',')) out.push_back(tok);
  return out;
}

struct BenchOptions {
  std::vector<int> R = {256, 512, 1024, 2048, 4096};
  std::vector<std::string> scenes;
  bool lines = true;
  bool errors = true;          // --no-errors: times only
  bool exact = true;           // --no-exact: the exact engine is not run
  std::vector<int> squares;    // --squares: random squares of these sizes instead of the named scenes
  double depth = 10;           // --depth: their depth complexity
  std::string scene_file, map_file, csv;
};

// Runs every method at every R on one scene; `exact_seconds` < 0: no engine time.
std::vector<Row> run_scene(const std::string& name, const Scene& scene, const View& view, const VisibilityMap& map,
                           double exact_seconds, const BenchOptions& opt) {
  std::vector<Row> rows;
  raster::ScreenScene ss;
  const double t_project = best_time([&] { ss = raster::project(scene, view); });
  const raster::LineRule smooth = raster::line_rule(scene, view, ss);
  std::printf("\n## %s: %zu faces, %zu screen pieces, %zu regions, %zu segments\n", name.c_str(), scene.faces.size(),
              ss.pieces.size(), map.regions.size(), map.segments.size());
  if (exact_seconds >= 0) std::printf("exact engine (visibility_franklin): %.3f s CPU\n", exact_seconds);
  std::printf("projection to screen pieces: %.3f s CPU (included in every baseline's total)\n\n", t_project);
  std::printf("| R | method | raster s | total s | total / exact | centre error | area error | lines missed | lines false |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  std::fflush(stdout);
  for (int R : opt.R) {
    const raster::Window w = raster::window_for(ss, R);
    raster::ExactLabels ex;
    const double t_exact_labels = opt.errors ? best_time([&] { ex = raster::exact_labels(map, w); }, 0, 1) : 0;
    std::vector<raster::Image> images;
    std::vector<Row> here;
    for (raster::Method m : raster::kMethods) {
      raster::Image img;
      const double t = best_time([&] { img = raster::render(m, ss, w); });
      Row row;
      row.scene = name;
      row.method = raster::name(m);
      row.R = R;
      row.seconds = t;
      row.total = t + t_project;
      row.exact = exact_seconds;
      row.errors = opt.errors;
      if (opt.errors) row.pixel_error = raster::pixel_error(ex.image, img).fraction();
      if (opt.lines && opt.errors) {
        const raster::LineError le = raster::line_error(map, img, w, smooth);
        row.missed = le.missed_fraction();
        row.false_drawn = le.false_fraction();
        row.lines = true;
      }
      if (opt.errors) images.push_back(std::move(img));
      here.push_back(row);
    }
    if (!opt.errors) {   // times only
      for (const Row& row : here) {
        char ratio[32] = "-";
        if (exact_seconds > 0) std::snprintf(ratio, sizeof ratio, "%.3f", row.total / exact_seconds);
        std::printf("| %d | %s | %.3f | %.3f | %s | - | - | - | - |\n", R, row.method.c_str(), row.seconds, row.total,
                    ratio);
        rows.push_back(row);
      }
      std::fflush(stdout);
      continue;
    }
    // The area error of every image, and of the exact centre labels (the best
    // any picture of R x R flat pixels can do), in one pass over a finer grid.
    const int k = std::max(1, std::min(4, 16384 / R));
    std::vector<const raster::Image*> all;
    for (const raster::Image& img : images) all.push_back(&img);
    all.push_back(&ex.image);
    const double t0 = cpu_now();
    const std::vector<raster::AreaError> area = raster::area_error(map, all, w, k);
    const double t_area = cpu_now() - t0;
    raster::LineError floor_lines;
    if (opt.lines) floor_lines = raster::line_error(map, ex.image, w, smooth);
    std::printf("| %d | exact centre labels (%.2f s; %zu crossings, %zu decided exactly, %zu centres on edges; "
                "area: %dx%d samples per pixel, %.2f s) | | | | 0 | %s | %s | %s |\n",
                R, t_exact_labels, ex.crossings, ex.exact_crossings, ex.boundary, k, k, t_area,
                pct(area.back().fraction()).c_str(), opt.lines ? pct(floor_lines.missed_fraction()).c_str() : "-",
                opt.lines ? pct(floor_lines.false_fraction()).c_str() : "-");
    for (std::size_t m = 0; m < here.size(); ++m) {
      Row& row = here[m];
      row.area_error = area[m].fraction();
      char ratio[32] = "-";
      if (exact_seconds > 0) std::snprintf(ratio, sizeof ratio, "%.3f", row.total / exact_seconds);
      std::printf("| %d | %s | %.3f | %.3f | %s | %s | %s | %s | %s |\n", R, row.method.c_str(), row.seconds,
                  row.total, ratio, pct(row.pixel_error).c_str(), pct(row.area_error).c_str(),
                  row.lines ? pct(row.missed).c_str() : "-", row.lines ? pct(row.false_drawn).c_str() : "-");
      rows.push_back(row);
    }
    std::fflush(stdout);
  }
  if (exact_seconds > 0) {
    // Crossover: where total time reaches the exact engine's, log-log interpolated.
    std::printf("\ncrossover (baseline total = exact engine %.3f s):\n", exact_seconds);
    for (raster::Method m : raster::kMethods) {
      std::vector<const Row*> mine;
      for (const Row& r : rows)
        if (r.method == raster::name(m)) mine.push_back(&r);
      std::string where;
      if (mine.empty()) continue;
      if (mine.front()->total >= exact_seconds) {
        where = "at or below R = " + std::to_string(mine.front()->R) + " (already " +
                std::to_string(mine.front()->total / exact_seconds).substr(0, 5) + "x the exact time)";
      } else {
        for (std::size_t k = 1; k < mine.size() && where.empty(); ++k)
          if (mine[k]->total >= exact_seconds) {
            const double l0 = std::log(mine[k - 1]->R), l1 = std::log(mine[k]->R);
            const double t0 = std::log(mine[k - 1]->total), t1 = std::log(mine[k]->total);
            const double at = std::exp(l0 + (std::log(exact_seconds) - t0) * (l1 - l0) / (t1 - t0));
            char buf[64];
            std::snprintf(buf, sizeof buf, "R ~ %.0f", at);
            where = buf;
          }
        if (where.empty()) {
          where = "above R = " + std::to_string(mine.back()->R) + " (there " +
                  std::to_string(mine.back()->total / exact_seconds).substr(0, 5) + "x the exact time)";
          // Extrapolated with t = a + b R^2 through the two largest resolutions.
          if (mine.size() >= 2) {
            const double r1 = mine[mine.size() - 2]->R, r2 = mine.back()->R;
            const double t1 = mine[mine.size() - 2]->total, t2 = mine.back()->total;
            const double b = (t2 - t1) / (r2 * r2 - r1 * r1), a = t1 - b * r1 * r1;
            if (b > 0) {
              char buf[96];
              std::snprintf(buf, sizeof buf, "; extrapolated (t = a + b R^2): R ~ %.0f", std::sqrt((exact_seconds - a) / b));
              where += buf;
            }
          }
        }
      }
      std::printf("  %-10s %s\n", raster::name(m), where.c_str());
    }
  }
  return rows;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

int usage() {
  std::fprintf(stderr,
               "usage: bench_raster [--R 256,512,...] [--big] [--scenes squares1e4,squares1e5,perspective1e4,terrain,cubes,sphere,coplanar1e4]\n"
               "                    [--no-lines] [--csv FILE] [--scene FILE --map MAP.json]\n"
               "                    [--squares N,N,... [--depth D]] [--no-errors] [--no-exact]\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  BenchOptions opt;
  for (int k = 1; k < argc; ++k) {
    const std::string a = argv[k];
    auto value = [&]() -> std::string {
      if (k + 1 >= argc) throw std::invalid_argument(a + " needs a value");
      return argv[++k];
    };
    try {
      if (a == "--R") opt.R = parse_ints(value());
      else if (a == "--big") opt.R.push_back(8192);
      else if (a == "--scenes") opt.scenes = parse_names(value());
      else if (a == "--no-lines") opt.lines = false;
      else if (a == "--csv") opt.csv = value();
      else if (a == "--scene") opt.scene_file = value();
      else if (a == "--map") opt.map_file = value();
      else if (a == "--squares") opt.squares = parse_ints(value());
      else if (a == "--depth") opt.depth = std::stod(value());
      else if (a == "--no-errors") opt.errors = false;
      else if (a == "--no-exact") opt.exact = opt.errors = false;
      else return usage();
    } catch (const std::exception& e) {
      std::fprintf(stderr, "bench_raster: %s\n", e.what());
      return usage();
    }
  }
  std::vector<Row> rows;
  try {
    if (!opt.scene_file.empty() || !opt.map_file.empty()) {
      if (opt.scene_file.empty() || opt.map_file.empty()) return usage();
      const Scene scene = read_scene(opt.scene_file);
      const VisibilityMap map = raster::read_map_json(slurp(opt.map_file));
      const auto r = run_scene(opt.scene_file, scene, raster::view_of(map), map, -1, opt);
      rows.insert(rows.end(), r.begin(), r.end());
    } else {
      std::vector<SceneCase> cases = all_cases();
      if (!opt.squares.empty()) {
        cases.clear();
        Camera down;
        down.dir = Vec3{0, 0, -1};
        for (int n : opt.squares) {
          const double d = opt.depth;
          cases.push_back({"squares_N" + std::to_string(n),
                           [n, d] { return gen::random_squares_depth(static_cast<std::size_t>(n), d, 1980); }, down});
        }
      }
      for (const SceneCase& c : cases) {
        if (!opt.scenes.empty() && std::find(opt.scenes.begin(), opt.scenes.end(), c.name) == opt.scenes.end())
          continue;
        const Scene scene = c.make();
        const View view = make_view(c.camera, scene);
        if (!opt.exact) {   // the baselines' times only
          const auto r = run_scene(c.name, scene, view, VisibilityMap{}, -1, opt);
          rows.insert(rows.end(), r.begin(), r.end());
          continue;
        }
        // Timed as bench_franklin times it: the map's destruction included.
        const double t_exact = best_time(
            [&] {
              VisibilityMap m = visibility_franklin(scene, view, vismap::Options{});
              if (m.regions.empty()) std::printf("(empty map)\n");
            },
            10.0, 3);
        const VisibilityMap map = visibility_franklin(scene, view, vismap::Options{});
        const auto r = run_scene(c.name, scene, view, map, t_exact, opt);
        rows.insert(rows.end(), r.begin(), r.end());
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_raster: %s\n", e.what());
    return 1;
  }
  if (!opt.csv.empty()) {
    std::ofstream out(opt.csv);
    out << "scene,method,R,raster_s,total_s,centre_error,area_error,lines_missed,lines_false,exact_s\n";
    auto num = [](bool have, double v) {
      if (!have) return std::string();
      std::ostringstream o;
      o.precision(9);
      o << v;
      return o.str();
    };
    for (const Row& r : rows)
      out << r.scene << ',' << r.method << ',' << r.R << ',' << r.seconds << ',' << r.total << ','
          << num(r.errors, r.pixel_error) << ',' << num(r.errors, r.area_error) << ',' << num(r.lines, r.missed) << ','
          << num(r.lines, r.false_drawn) << ',' << num(r.exact >= 0, r.exact) << '\n';
  }
  return 0;
}
