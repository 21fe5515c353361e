// Stability stress (issue 4, item 7): degenerate configurations from the test
// corpus -- shared edges, T-junctions, coplanar overlaps, vertices on edges,
// touching corners, cyclic overlaps, a pierced face -- perturbed by relative
// amounts 1e-1 ... 1e-300, scaled by 1e-15 ... 1e15 and rotated, then given to
// every engine:
//
//   franklin, newell    the exact engines (must show zero on every row)
//   franklin_float      the same Franklin code on doubles (engine/exact_kernel.h)
//   zbuffer, scanline, warnock, raycast   the image-precision baselines (R = 256)
//
// Each engine runs in a child process (fork), so that a crash or a hang (20 s)
// is counted rather than fatal. What is counted per engine:
//   crash     killed by a signal, or out of time
//   invalid   the map's topology is broken (the builder's consistency check threw,
//             or the checker's topology/format checks fail)
//   labels    a region is wrong: the brute-force exact checker (vismap verify)
//             finds a sample labelled wrongly or a wrong total area; for the
//             raster baselines, a pixel centre labelled unlike the exact map
//   lines     a drawn segment is hidden or of the wrong kind, or a visible edge is
//             not drawn (the checker); the raster baselines draw no lines: "-"
//
// usage: stability_stress [--data DIR] [--quick] [--samples N] [--dump DIR]
//   prints a Markdown report on stdout, progress on stderr; exit status 1 if an
//   exact engine failed anywhere. --dump writes every scene an exact engine failed
//   on (OFF) with the checker's first failures on stderr; --only keeps the
//   configurations whose file name contains FILE (same seeds as a full run).
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "arrangements/json_writer.h"
#include "bench/raster/exact_error.h"
#include "bench/scene_gen.h"
#include "bench/raster/raster.h"
#include "engine/camera.h"
#include "engine/scene.h"
#include "engine/visibility.h"
#include "verify/checker.h"

#include <fstream>

