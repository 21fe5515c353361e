#!/usr/bin/env bash
# One command on a fresh Debian machine: install what is missing, build, and
# render the bundled example scene to build/example.svg (and its exact map).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)" --target vismap
build/vismap examples/boxes.off --dir -1,-2,-1.5 -o build/example.svg --json build/example.json
echo "wrote build/example.svg and build/example.json"
