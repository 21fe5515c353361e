// One reader per mesh format, all over bytes already in memory. Internal to
// vismap_io; read_scene.cpp picks one and fills Scene::file.
#pragma once
#include <string>
#include <string_view>

#include "engine/scene.h"

namespace vismap::io {

// Each appends to `out` (empty on entry) and throws InputError naming `name`.
void read_off(std::string_view bytes, const std::string& name, const ReadLimits& limits, Scene& out);
void read_obj(std::string_view bytes, const std::string& name, const ReadLimits& limits, Scene& out);
void read_stl(std::string_view bytes, const std::string& name, const ReadLimits& limits, Scene& out);
void read_ply(std::string_view bytes, const std::string& name, const ReadLimits& limits, Scene& out);
void read_vmscene(std::string_view bytes, const std::string& name, const ReadLimits& limits, Scene& out);

// Whether `word` is an OFF header read_off takes: OFF, or Geomview's variants
// whose vertex lines carry more values after x y z, which it ignores (ST texture
// coordinates, C a colour, N a normal, in that order: COFF, NOFF, CNOFF, STOFF,
// STCNOFF...). Not 4OFF or nOFF (homogeneous or other-dimensional vertices).
bool is_off_header(std::string_view word);

}  // namespace vismap::io
