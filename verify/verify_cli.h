// `vismap verify SCENE MAP.json [options]`: the command line of the checker.
// Shared by build/vismap (as its `verify` subcommand) and the old stand-alone
// tool name; GMP and the readers only, no engine code.
#pragma once
#include <string>
#include <vector>

namespace vismap_check {

extern const char* const kVerifyHelp;

// `args` are the words after "verify". Prints the report on standard output and
// problems with the input on standard error. Returns the exit status: 0 the map
// holds, 1 it does not (or the scene or the map cannot be read), 2 bad usage.
int verify_command(const std::vector<std::string>& args);

}  // namespace vismap_check
