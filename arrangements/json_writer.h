// The exact map as JSON, exactly as ../shared/spec/vismap-json.md prescribes.
#pragma once
#include <string>

#include "arrangements/visibility_map.h"

namespace vismap {

std::string to_json(const VisibilityMap& map);

}  // namespace vismap
