#!/usr/bin/env bash
# Reruns the benchmark tables of docs/performance.md that the benchmarks write themselves
# (--markdown): each replaces its own section (same device, same command) and leaves the others.
# On a GPU the largest grid goes first: the GPU leaves its idle clock only under load.
#   docs/performance.sh [gpu|lavapipe] [path/to/motionfx]   (default: lavapipe build/apps/motionfx)
set -euo pipefail
cd "$(dirname "$0")/.."
profile=${1:-lavapipe}
MOTIONFX=${2:-build/apps/motionfx}
out=docs/performance.md
plots=docs/images
case "$profile" in
gpu)
    "$MOTIONFX" bench solver --grids 256,192,128,96,64,32 --steps 20 --markdown "$out" \
        --plot "$plots/bench_solver_roofline_gpu.svg"
    "$MOTIONFX" bench solver --grids 256,128,64 --steps 10 --pressure multigrid --markdown "$out"
    "$MOTIONFX" bench frame --size 1920x1080 --frames 60 --markdown "$out"
    "$MOTIONFX" bench frame --frames 60 --markdown "$out"
    ;;
lavapipe)
    "$MOTIONFX" bench solver --grids 32,64,96,128 --markdown "$out" \
        --plot "$plots/bench_solver_roofline_lavapipe.svg"
    "$MOTIONFX" bench frame --frames 20 --markdown "$out"
    ;;
*)
    echo "usage: docs/performance.sh [gpu|lavapipe] [path/to/motionfx]" >&2
    exit 2
    ;;
esac
echo "updated $out; look at the tables before committing them"
