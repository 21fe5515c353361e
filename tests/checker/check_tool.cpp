// vismap_check_tool SCENE MAP.json [options]: the old name of `vismap verify`.
#include <string>
#include <vector>

#include "verify/verify_cli.h"

int main(int argc, char** argv) {
  return vismap_check::verify_command(std::vector<std::string>(argv + 1, argv + argc));
}
