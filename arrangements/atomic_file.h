// Output files are written whole or not at all: to a temporary name in the same
// folder, renamed over the target only when complete. "-" means standard output.
#pragma once
#include <string>

namespace vismap {

// Throws std::runtime_error naming the file when it cannot be written.
void write_file_atomically(const std::string& path, const std::string& contents);

}  // namespace vismap
