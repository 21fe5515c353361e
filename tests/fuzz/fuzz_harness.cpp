#include "tests/fuzz/fuzz_harness.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <utility>
#include <vector>

#include "arrangements/json_writer.h"
#include "verify/checker.h"

namespace vismap_fuzz {
namespace {

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string vec(const vismap::Vec3& v) { return num(v.x) + "," + num(v.y) + "," + num(v.z); }

// Reads bytes in order; zeros once they run out, so that every input decodes.
class Bytes {
 public:
  Bytes(const std::uint8_t* d, std::size_t n) : d_(d), n_(n) {}
  unsigned next() { return i_ < n_ ? d_[i_++] : 0u; }
  bool done() const { return i_ >= n_; }

 private:
  const std::uint8_t* d_;
  std::size_t n_, i_ = 0;
};

// Coordinates: small integers and halves, so that degeneracies are common.
constexpr double kCoord[] = {0, 1, 2, 3, -1, 0.5, 1.5, 4};
constexpr double kDepth[] = {0, 1, 2, -1, 0.5, 3, 1, 0};

const vismap::Vec3 kDirs[] = {{0, 0, -1}, {-1, -1, -1}, {1, -2, -4}, {0, -1, -1},
                              {-1, 0, 0}, {-1, -2, -1.5}, {0, 1, -1}, {2, 1, -3}};
const vismap::Vec3 kEyes[] = {{1.5, 1.5, 6}, {5, -4, 4}, {1, 1, 1.5}, {-2, 5, 3},
                              {2, 2, 0.5}, {0.5, -3, 1}, {8, 8, 8}, {1, 1, 0}};
const vismap::Vec3 kTargets[] = {{1, 1, 0}, {0, 0, 0}, {1.5, 1.5, 1}, {2, 2, 2}};
const double kFovs[] = {40, 60, 90, 120};
const double kCreases[] = {30, 0, 89, 180};
const double kSeamFold[] = {0, 0, -1, 1};   // the second square's far edge: coplanar (smooth), folded

}  // namespace

TinyCase decode_tiny(const std::uint8_t* data, std::size_t size) {
  Bytes b(data, size);
  TinyCase t;
  t.scene.file = "fuzz.off";

  // Camera and lines.
  const unsigned cam = b.next();
  std::ostringstream args;
  if ((cam & 1u) == 0) {
    t.camera.dir = kDirs[(cam >> 1) & 7u];
    args << "--dir " << vec(*t.camera.dir);
  } else {
    t.camera.eye = kEyes[(cam >> 1) & 7u];
    t.camera.target = kTargets[(cam >> 4) & 3u];
    t.camera.fov_deg = kFovs[(cam >> 6) & 3u];
    args << "--eye " << vec(*t.camera.eye) << " --target " << vec(*t.camera.target) << " --fov "
         << num(*t.camera.fov_deg);
  }
  const unsigned lines = b.next();
  t.options.crease_deg = kCreases[lines & 3u];
  t.options.smooth = (lines & 4u) != 0;
  const bool seam = (lines & 8u) != 0, scaled = (lines & 16u) != 0;

  // A seam: two squares sharing the edge x = 1 (coplanar, folded down or up), and
  // random vertices often in the plane x = 1, which every view along it sees
  // edge-on: faces standing on the seam or stacked under it, lines under it.
  if (seam) {
    const double z = kSeamFold[(lines >> 5) & 3u];
    t.scene.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 2, 0}, {0, 2, 0}, {2, 0, z}, {2, 2, z}};
    t.scene.faces = {{0, 1, 2, 3}, {1, 4, 5, 2}};
  }
  // Vertex pool: up to 16 more vertices, each coordinate from a small set.
  const unsigned nv = 3 + b.next() % 14;
  for (unsigned i = 0; i < nv; ++i) {
    const unsigned xy = b.next(), z = b.next();
    const double x = seam && (xy & 64u) ? 1 : kCoord[xy & 7u];
    t.scene.vertices.push_back({x, kCoord[(xy >> 3) & 7u], kDepth[z & 7u] + ((z >> 3) & 1u ? 0.25 : 0)});
  }
  const auto pool = static_cast<unsigned>(t.scene.vertices.size());
  // Faces: up to 12 more, 3 to 5 corners each, corners from the pool.
  const unsigned nf = 1 + b.next() % 12;
  for (unsigned f = 0; f < nf && !b.done(); ++f) {
    const unsigned k = 3 + b.next() % 3;
    std::vector<std::uint32_t> face;
    for (unsigned c = 0; c < k; ++c) face.push_back(b.next() % pool);
    t.scene.faces.push_back(face);
  }
  if (t.scene.faces.empty()) t.scene.faces.push_back({0, 1, 2});

  // Scale: the whole scene (and the eye) by 2^k, k in -1000..1000: the same
  // geometry, at the ends of the double range.
  if (scaled) {
    const unsigned hi = b.next(), lo = b.next();
    const double s = std::ldexp(1.0, static_cast<int>(((hi << 8) | lo) % 2001) - 1000);
    for (vismap::Vec3& v : t.scene.vertices) v = {v.x * s, v.y * s, v.z * s};
    for (auto* p : {&t.camera.eye, &t.camera.target})
      if (*p) **p = {(*p)->x * s, (*p)->y * s, (*p)->z * s};
    if (t.camera.eye) {
      args.str("");
      args << "--eye " << vec(*t.camera.eye) << " --target " << vec(*t.camera.target) << " --fov "
           << num(*t.camera.fov_deg);
    }
  }
  if (t.options.crease_deg != 30) args << " --crease " << num(t.options.crease_deg);
  if (t.options.smooth) args << " --smooth";
  // Always with the hidden lines: the checker checks them too, and both engines must agree on them.
  t.options.hidden = true;
  args << " --hidden";
  t.args = args.str();
  return t;
}

