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
    # Out of the idle clock first (a first grid measured from it reads several times slower).
    "$MOTIONFX" bench solver --grids 128,128 --steps 30 >/dev/null
    # The solver: the largest grid first; the store paths side by side; multigrid's pressure.
    "$MOTIONFX" bench solver --grids 256,192,128,96,64,32 --steps 20 --markdown "$out" \
        --plot "$plots/bench_solver_roofline_gpu.svg" --json out/bench_solver_gpu.json
    # Frames: the hero frame at 1920x1080 with the compute march (the GPU's), the fragment march
    # and one sample (a per-sample cost, the rasteriser's, falls about 4x with one sample).
    "$MOTIONFX" bench frame --size 1920x1080 --frames 60 --markdown "$out"
    "$MOTIONFX" bench frame --size 1920x1080 --frames 60 --smoke-march fragment --markdown "$out"
    "$MOTIONFX" bench frame --size 1920x1080 --frames 60 --samples 1 --markdown "$out"
    # The multigrid by device (bricks of 1, the coarse workgroup 1,024) against lavapipe's bricks
    # of 4, the residual pass before the restriction, a coarse workgroup of 256; then MGPCG.
    "$MOTIONFX" bench solver --grids 256,128,64 --steps 10 --pressure multigrid --markdown "$out"
    "$MOTIONFX" bench solver --grids 256,128,64 --steps 10 --pressure multigrid --brick 4 \
        --markdown "$out"
    "$MOTIONFX" bench solver --grids 256,128,64 --steps 10 --pressure multigrid \
        --residual-in-restriction off --markdown "$out"
    "$MOTIONFX" bench solver --grids 256,128,64 --steps 10 --pressure multigrid --coarse-group 256 \
        --markdown "$out"
    # The one-workgroup coarse cycle from lower levels (512 and 64 cells instead of 4,096).
    for cells in 512 64; do
        "$MOTIONFX" bench solver --grids 256,128,64 --steps 10 --pressure multigrid \
            --coarse-cells "$cells" --markdown "$out"
    done
    "$MOTIONFX" bench solver --grids 256,128,64 --steps 10 --pressure mgpcg --markdown "$out"
    # Time to a divergence 1e-3 of the start at 128^3 (printed; not a Markdown section yet).
    "$MOTIONFX" bench accuracy --grid 16 --steps 4 --scenarios puff --target-grid 128 \
        --target-solvers multigrid,mgpcg --csv out/bench_accuracy_gpu.csv \
        --plot out/bench_accuracy_gpu.svg
    # The default frame; the sparse kick against the dense grid; the store path and the first
    # sweep the other way.
    "$MOTIONFX" bench frame --frames 60 --markdown "$out"
    "$MOTIONFX" bench frame docs/scenes/smoke.json --sparse 256 --frames 60 --markdown "$out"
    "$MOTIONFX" bench solver --grids 256,128,64 --steps 20 --store buffer --markdown "$out"
    "$MOTIONFX" bench solver --grids 256,128,64 --steps 20 --first-sweep-in-divergence off \
        --markdown "$out"
    # The fighter's body as solids (docs/performance.md, "What solids cost"): without and with it,
    # stepped by turns, the stages whole (a GPU's default) and split.
    "$MOTIONFX" bench solver --grids 128,48 --steps 20 --solids both --markdown "$out"
    "$MOTIONFX" bench solver --grids 128,48 --steps 20 --solids both --solid-lists on \
        --markdown "$out"
    ;;
lavapipe)
    "$MOTIONFX" bench solver --grids 32,64,96,128 --markdown "$out" \
        --plot "$plots/bench_solver_roofline_lavapipe.svg"
    "$MOTIONFX" bench frame --frames 20 --markdown "$out"
    "$MOTIONFX" bench solver --grids 48 --steps 20 --solids both --markdown "$out"
    "$MOTIONFX" bench solver --grids 48 --steps 20 --solids both --solid-lists off \
        --markdown "$out"
    ;;
*)
    echo "usage: docs/performance.sh [gpu|lavapipe] [path/to/motionfx]" >&2
    exit 2
    ;;
esac
echo "updated $out; look at the tables before committing them"
