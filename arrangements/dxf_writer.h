// The drawing as DXF (AutoCAD R12, ASCII), for CAD: one layer per line class
// (hidden lines on a layer with the HIDDEN linetype), each chain a LINE (two
// points) or a POLYLINE, in screen units (orthographic: world units) at 1:1.
#pragma once
#include <string>

#include "arrangements/drawing.h"

namespace vismap {

std::string to_dxf(const Drawing& drawing);

}  // namespace vismap
