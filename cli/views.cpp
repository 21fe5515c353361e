#include "cli/views.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "cli/camera_options.h"
#include "engine/threads.h"

namespace vismap::cli {
namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string vec(const Vec3& v) { return number(v.x) + "," + number(v.y) + "," + number(v.z); }

// cos and sin of k/n of a turn: exact at the quarter turns (so that orbit:4
// looks along the axes' planes exactly), else the library's.
std::pair<double, double> turn(int k, int n) {
  if ((4 * k) % n == 0) {
    static const double c[4] = {1, 0, -1, 0}, s[4] = {0, 1, 0, -1};
    const int q = (4 * k / n) % 4;
    return {c[q], s[q]};
  }
  const double a = 2 * std::numbers::pi * k / n;
  return {std::cos(a), std::sin(a)};
}

std::vector<NamedView> orbit(const std::string& args) {
  const std::size_t comma = args.find(',');
  const std::string refusal = "orbit:N[,ELEVATION] takes a whole number of views N from 1 to 100000 and an "
                              "elevation strictly between -90 and 90 degrees, got 'orbit:" + args + "'";
  double n = 0, elevation = 30;
  try {
    n = parse_number("orbit", args.substr(0, comma));
    if (comma != std::string::npos) elevation = parse_number("orbit", args.substr(comma + 1));
  } catch (const std::invalid_argument&) {
    throw std::invalid_argument(refusal);
  }
  if (n < 1 || n > 100000 || n != std::floor(n) || elevation <= -90 || elevation >= 90) throw std::invalid_argument(refusal);
  std::vector<NamedView> out;
  const double e = elevation * std::numbers::pi / 180;
  const double ce = elevation == 0 ? 1 : std::cos(e), se = elevation == 0 ? 0 : std::sin(e);
  for (int k = 0; k < static_cast<int>(n); ++k) {
    const auto [ca, sa] = turn(k, static_cast<int>(n));
    NamedView v;
    v.camera.dir = Vec3{0 - ce * ca, 0 - ce * sa, 0 - se};   // (0 - x: no "-0" in the options)
    v.options = "--dir " + vec(*v.camera.dir);
    out.push_back(std::move(v));
  }
  return out;
}

// One line of a views file: the camera options it gives.
NamedView camera_line(const std::string& line, const std::string& where) {
  std::istringstream words(line);
  std::string opt, value;
  NamedView v;
  while (words >> opt) {
    if (!(words >> value)) throw InputError(where + ": " + opt + " needs a value");
    try {
      set_camera_option(v.camera, opt, value);
    } catch (const std::invalid_argument& e) {
      throw InputError(where + ": " + e.what());
    }
    v.options += (v.options.empty() ? "" : " ") + opt + " " + value;
  }
  return v;
}

std::vector<NamedView> views_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the views file");
  std::vector<NamedView> out;
  std::string line;
  for (std::size_t n = 1; std::getline(in, line); ++n) {
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    out.push_back(camera_line(line, path + ":" + std::to_string(n)));
  }
  if (out.empty()) throw InputError(path + ": no view in the views file (one camera per line, e.g. --dir -1,-2,-3)");
  return out;
}

bool first_angle(const std::string& spec) {
  if (spec == "sheet" || spec == "sheet:first") return true;
  if (spec == "sheet:third") return false;
  throw std::invalid_argument("a sheet is sheet, sheet:first or sheet:third, got '" + spec + "'");
}

// Front, top, right and isometric, in their cells: first-angle puts the top view
// under the front one and the right view left of it; third-angle above and right.
std::vector<NamedView> sheet(const std::string& spec) {
  const bool first = first_angle(spec);
  struct Cell {
    const char* label;
    Vec3 dir;
    std::optional<Vec3> up;
    int row, col;
  };
  const Cell cells[4] = {
      {"FRONT", {0, 1, 0}, std::nullopt, first ? 0 : 1, first ? 1 : 0},
      {"TOP", {0, 0, -1}, Vec3{0, 1, 0}, first ? 1 : 0, first ? 1 : 0},
      {"RIGHT", {-1, 0, 0}, std::nullopt, first ? 0 : 1, first ? 0 : 1},
      {"ISOMETRIC", {-1, 1, -1}, std::nullopt, first ? 1 : 0, first ? 0 : 1},
  };
  std::vector<NamedView> out;
  for (const Cell& c : cells) {
    NamedView v;
    v.camera.dir = c.dir;
    v.camera.up = c.up;
    v.options = "--dir " + vec(c.dir) + (c.up ? " --up " + vec(*c.up) : "");
    v.label = c.label;
    v.row = c.row;
    v.col = c.col;
    out.push_back(std::move(v));
  }
  return out;
}

}  // namespace

bool is_sheet(const std::string& spec) { return spec.rfind("sheet", 0) == 0 && (spec.size() == 5 || spec[5] == ':'); }

std::string sheet_note(const std::string& spec) {
  if (!is_sheet(spec)) return "";
  return first_angle(spec) ? "FIRST-ANGLE PROJECTION" : "THIRD-ANGLE PROJECTION";
}

std::vector<NamedView> parse_views(const std::string& spec) {
  if (is_sheet(spec)) return sheet(spec);
  if (spec.rfind("orbit:", 0) == 0) return orbit(spec.substr(6));
  return views_file(spec);
}

namespace {

// The field: "%d" or "%0Nd" at `at`, `len` characters long.
bool find_field(const std::string& p, std::size_t& at, std::size_t& len, int& width) {
  for (at = p.find('%'); at != std::string::npos; at = p.find('%', at + 1)) {
    std::size_t i = at + 1;
    width = 0;
    if (i < p.size() && p[i] == '0')
      for (++i; i < p.size() && p[i] >= '0' && p[i] <= '9' && width < 100; ++i) width = 10 * width + (p[i] - '0');
    if (i < p.size() && p[i] == 'd') {
      len = i + 1 - at;
      return true;
    }
  }
  return false;
}

}  // namespace

bool has_view_field(const std::string& pattern) {
  std::size_t at, len;
  int width;
  return find_field(pattern, at, len, width);
}

std::string view_file_name(const std::string& pattern, std::size_t k) {
  std::size_t at, len;
  int width;
  if (!find_field(pattern, at, len, width)) return pattern;
  std::string n = std::to_string(k);
  if (static_cast<int>(n.size()) < width) n.insert(0, static_cast<std::size_t>(width) - n.size(), '0');
  return pattern.substr(0, at) + n + pattern.substr(at + len);
}

int views_side_by_side(std::size_t views, int threads, std::size_t faces, std::uint64_t max_memory) {
  if (faces >= engine::kFewFaces) return 1;
  std::uint64_t most = std::min<std::uint64_t>({views, static_cast<std::uint64_t>(std::max(threads, 1)), 16});
  if (max_memory != 0) most = std::min(most, max_memory / (kBytesPerFace * std::max<std::uint64_t>(faces, 1)));
  return most < 2 ? 1 : static_cast<int>(most);
}

}  // namespace vismap::cli
