// The exact map as JSON, exactly as ../shared/spec/vismap-json.md prescribes.
#pragma once
#include <functional>
#include <string>

#include "arrangements/visibility_map.h"

namespace vismap {

std::string to_json(const VisibilityMap& map);

// The same text in pieces of a few MB, each handed to `sink` in order: a map of
// 10^6 faces has about a GB of it, which then never lies in memory whole.
void write_json(const VisibilityMap& map, const std::function<void(const std::string&)>& sink);

}  // namespace vismap
