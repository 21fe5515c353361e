// vismap_check_tool SCENE_FILE MAP.json [--samples N] [--seed S] [--crease DEG] [--smooth]
// Checks a map written by `vismap --json` against the scene; exit 0 iff it is correct.
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include "engine/scene.h"
#include "tests/checker/checker.h"

namespace {

int usage() {
  std::cerr << "usage: vismap_check_tool SCENE_FILE MAP.json [--samples N] [--seed S] [--crease DEG] [--smooth]\n";
  return 2;
}

bool number(const char* s, double& out) {
  char* end = nullptr;
  out = std::strtod(s, &end);
  return end != s && *end == '\0';
}

bool count(const char* s, std::uint64_t& out) {
  char* end = nullptr;
  out = std::strtoull(s, &end, 10);
  return end != s && *end == '\0' && s[0] != '-';
}

}  // namespace

int main(int argc, char** argv) {
  std::string scene_path, map_path;
  vismap_check::Options opt;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    bool has_value = i + 1 < argc;
    std::uint64_t n = 0;
    double d = 0;
    if (a == "--smooth") {
      opt.smooth = true;
    } else if (a == "--samples" && has_value && count(argv[i + 1], n)) {
      opt.samples = n;
      ++i;
    } else if (a == "--seed" && has_value && count(argv[i + 1], n)) {
      opt.seed = n;
      ++i;
    } else if (a == "--crease" && has_value && number(argv[i + 1], d)) {
      opt.crease_deg = d;
      ++i;
    } else if (a.size() > 1 && a[0] == '-') {
      return usage();
    } else if (scene_path.empty()) {
      scene_path = a;
    } else if (map_path.empty()) {
      map_path = a;
    } else {
      return usage();
    }
  }
  if (map_path.empty()) return usage();

  vismap::Scene scene;
  try {
    scene = vismap::read_scene(scene_path);
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return 2;
  }
  std::ifstream in(map_path, std::ios::binary);
  if (!in) {
    std::cerr << map_path << ": cannot open\n";
    return 2;
  }
  std::stringstream text;
  text << in.rdbuf();

  vismap_check::Report rep = vismap_check::check_map(scene, text.str(), opt);
  for (const std::string& f : rep.failures) std::cout << "FAIL " << f << "\n";
  std::cout << (rep.ok ? "OK" : "FAILED") << ": " << rep.samples_checked << " region samples, "
            << rep.segment_points_checked << " segment points, " << rep.edge_points_checked << " edge points checked\n";
  return rep.ok ? 0 : 1;
}
