#!/bin/sh
# Build and run the LCP benchmark (Release). Usage: benchmarks/lcp/run.sh [build-dir]
set -e
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../../build/bench-lcp}
cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build "$build" --parallel 2 > /dev/null
exec "$build/bench_lcp"
