#include "arrangements/dxf_writer.h"

#include <string>

#include "arrangements/rational.h"

namespace vismap {
namespace {

// One group: its code, then its value, each on a line.
void group(std::string& out, int code, const std::string& value) {
  out += std::to_string(code);
  out += '\n';
  out += value;
  out += '\n';
}

std::string real(double v) { return general_text(v, 17); }

// AutoCAD colour index per class: outline white/black, crease blue,
// intersection red, smooth green, hidden grey.
int colour(LineClass c) {
  switch (c) {
    case LineClass::Crease: return 5;
    case LineClass::Intersection: return 1;
    case LineClass::Smooth: return 3;
    case LineClass::Hidden: return 8;
    default: return 7;
  }
}

void linetypes(std::string& out) {
  group(out, 0, "TABLE");
  group(out, 2, "LTYPE");
  group(out, 70, "2");
  group(out, 0, "LTYPE");
  group(out, 2, "CONTINUOUS");
  group(out, 70, "0");
  group(out, 3, "Solid line");
  group(out, 72, "65");
  group(out, 73, "0");
  group(out, 40, "0.0");
  group(out, 0, "LTYPE");
  group(out, 2, "HIDDEN");
  group(out, 70, "0");
  group(out, 3, "Hidden __ __ __");
  group(out, 72, "65");
  group(out, 73, "2");
  group(out, 40, "9.525");
  group(out, 49, "6.35");
  group(out, 49, "-3.175");
  group(out, 0, "ENDTAB");
}

void layers(std::string& out) {
  group(out, 0, "TABLE");
  group(out, 2, "LAYER");
  group(out, 70, std::to_string(kLineClasses + 1));
  group(out, 0, "LAYER");
  group(out, 2, "0");
  group(out, 70, "0");
  group(out, 62, "7");
  group(out, 6, "CONTINUOUS");
  for (std::size_t k = 0; k < kLineClasses; ++k) {
    const auto c = static_cast<LineClass>(k);
    group(out, 0, "LAYER");
    group(out, 2, class_name(c));
    group(out, 70, "0");
    group(out, 62, std::to_string(colour(c)));
    group(out, 6, c == LineClass::Hidden ? "HIDDEN" : "CONTINUOUS");
  }
  group(out, 0, "ENDTAB");
}

void vertex(std::string& out, const char* layer, const std::array<double, 2>& p) {
  group(out, 0, "VERTEX");
  group(out, 8, layer);
  group(out, 10, real(p[0]));
  group(out, 20, real(p[1]));
  group(out, 30, "0.0");
}

void entity(std::string& out, const Chain& c) {
  const char* layer = class_name(c.cls);
  if (c.screen.size() == 2 && !c.closed) {
    group(out, 0, "LINE");
    group(out, 8, layer);
    group(out, 10, real(c.screen[0][0]));
    group(out, 20, real(c.screen[0][1]));
    group(out, 30, "0.0");
    group(out, 11, real(c.screen[1][0]));
    group(out, 21, real(c.screen[1][1]));
    group(out, 31, "0.0");
    return;
  }
  group(out, 0, "POLYLINE");
  group(out, 8, layer);
  group(out, 66, "1");
  group(out, 10, "0.0");
  group(out, 20, "0.0");
  group(out, 30, "0.0");
  group(out, 70, c.closed ? "1" : "0");
  for (const auto& p : c.screen) vertex(out, layer, p);
  group(out, 0, "SEQEND");
  group(out, 8, layer);
}

}  // namespace

std::string to_dxf(const Drawing& drawing) {
  std::string out;
  group(out, 0, "SECTION");
  group(out, 2, "HEADER");
  group(out, 9, "$ACADVER");
  group(out, 1, "AC1009");
  group(out, 0, "ENDSEC");
  group(out, 0, "SECTION");
  group(out, 2, "TABLES");
  linetypes(out);
  layers(out);
  group(out, 0, "ENDSEC");
  group(out, 0, "SECTION");
  group(out, 2, "ENTITIES");
  for (const Chain& c : drawing.chains) entity(out, c);
  group(out, 0, "ENDSEC");
  group(out, 0, "EOF");
  return out;
}

}  // namespace vismap
