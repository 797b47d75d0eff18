#!/usr/bin/env bash
# Build the C++ drivers of examples/cpp into examples/cpp/build (CMake; the CGAL and
# OpenMesh drivers only where those libraries are installed; the log in build/build.log).
# Without cmake there is nothing to build: the rest of ddg-oracle does not need them.
set -uo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
if ! command -v cmake >/dev/null; then
    echo "examples/cpp: cmake is not installed, no C++ driver built"
    exit 0
fi
mkdir -p "$here/build"
log="$here/build/build.log"
if ! { cmake -S "$here" -B "$here/build" -DCMAKE_BUILD_TYPE=Release &&
       cmake --build "$here/build" -j 2; } > "$log" 2>&1; then
    tail -n 30 "$log" >&2
    echo "examples/cpp: the build failed (log: $log)" >&2
    exit 1
fi
grep '^-- ddg-oracle:' "$log" | sed 's/^-- ddg-oracle: /examples\/cpp: /'
for d in cotan_driver cgal_driver openmesh_driver; do
    if [ -x "$here/build/$d" ]; then echo "examples/cpp: built build/$d"; fi
done
