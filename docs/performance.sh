#!/usr/bin/env bash
# Reruns the benchmark tables of docs/performance.md that the benchmarks write themselves
# (--markdown): each replaces its own section (same device, same command) and leaves the others.
# On a GPU the largest grid goes first: the GPU leaves its idle clock only under load.
#   docs/performance.sh [gpu|lavapipe] [path/to/motionfx]   (default: lavapipe build/apps/motionfx)
set -euo pipefail
cd "$(dirname "$0")/.."
mkdir -p out
profile=${1:-lavapipe}
MOTIONFX=${2:-build/apps/motionfx}
out=docs/performance.md
plots=docs/images
case "$profile" in
gpu)
    # The solver: the largest grid first; the store paths side by side; multigrid's pressure.
    "$MOTIONFX" bench solver --grids 256,192,128,96,64,32 --steps 20 --markdown "$out" \
        --plot "$plots/bench_solver_roofline_gpu.svg" --json out/bench_solver_gpu.json
    "$MOTIONFX" bench solver --grids 256,128,64 --steps 20 --store buffer --markdown "$out"
    # The Jacobi solve's first sweep in its own pass instead of the divergence pass.
    "$MOTIONFX" bench solver --grids 256,128,64 --steps 20 --first-sweep-in-divergence off \
        --markdown "$out"
    "$MOTIONFX" bench solver --grids 256,128,64 --steps 10 --pressure multigrid --markdown "$out"
    # The multigrid's by-device choices the other way: the lavapipe coarse workgroup (8), the
    # residual pass before the restriction; then MGPCG.
    "$MOTIONFX" bench solver --grids 256,128,64 --steps 10 --pressure multigrid --coarse-group 8 \
        --markdown "$out"
    "$MOTIONFX" bench solver --grids 256,128,64 --steps 10 --pressure multigrid \
        --residual-in-restriction off --markdown "$out"
    "$MOTIONFX" bench solver --grids 256,128,64 --steps 10 --pressure mgpcg --markdown "$out"
    # Time to a divergence 1e-3 of the start at 128^3 (printed; not a Markdown section yet).
    "$MOTIONFX" bench accuracy --grid 16 --steps 4 --scenarios puff --target-grid 128 \
        --csv out/bench_accuracy_gpu.csv --plot out/bench_accuracy_gpu.svg
    # Frames: the hero frame at 1920x1080 and 960x540; the sparse kick against the dense grid.
    "$MOTIONFX" bench frame --size 1920x1080 --frames 60 --markdown "$out"
    # A per-sample cost (the rasteriser's, the ROPs') falls about 4x with one sample.
    "$MOTIONFX" bench frame --size 1920x1080 --frames 60 --samples 1 --markdown "$out"
    "$MOTIONFX" bench frame --frames 60 --markdown "$out"
    "$MOTIONFX" bench frame docs/scenes/smoke.json --sparse 256 --frames 60 --markdown "$out"
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