std::string to_off(const vismap::Scene& scene) {
  std::string s = "OFF\n" + std::to_string(scene.vertices.size()) + " " + std::to_string(scene.faces.size()) + " 0\n";
  for (const vismap::Vec3& v : scene.vertices) s += num(v.x) + " " + num(v.y) + " " + num(v.z) + "\n";
  for (const auto& f : scene.faces) {
    s += std::to_string(f.size());
    for (std::uint32_t i : f) s += " " + std::to_string(i);
    s += "\n";
  }
  return s;
}

Engines engines_from_env() {
  const char* e = std::getenv("VISMAP_FUZZ_ENGINE");
  const std::string w = e ? e : "franklin";
  return w == "all"    ? Engines::All
         : w == "both" ? Engines::Both
         : w == "bsp"  ? Engines::Bsp
         : w == "newell" ? Engines::Newell
                         : Engines::Franklin;
}

void check_pipeline(const std::uint8_t* data, std::size_t size, Engines engines) {
  TinyCase t = decode_tiny(data, size);
  vismap::View view;
  try {
    view = vismap::make_view(t.camera, t.scene);
  } catch (const std::invalid_argument&) {
    return;  // an impossible camera (eye on the target): refused, as the CLI does
  }
  auto runs = [&](const std::string& engine) {
    switch (engines) {
      case Engines::All: return true;
      case Engines::Both: return engine != "bsp";
      case Engines::Bsp: return engine == "bsp";
      case Engines::Newell: return engine == "newell";
      case Engines::Franklin: break;
    }
    return engine == "franklin";
  };
  std::vector<std::pair<std::string, std::string>> maps;   // (engine, JSON)
  for (const char* engine : {"franklin", "newell", "bsp"}) {
    if (!runs(engine)) continue;
    const bool franklin = std::string(engine) == "franklin";
    const std::string algo = franklin ? "" : std::string(" --algorithm ") + engine;
    const std::string repro = "\n--- scene (fuzz.off) ---\n" + to_off(t.scene) + "--- command ---\nvismap fuzz.off " +
                              t.args + algo + " --json map.json && vismap verify fuzz.off map.json" +
                              (t.options.smooth ? " --smooth" : "") +
                              (t.options.crease_deg != 30 ? " --crease " + num(t.options.crease_deg) : "") + "\n";
    std::string json;
    try {
      vismap::Options o = t.options;
      o.algorithm = franklin ? vismap::Algorithm::Franklin
                  : std::string(engine) == "newell" ? vismap::Algorithm::Newell
                                                    : vismap::Algorithm::Bsp;
      vismap::VisibilityMap map = vismap::compute_map(t.scene, view, o);
      map.stats = {};
      json = vismap::to_json(map);
    } catch (const std::exception& e) {
      die(std::string("the ") + engine + " engine threw: " + e.what() + repro);
    }
    // The checker twice: as users run it, then strict (every stretch of every
    // line, the winner among coinciding lines recomputed, no shortcut).
    vismap_check::Options opt;
    opt.samples = 150;
    opt.crease_deg = t.options.crease_deg;
    opt.smooth = t.options.smooth;
    for (bool strict : {false, true}) {
      opt.strict = strict;
      const vismap_check::Report rep = vismap_check::check_map(t.scene, json, opt);
      if (rep.ok) continue;
      std::string why = std::string("the checker") + (strict ? " (--strict)" : "") + " rejects the " + engine +
                        " engine's map:\n";
      for (const std::string& f : rep.failures) why += "  " + f + "\n";
      die(why + repro + (strict ? "(with --strict)\n" : ""));
    }
    maps.emplace_back(engine, json);
    if (!franklin) continue;
    // Franklin again with one option changed (`flag`, as the CLI spells it): its JSON.
    auto franklin_with = [&](const vismap::Options& o, const std::string& flag) {
      try {
        vismap::VisibilityMap map = vismap::visibility_franklin(t.scene, view, o);
        map.stats = {};
        return vismap::to_json(map);
      } catch (const std::exception& e) {
        die("the franklin engine threw with " + flag + ": " + e.what() + repro);
      }
    };
    // On one thread and on three: the same map, byte for byte.
    for (int threads : {1, 3}) {
      vismap::Options o = t.options;
      o.threads = threads;
      const std::string flag = "--threads " + std::to_string(threads);
      if (franklin_with(o, flag) != json) die(flag + " changed the map" + repro + "(compare with " + flag + ")\n");
    }
    // Many views of the scene (ViewSeries: the facets, edge matching and closed
    // components made once, for another view first): this view's map the same.
    try {
      vismap::ViewSeries series(t.scene, t.options, 2);
      vismap::Camera other;
      other.dir = vismap::Vec3{-1, -2, -4};
      series.map(vismap::make_view(other, t.scene));
      vismap::VisibilityMap map = series.map(view);
      map.stats = {};
      if (vismap::to_json(map) != json)
        die("a second view of a series (after --dir -1,-2,-4) changed the map" + repro +
            "(compare with --views FILE, FILE holding --dir -1,-2,-4 and this camera)\n");
    } catch (const std::exception& e) {
      die(std::string("the franklin engine threw as a series' second view: ") + e.what() + repro);
    }
    // The lines alone (--no-regions): Franklin computes less, and must write the same segments.
    vismap::Options lines_only = t.options;
    lines_only.regions = false;
    const std::string lines = franklin_with(lines_only, "--no-regions");
    auto segments = [](const std::string& j) { return j.substr(j.find("\"segments\"")); };
    if (segments(lines) != segments(json))
      die("--no-regions changed the segments" + repro + "(compare with --no-regions)\n");
  }
  for (std::size_t k = 1; k < maps.size(); ++k)
    if (maps[k].second != maps[0].second)
      die("the " + maps[0].first + " and " + maps[k].first +
          " engines' maps differ (both accepted by the checker)\n--- scene (fuzz.off) ---\n" + to_off(t.scene) +
          "--- options ---\n" + t.args + "\n");
}

}  // namespace vismap_fuzz
