#!/usr/bin/env bash
# Runs one libFuzzer target for a given time, in its own clang build (build-fuzz/).
#
#   scripts/fuzz.sh TARGET [SECONDS] [extra libFuzzer flags...]
#   scripts/fuzz.sh all SECONDS        # every target in turn, SECONDS each
#
# TARGET: read_off, read_obj, read_stl, read_ply (one reader on arbitrary bytes)
# or pipeline (the whole engine on tiny scenes, every map checked by the
# independent exact checker). Seeds: tests/fuzz/corpus/TARGET (read only); what
# the fuzzer learns goes to build-fuzz/corpus/TARGET; crashes (a finding: the
# input, and on stderr the scene as OFF with the vismap command that fails) go
# to build-fuzz/findings/TARGET/. One process, in-process fuzzing (no -jobs):
# run targets one after another on a shared machine.
# Needs clang and libFuzzer (Debian: clang, libclang-rt-14-dev).
set -euo pipefail
cd "$(dirname "$0")/.."
target=${1:?usage: scripts/fuzz.sh TARGET|all [SECONDS] [libFuzzer flags]}
seconds=${2:-60}
shift $(( $# >= 2 ? 2 : 1 ))
targets=(read_off read_obj read_stl read_ply pipeline)
if [ "$target" = all ]; then
  for t in "${targets[@]}"; do "$0" "$t" "$seconds" "$@"; done
  exit 0
fi
case " ${targets[*]} " in *" $target "*) ;; *) echo "unknown target '$target'; one of: ${targets[*]} all" >&2; exit 2;; esac

command -v clang++ >/dev/null || { echo "fuzz.sh: clang++ is needed (apt-get install clang libclang-rt-14-dev)" >&2; exit 2; }
build=build-fuzz
if [ ! -f "$build/CMakeCache.txt" ]; then
  CC=clang CXX=clang++ cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" -DVISMAP_FUZZ=ON -DVISMAP_TESTS=OFF -DVISMAP_BENCH=OFF >/dev/null
fi
cmake --build "$build" -j"${FUZZ_BUILD_JOBS:-2}" --target "fuzz_$target" >/dev/null

mkdir -p "$build/corpus/$target" "$build/findings/$target"
dict=()
case $target in read_*) dict=(-dict="tests/fuzz/dict/${target#read_}.dict");; esac
max_len=()
[ "$target" = pipeline ] && max_len=(-max_len=200)
echo "fuzz.sh: $target for $seconds s" >&2
start=$(date +%s)
set +e
"$build/tests/fuzz/fuzz_$target" -max_total_time="$seconds" -timeout=30 -rss_limit_mb=2048 \
  -print_final_stats=1 -artifact_prefix="$build/findings/$target/" "${dict[@]}" "${max_len[@]}" "$@" \
  "$build/corpus/$target" "tests/fuzz/corpus/$target"
rc=$?
set -e
echo "fuzz.sh: $target ran $(( $(date +%s) - start )) s, exit $rc; findings in $build/findings/$target/" >&2
exit $rc
