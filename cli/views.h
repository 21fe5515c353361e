// Many views in one run (vismap SCENE --views SPEC): the cameras a spec names,
// and each view's output file names. The scene is read once; each view is
// computed and written as a single run with its camera would be.
#pragma once
#include <string>
#include <vector>

#include "vismap/vismap.h"

namespace vismap::cli {

struct NamedView {
  Camera camera;
  std::string options;   // the camera as command-line options ("--dir 1,-2,0.5"), for messages
  std::string label;     // on a sheet: "FRONT", "TOP", "RIGHT", "ISOMETRIC"
  int row = -1, col = -1;   // on a sheet: its cell, from the top left; -1: no sheet
};

// SPEC is "sheet[:first|:third]" (a drawing sheet: front, looking along +y;
// top, along -z; right, along -x; and an isometric view from (1,-1,1), laid out
// in first-angle projection, the default, or third-angle), "orbit:N[,ELEVATION]" (N orthographic views around the scene's z
// axis, looking down at ELEVATION degrees, default 30: view k looks along
// -(cos e cos a, cos e sin a, sin e) with a = 360 k / N degrees), or a file of
// one camera per line in the command line's options (--dir, or --eye with
// --target and --fov; --up), '#' starting a comment. Throws
// std::invalid_argument (a spec) or InputError (the file, naming its line).
std::vector<NamedView> parse_views(const std::string& spec);

// What a sheet says of its projection ("FIRST-ANGLE PROJECTION"); empty when
// SPEC is not a sheet.
std::string sheet_note(const std::string& spec);

// The output name for view k: "%d" (or "%0Nd", zero-padded to N digits) in
// `pattern` replaced by k; false when the pattern has no such field.
bool has_view_field(const std::string& pattern);
std::string view_file_name(const std::string& pattern, std::size_t k);

}  // namespace vismap::cli
