#!/bin/sh
# run.sh BUILD_DIR CONSUMER_SOURCE VISMAP_BIN SCENE: installs the package from
# BUILD_DIR into a temporary prefix, builds the consumer project against it
# (shared and static), and checks that both write the command line's JSON.
set -eu
build=$1 src=$2 bin=$3 scene=$4
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/prefix" >/dev/null
# What the package hands its users names none of the engine's internals.
if grep -rlE "exact_config|#include *<(CGAL|gmp|boost)|CGAL::" "$tmp/prefix/include" "$tmp/prefix/lib/cmake/vismap"; then
  echo "the installed package exposes the engine's configuration" >&2
  exit 1
fi
cmake -S "$src" -B "$tmp/build" -DCMAKE_PREFIX_PATH="$tmp/prefix" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$tmp/build" -j2 >/dev/null
"$bin" "$scene" --dir -1,-2,-3 --json "$tmp/cli.json"
for exe in consumer consumer_static; do
  "$tmp/build/$exe" "$scene" "$tmp/$exe.json"
  cmp "$tmp/cli.json" "$tmp/$exe.json"
done
echo "the consumer's maps (shared and static) are the command line's"
