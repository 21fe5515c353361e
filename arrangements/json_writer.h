// The exact map as JSON, exactly as docs/format.md prescribes.
#pragma once
#include <functional>
#include <string>

#include "arrangements/visibility_map.h"

namespace vismap {

std::string to_json(const VisibilityMap& map, int threads = 1);

// The same text in pieces of a few MB, each handed (moved) to `sink` in order: a map of
// 10^6 faces has about a GB of it, which then never lies in memory whole. Made on
// `threads` threads, and `sink` called from them, one call at a time (while the
// others make the next pieces); the text is the same for every count.
void write_json(const VisibilityMap& map, const std::function<void(std::string)>& sink, int threads = 1);

}  // namespace vismap
