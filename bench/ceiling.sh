#!/usr/bin/env bash
# The ceiling tables of docs/PERFORMANCE.md: rayview's render time against plain Embree casting the same rays,
# at 1 and 2 threads, on the seven bench scenes (bench_scenes.py) and on all 16 conformance scenes; each table gives
# both shares, against Embree single rays and against Embree 16-wide camera packets.
# Usage: bench/ceiling.sh [BUILD_DIR] [SHARED_DIR]   (defaults: build/release, ../shared)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build/release}
shared=${2:-../shared}
bench="$build/bench/ceiling_bench"
[ -x "$bench" ] || { echo "build $bench first: cmake --build --preset release --target ceiling_bench" >&2; exit 1; }

c="$shared/conformance/ceng477"
p="$shared/peer-scenes/mertugr__mesh-trace/scenes"
seven=("$c/bunny.xml" "$c/car.xml" "$c/killeroo_2020.xml" "$c/dragon_lowres.xml" "$c/monkey.xml"
       "$p/grid_large.xml" "$p/mirror_scene.xml")
conformance=()
for f in "$c"/*.xml; do
  case "$f" in *.ceng477.xml) ;; *) conformance+=("$f") ;; esac
done

echo "machine: $(lscpu | sed -n 's/^Model name: *//p' | head -1), $(nproc) CPUs; $(date -u +%Y-%m-%d); commit $(git rev-parse --short HEAD)"
for threads in 1 2; do
  echo; echo "### The seven bench scenes, $threads thread(s)"; echo
  "$bench" --threads "$threads" --repeat 3 "${seven[@]}"
done
for threads in 1 2; do
  echo; echo "### All ${#conformance[@]} conformance scenes, $threads thread(s)"; echo
  "$bench" --threads "$threads" --repeat 3 "${conformance[@]}"
done
