// The command line's numbers and camera options, parsed one way for the
// arguments and for a views file (cli/views.cpp). Errors are
// std::invalid_argument with the message the command line prints
// ("--dir expects X,Y,Z, got '0,0'").
#pragma once
#include <string>

#include "vismap/vismap.h"

namespace vismap::cli {

// A finite number, all of `text` (opt names it in the message).
double parse_number(const std::string& opt, const std::string& text);
// X,Y,Z: three of them.
Vec3 parse_vec3(const std::string& opt, const std::string& text);

// Whether `opt` is a camera option (--dir, --eye, --target, --fov, --up), and
// setting one on `camera` from its value.
bool is_camera_option(const std::string& opt);
void set_camera_option(Camera& camera, const std::string& opt, const std::string& value);

}  // namespace vismap::cli
