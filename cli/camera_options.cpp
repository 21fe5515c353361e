#include "cli/camera_options.h"

#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <vector>

namespace vismap::cli {

double parse_number(const std::string& opt, const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(v))
    throw std::invalid_argument(opt + " expects a finite number, got '" + text + "'");
  return v;
}

Vec3 parse_vec3(const std::string& opt, const std::string& text) {
  std::vector<double> v;
  for (std::size_t start = 0;;) {
    const std::size_t comma = text.find(',', start);
    v.push_back(parse_number(opt, text.substr(start, comma - start)));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (v.size() != 3) throw std::invalid_argument(opt + " expects X,Y,Z, got '" + text + "'");
  return {v[0], v[1], v[2]};
}

bool is_camera_option(const std::string& opt) {
  return opt == "--dir" || opt == "--eye" || opt == "--target" || opt == "--fov" || opt == "--up";
}

void set_camera_option(Camera& camera, const std::string& opt, const std::string& value) {
  if (opt == "--fov") camera.fov_deg = parse_number(opt, value);
  else if (opt == "--dir") camera.dir = parse_vec3(opt, value);
  else if (opt == "--eye") camera.eye = parse_vec3(opt, value);
  else if (opt == "--target") camera.target = parse_vec3(opt, value);
  else if (opt == "--up") camera.up = parse_vec3(opt, value);
  else throw std::invalid_argument("expected a camera option (--dir, --eye, --target, --fov, --up), found '" + opt + "'");
}

}  // namespace vismap::cli