namespace {

using vismap::Scene;
using vismap::Vec3;

struct Config {
  const char* file;
  const char* what;
};
const Config kConfigs[] = {
    {"shared_edge_crease.off", "shared edge"},     {"shared_edge_coplanar.off", "shared edge, coplanar"},
    {"t_junction.off", "T-junction"},              {"coplanar_overlap.off", "coplanar overlap"},
    {"vertex_on_edge.off", "vertex on edge"},      {"touching_corners.off", "touching corners"},
    {"newell_cyclic.off", "cyclic overlap"},       {"pierced_face.off", "pierced face"},
    {"interpenetrating_boxes.off", "interpenetrating boxes"},
};

// The scene perturbed (each coordinate times 1 + eps*u, u uniform in [-1, 1]),
// rotated (a seeded random rotation, or none) and scaled, in doubles: whatever
// the doubles end up being is the input the engines must answer exactly.
Scene transform(const Scene& base, double eps, double scale, bool rotate, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::array<std::array<double, 3>, 3> R{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  if (rotate) {   // a random unit quaternion
    double q[4], n = 0;
    for (double& c : q) { c = u(rng); n += c * c; }
    n = std::sqrt(n);
    for (double& c : q) c /= n;
    const double w = q[0], x = q[1], y = q[2], z = q[3];
    R = {{{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
          {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
          {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}}};
  }
  Scene s = base;
  for (Vec3& v : s.vertices) {
    double p[3] = {v.x, v.y, v.z};
    if (eps > 0)
      for (double& c : p) c *= 1 + eps * u(rng);
    double r[3];
    for (int i = 0; i < 3; ++i) r[i] = (R[i][0] * p[0] + R[i][1] * p[1] + R[i][2] * p[2]) * scale;
    v = Vec3{r[0], r[1], r[2]};
  }
  return s;
}

// Runs f in a child process; f writes its answer to the given fd. Returns false
// (and sets *crashed) when the child dies by a signal or runs out of time.
template <class F>
bool in_child(F&& f, std::string& out) {
  int fd[2];
  if (pipe(fd) != 0) throw std::runtime_error("pipe failed");
  std::fflush(nullptr);
  pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    close(fd[0]);
    alarm(20);
    std::string answer;
    try {
      answer = f();
    } catch (const std::logic_error& e) {
      answer = std::string("INVALID ") + e.what();
    } catch (const std::exception& e) {
      answer = std::string("ERROR ") + e.what();
    }
    std::size_t done = 0;
    while (done < answer.size()) {
      ssize_t n = write(fd[1], answer.data() + done, answer.size() - done);
      if (n <= 0) break;
      done += static_cast<std::size_t>(n);
    }
    _exit(0);
  }
  close(fd[1]);
  out.clear();
  char buf[65536];
  ssize_t n;
  while ((n = read(fd[0], buf, sizeof buf)) > 0) out.append(buf, static_cast<std::size_t>(n));
  close(fd[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

struct Tally {
  int runs = 0, crash = 0, invalid = 0, labels = 0, lines = 0;
  bool raster = false;
  bool clean() const { return crash + invalid + labels + lines == 0; }
};

// Sorts a checker report's failures into the columns.
void judge(const vismap_check::Report& r, Tally& t) {
  if (r.ok) return;
  bool inv = false, lab = false, lin = false;
  for (const std::string& f : r.failures) {
    const std::string cat = f.substr(0, f.find(':'));
    if (cat == "regions" || cat == "area") lab = true;
    else if (cat == "segment" || cat == "coverage") lin = true;
    else if (cat == "topology" || cat == "format") inv = true;
  }
  if (!inv && !lab && !lin) inv = true;
  t.invalid += inv;
  t.labels += lab;
  t.lines += lin;
}

std::string fmt_exp(double v) {
  if (v == 0) return "0";
  char b[32];
  std::snprintf(b, sizeof b, "1e%d", static_cast<int>(std::lround(std::log10(v))));
  return b;
}

}  // namespace

int main(int argc, char** argv) {
  std::string data = VISMAP_DATA_DIR;
  bool quick = false;
  std::size_t samples = 400;
  std::string dump, only;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--data" && i + 1 < argc) data = argv[++i];
    else if (a == "--quick") quick = true;
    else if (a == "--samples" && i + 1 < argc) samples = std::stoul(argv[++i]);
    else if (a == "--dump" && i + 1 < argc) dump = argv[++i];
    else if (a == "--only" && i + 1 < argc) only = argv[++i];
    else if (a == "-h" || a == "--help") {
      std::printf("usage: stability_stress [--data DIR] [--quick] [--samples N] [--dump DIR] [--only FILE]\n");
      return 0;
    } else {
      std::fprintf(stderr, "stability_stress: unknown argument '%s'\n", a.c_str());
      return 2;
    }
  }
  const std::vector<double> epsilons = quick ? std::vector<double>{0, 1e-3, 1e-15, 1e-300}
                                             : std::vector<double>{0, 1e-1, 1e-3, 1e-6, 1e-9, 1e-12, 1e-15, 1e-30,
                                                                   1e-100, 1e-300};
  const std::vector<double> scales = quick ? std::vector<double>{1e-15, 1, 1e15}
                                           : std::vector<double>{1e-15, 1e-5, 1, 1e5, 1e15};
  const std::vector<std::string> engines = {"franklin", "newell", "franklin_float",
                                            "zbuffer",  "scanline", "warnock", "raycast"};
  const vismap::raster::Method methods[] = {vismap::raster::Method::ZBuffer, vismap::raster::Method::ScanLine,
                                            vismap::raster::Method::Warnock, vismap::raster::Method::RayCast};
  constexpr int R = 256;

  // Rows: the perturbation; within a row, every config, scale and rotation.
  std::map<double, std::map<std::string, Tally>> rows;
  std::map<std::string, std::map<std::string, Tally>> per_config;
  std::uint64_t seed = 1;
  int scenes = 0;
  for (const Config& cfg : kConfigs) {
    const Scene base = vismap::read_scene(data + "/" + cfg.file);
    for (double eps : epsilons)
      for (double scale : scales)
        for (bool rotate : {false, true}) {
          if (!only.empty() && std::string(cfg.file).find(only) == std::string::npos) { ++seed; continue; }
          const Scene scene = transform(base, eps, scale, rotate, seed++);
          vismap::Camera cam;
          cam.dir = Vec3{-0.25, -0.5, -1};   // oblique: every face seen, no edge-on ties by design
          const vismap::View view = vismap::make_view(cam, scene);
          const vismap::Options opt;
          vismap_check::Options copt;
          copt.samples = samples;
          copt.seed = seed;
          ++scenes;

          // The exact engines and the float variant: the map, judged by the checker.
          std::string exact_json;
          for (const std::string& e : {std::string("franklin"), std::string("newell"), std::string("franklin_float")}) {
            std::string out;
            bool ok = in_child(
                [&] {
                  // The exact engines through the one dispatch; the float variant is bench-only.
                  vismap::Options o = opt;
                  o.algorithm = e == "newell" ? vismap::Algorithm::Newell : vismap::Algorithm::Franklin;
                  vismap::VisibilityMap m = e == "franklin_float" ? vismap::visibility_franklin_float(scene, view, opt)
                                                                  : vismap::compute_map(scene, view, o);
                  return vismap::to_json(m);
                },
                out);
            const bool answered = ok && out.rfind("INVALID ", 0) != 0 && out.rfind("ERROR ", 0) != 0;
            const vismap_check::Report report =
                answered ? vismap_check::check_map(scene, out, copt) : vismap_check::Report{};
            for (Tally* t : {&rows[eps][e], &per_config[cfg.what][e]}) {
              ++t->runs;
              if (!ok) { ++t->crash; continue; }
              if (!answered) { ++t->invalid; continue; }
              judge(report, *t);
            }
            if (!dump.empty() && e != "franklin_float" && (!answered || !report.ok)) {
              const std::string name = dump + "/" + e + "_" + std::to_string(seed) + ".off";
              std::ofstream(name) << vismap::gen::to_off(scene);
              std::fprintf(stderr, "%s: %s failed (%s)\n", name.c_str(), e.c_str(),
                           answered ? (report.failures.empty() ? "?" : report.failures[0].c_str()) : out.c_str());
            }
            if (ok && e == "franklin" && out.rfind("INVALID", 0) != 0 && out.rfind("ERROR", 0) != 0) exact_json = out;
          }

          // The raster baselines: labels at pixel centres against the exact map's.
          vismap::raster::ScreenScene ss = vismap::raster::project(scene, view);
          vismap::raster::Window w = vismap::raster::window_for(ss, R);
          vismap::raster::ExactLabels truth;
          bool have_truth = false;
          if (!exact_json.empty()) {
            truth = vismap::raster::exact_labels(vismap::raster::read_map_json(exact_json), w);
            have_truth = true;
          }
          for (std::size_t k = 0; k < 4; ++k) {
            const std::string e = engines[3 + k];
            std::string out;
            bool ok = in_child(
                [&] {
                  vismap::raster::Image img = vismap::raster::render(methods[k], ss, w);
                  return std::string(reinterpret_cast<const char*>(img.label.data()),
                                     img.label.size() * sizeof(std::int32_t));
                },
                out);
            for (Tally* t : {&rows[eps][e], &per_config[cfg.what][e]}) {
              t->raster = true;
              ++t->runs;
              if (!ok || out.size() != static_cast<std::size_t>(R) * R * sizeof(std::int32_t)) { ++t->crash; continue; }
              if (!have_truth) continue;
              vismap::raster::Image img = truth.image;
              std::memcpy(img.label.data(), out.data(), out.size());
              if (vismap::raster::pixel_error(truth.image, img).wrong > 0) ++t->labels;
            }
          }
        }
    std::fprintf(stderr, "stability_stress: %s done (%d scenes so far)\n", cfg.file, scenes);
  }

  // The report.
  auto cell = [](const Tally& t) {
    if (t.raster) return std::to_string(t.crash) + " / - / " + std::to_string(t.labels) + " / -";
    return std::to_string(t.crash) + " / " + std::to_string(t.invalid) + " / " + std::to_string(t.labels) + " / " +
           std::to_string(t.lines);
  };
  auto table = [&](const char* first, auto& rowsmap, auto&& label) {
    std::printf("| %s |", first);
    for (const auto& e : engines) std::printf(" %s |", e.c_str());
    std::printf("\n|---|");
    for (std::size_t i = 0; i < engines.size(); ++i) std::printf("---:|");
    std::printf("\n");
    for (auto& [key, byengine] : rowsmap) {
      std::printf("| %s |", label(key).c_str());
      for (const auto& e : engines) std::printf(" %s |", cell(byengine[e]).c_str());
      std::printf("\n");
    }
  };
  std::printf("%d scenes: %zu configurations x %zu perturbations x %zu scales x 2 rotations; each cell: "
              "crash / invalid / wrong labels / wrong lines (scenes), raster R = %d.\n\n",
              scenes, std::size(kConfigs), epsilons.size(), scales.size(), R);
  std::printf("### By relative perturbation\n\n");
  table("perturbation", rows, [](double e) { return fmt_exp(e); });
  std::printf("\n### By configuration\n\n");
  table("configuration", per_config, [](const std::string& s) { return s; });

  bool exact_clean = true;
  for (auto& [eps, byengine] : rows)
    for (const char* e : {"franklin", "newell"}) exact_clean &= byengine[e].clean();
  std::printf("\nexact engines: %s\n", exact_clean ? "zero failures on every row" : "FAILURES (see above)");
  return exact_clean ? 0 : 1;
}
