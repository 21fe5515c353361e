#!/usr/bin/env bash
# Builds everything with AddressSanitizer + UndefinedBehaviorSanitizer in its own
# folder (build-asan/) and runs the whole test suite there (.ci/run calls this
# after scripts/test.sh). Any sanitizer report fails the test that made it.
#   scripts/test-sanitize.sh [ctest arguments...]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
# -O1 -g1 (line tables: every report still names file and line) and no
# points-to analysis: with it, GCC took ~13 of this build's minutes on
# engine/screen_scene.cpp alone (-ftime-report: tree PTA 646 of 785 s; these
# flags: 303 s). Neither changes what the sanitizers check.
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -fno-tree-pta" \
  -DVISMAP_SANITIZE=ON -DVISMAP_BENCH=OFF >/dev/null
cmake --build build-asan -j"$(nproc)"
export ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=1:strict_string_checks=1:check_initialization_order=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
# (Third-party memory held to the end of the process, named in scripts/lsan.supp.)
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/scripts/lsan.supp}
ctest --test-dir build-asan --output-on-failure -j"$(nproc)" "$@"
