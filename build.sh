#!/usr/bin/env bash
# One entry point for set-up, build and run on Debian 12 (as root, or as a user with sudo).
#
#   ./build.sh run    install missing packages, build, render the built-in default into out/
#   ./build.sh test   install missing packages, build, run the whole test suite (ctest), then
#                     build and run it again with AddressSanitizer + UndefinedBehaviorSanitizer
#   ./build.sh deps   only install the missing packages
#   ./build.sh build  install and build (build/), nothing else
#   ./build.sh fuzz [seconds]
#                     build the libFuzzer harnesses with clang (build-fuzz/) and run each for
#                     `seconds` (default 60) on the seed corpus; findings land in build-fuzz/findings
#
# Environment: MOTIONFX_JOBS (default 2) build jobs; MOTIONFX_SKIP_ASAN=1 skips the sanitizer pass
# of `test`; MOTIONFX_BUILD_DIR (default build) the build directory.
set -euo pipefail

cd "$(dirname "$0")"
ROOT=$(pwd)
JOBS=${MOTIONFX_JOBS:-2}
BUILD_DIR=${MOTIONFX_BUILD_DIR:-build}

PACKAGES=(
    cmake make g++ pkg-config
    libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers glslang-tools
    libglm-dev libtinygltf-dev nlohmann-json3-dev libeigen3-dev libgtest-dev libstb-dev
    libglfw3-dev libimgui-dev libx11-dev xvfb ffmpeg
    libopenvdb-dev libboost-iostreams-dev python3-openvdb python3-pil python3-numpy openexr godot3-runner
)

# The fuzzers need clang and its libFuzzer runtime; only `fuzz` installs them.
FUZZ_PACKAGES=(clang libclang-rt-dev)

say() { printf '\n== %s\n' "$*"; }

# install_dependencies [package...]: the given packages (default: PACKAGES) that are missing.
install_dependencies() {
    local wanted=("$@")
    [ ${#wanted[@]} -gt 0 ] || wanted=("${PACKAGES[@]}")
    local missing=()
    for package in "${wanted[@]}"; do
        if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
            missing+=("$package")
        fi
    done
    if [ ${#missing[@]} -eq 0 ]; then
        return 0
    fi
    say "installing ${missing[*]}"
    local sudo=()
    if [ "$(id -u)" -ne 0 ]; then
        if command -v sudo >/dev/null 2>&1; then
            sudo=(sudo)
        else
            echo "build.sh: missing packages (${missing[*]}) and not root; run as root or install sudo" >&2
            exit 1
        fi
    fi
    "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -q
    "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends \
        "${missing[@]}"
}

# Each stage's wall time, printed as a table at the end of `test` (and `fuzz`).
STAGE_NAMES=()
STAGE_SECONDS=()
# stage NAME COMMAND...: runs COMMAND, recording how long it took under NAME.
stage() {
    local name=$1
    shift
    local start=$SECONDS
    "$@"
    STAGE_NAMES+=("$name")
    STAGE_SECONDS+=($((SECONDS - start)))
}
stage_table() {
    say "stage times"
    local total=0
    for i in "${!STAGE_NAMES[@]}"; do
        printf '  %-28s %6d s\n' "${STAGE_NAMES[$i]}" "${STAGE_SECONDS[$i]}"
        total=$((total + STAGE_SECONDS[i]))
    done
    printf '  %-28s %6d s\n' "total" "$total"
}

# build DIR [cmake arguments...] [-- build targets...]
build() {
    local dir=$1
    shift
    local configure=() targets=()
    while [ $# -gt 0 ] && [ "$1" != "--" ]; do
        configure+=("$1")
        shift
    done
    [ $# -gt 0 ] && shift
    targets=("$@")
    say "configuring and building in $dir${targets[*]:+ (${targets[*]})}"
    cmake -S "$ROOT" -B "$dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo "${configure[@]}"
    if [ ${#targets[@]} -gt 0 ]; then
        cmake --build "$dir" -j "$JOBS" --target "${targets[@]}"
    else
        cmake --build "$dir" -j "$JOBS"
    fi
}

run_tests() {
    local dir=$1
    shift
    say "running the tests in $dir"
    # Each test is a process of its own; two at a time on the 2-core CI machine.
    ctest --test-dir "$dir" --output-on-failure -j "$JOBS" --timeout 600 "$@"
}

# The sanitizer pass runs what handles input and host memory: every test but the long GPU-bound
# runs below, each already run in the normal pass (the sanitizers check our host code, and these
# spend their time in lavapipe and the validation layer, which are not instrumented). The host
# code each of them drives runs sanitized in the short tests that stay (named with each).
SANITIZER_EXCLUDED=(
    # 2,000 solver steps per hard case, GPU and CPU reference; stages alone: Stages/FluidStageTest
    '^FluidStability/'
    # 100 whole steps per scenario, and the convergence study; stages alone as above
    '^Scenarios/' 'TaylorGreen'
    # the kick through a cloud: 30 reference steps at 24³; the solids' stages: the other FluidSolids
    '^FluidSolids[.]TheKick'
    # solids on the GPU over many steps (2,000-step hard cases, 100 steps, the kick, the spheres,
    # both store paths, split and whole stages) and their fp16 and corrected-advection stage
    # variants; the solids' host code (setSolids, the mark's recording, the split dispatches, the
    # bindings): GpuSolids/GpuSolidsStageTest's fp32 stages, GpuSolidsTest.RemovedSolids...,
    # .BadSolids... and .TheStagesAreSplit...
    '^GpuSolids/GpuSolidsHardCaseTest' '^GpuSolids/GpuSolidsStageTest[.].*(_fp16|maccormack|bfecc)'
    '^GpuSolidsTest[.](HundredSteps|EveryPressureSolver|BothStorePaths|SplitStages|TheKick|AMovingSphere|AStillSphere)'
    # a scene's kick with and without collision, 36 frames each; the scene's solids' set-up and
    # steps: SceneCollideTest.CollideBones...
    '^SceneCollideTest[.]TheKicks'
    # the impact's burst into a 48³ grid, twelve frames twice; the burst's host code
    # (recordBursts, its barriers) runs sanitized in Scenes/SyncValidation's versus scene
    '^ImpactGpu[.]AHitBurstsIntoTheSmoke'
    # the sparse solver's 100- and 2,000-step runs; its bookkeeping: SparseBricks, Stages/SparseStage
    '^SparseSolverTest[.].*For(100|2000)Steps'
    # solids on the sparse grid over many steps (the 2,000-step hard cases, 100 steps, the kick);
    # their host code (setSolids, the mark's recording, the rebuild's solid pass):
    # Stages/SparseSolidsStageTest, SparseSolidsTest.TheRebuild... and .AGridWithSolidsSettles...
    '^SparseSolids/SparseSolidsHardCaseTest' '^SparseSolidsTest[.](HundredSteps|TheKick)'
    # pressure and advection solvers against the reference over many sizes, steps and tolerances;
    # their set-up and dispatches: the stage tests (Stages/, GpuAdvection/GpuAdvectionStageTest)
    '^GpuPressureTest[.]' '^GpuPressure/' '^GpuAdvection/GpuAdvectionStepsTest' '^FluidAccuracy'
    '^FluidInvariant.*Gpu[.]'
    # the store paths compared over ten steps and over every option set; the direct path's host
    # code (its bindings, the fused vorticity pass): Fluid/StorePathTest.EveryStage.../mixed
    '^Fluid/StorePathTest[.]TenSteps' '^Fluid/StorePathTest[.]EveryStage.*/(closed|fp16|maccormack|multigrid)'
    # the first Jacobi sweep in the divergence pass, compared over steps on every option set; its
    # host code (both outputs, the solve starting at its second sweep): .../mixed and .../one_sweep
    '^Fluid/FirstSweepTest[.].*/(walls|open|periodic|fp16|direct_store|buffer_store|substeps)'
    # the half-storage and corrected-advection variants of each stage against the reference; the
    # stage's set-up, dispatch and readback: Stages/FluidStageTest, Stages/SparseStageTest
    '^GpuHalf/' '^GpuAdvection/'
    # whole scenes simulated for their numbers (smoke against a dense grid, scenarios, 30/60 fps);
    # a scene's set-up and frames: SceneSimulationTest's short tests, Scenes/SyncValidation
    '^SparseSceneTest[.]' '^SceneScenarioTest[.]' 'ThirtyAndSixtyFramesPerSecondAgree'
    # golden images: drawing compared to pictures; each pass's host code: its own pass tests
    '^GoldenImage[.]'
    # 200 random panel edits, each re-creating a scene's GPU resources and drawing it; the edits
    # themselves: SceneDocument, PanelWidgets and the fuzz corpus (every seed's tables)
    '^PanelEdits[.]'
    # an H.264 video of rendered frames (ffmpeg's work); the program's render path:
    # Cli.RenderWritesNumberedFramesWithValidationClean
    'RenderWritesAnH264Video'
    # the fighter framed again at 1/100 and 50 times its size; scaling: CharacterScale, and the
    # framing of every other character stays
    'CharacterFraming[.].*/fighter_x'
    # a hang guard over 64 effects and 100,000 frames (it runs in the normal pass); the bounded
    # sampling it guards: HostileScene.LiveSampledFramesAreBoundedAndSpanTheWindow
    'LongSceneWithManyAutomaticEffects'
    # the install and a separate project built against it (cmake and the compiler, which the
    # preloaded sanitizer runtime would instrument), and that project's program run (it is not
    # built with the sanitizers); the library's entry points: RuntimeApi.*, RuntimeFrame.*
    '^RuntimeInstall[.]' '^RuntimeExample[.]'
    # the runtime's frames against the program's, 21 frames each side; the runtime's frame
    # recording and its refusals: RuntimeFrame.BadTargets..., RuntimeFrame.TheTimeCannotGoBack
    '^RuntimeFrame[.](OverTheProgramsPicture|WithFourSamples)'
    # flipbook sheets read by third-party programs (Pillow, OpenEXR's tools, Godot 3), which run
    # without the sanitizers; the bake's own code: the other Bake tests and Flipbook*, SixWay*
    '^Bake[.](ADebianImageReader|GodotDraws)'
    # benchmarks run as the program (GPU timings); their bad values and refusals stay
    # (Cli.Bench*BadValuesAreOneLine, Cli.BenchEffectsRefuses*)
    '^Cli[.]Bench.*(Prints|Writes)'
)

run_sanitized_tests() {
    local exclude
    exclude=$(IFS='|'; echo "${SANITIZER_EXCLUDED[*]}")

    # The loader unloads the Vulkan driver and the validation layer before exit, which leaves
    # LeakSanitizer unable to tell their memory from ours. Preloading both keeps them mapped:
    # lavapipe's memory then stays reachable, and the validation layer's own leaks are
    # suppressed by name (tests/sanitizers/lsan.supp). Any other leak fails the test.
    LD_PRELOAD="$(g++ -print-file-name=libasan.so) libVkLayer_khronos_validation.so libvulkan_lvp.so" \
    ASAN_OPTIONS=abort_on_error=1:detect_leaks=1 \
    LSAN_OPTIONS="suppressions=$ROOT/tests/sanitizers/lsan.supp:print_suppressions=0" \
    UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
        run_tests "$BUILD_DIR-asan" -E "$exclude"
}

# fuzz SECONDS: builds the harnesses of tests/fuzz with clang and runs each for SECONDS.
fuzz() {
    local seconds=$1
    local dir="$BUILD_DIR-fuzz"
    CC=clang CXX=clang++ build "$dir" -DMOTIONFX_FUZZ=ON -DMOTIONFX_BUILD_TESTS=OFF \
        -DMOTIONFX_BUILD_APPS=OFF -- motionfx_fuzz_gltf motionfx_fuzz_scene motionfx_fuzz_png
    local -A seeds=(
        [gltf]="$ROOT/tests/fuzz/corpus/gltf $ROOT/../shared/gltf-bad $ROOT/../shared/assets"
        [scene]="$ROOT/tests/fuzz/corpus/scene $ROOT/docs/scenes"
        [png]="$ROOT/tests/fuzz/corpus/png $ROOT/docs/scenes/gallery/textures"
    )
    for harness in gltf scene png; do
        # New inputs go to the first folder (kept between runs); the seeds are read only.
        local corpus="$dir/corpus/$harness" findings="$dir/findings/$harness/"
        mkdir -p "$corpus" "$findings"
        local existing=()
        for folder in ${seeds[$harness]}; do
            [ -d "$folder" ] && existing+=("$folder")
        done
        say "fuzzing $harness for $seconds s (new inputs: $corpus; findings: $findings)"
        # -timeout: an input taking 10 s is a hang; -rss_limit_mb: past 2 GB is unbounded memory.
        ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
            "$dir/tests/fuzz/motionfx_fuzz_$harness" -max_total_time="$seconds" -timeout=10 \
            -rss_limit_mb=2048 -dict="$ROOT/tests/fuzz/$harness.dict" -artifact_prefix="$findings" \
            -print_final_stats=1 "$corpus" "${existing[@]}"
    done
}

command=${1:-run}
case "$command" in
deps)
    install_dependencies
    ;;
build)
    install_dependencies
    build "$BUILD_DIR"
    ;;
run)
    install_dependencies
    # Only the program: the test suite is built by `test`.
    build "$BUILD_DIR" -- motionfx
    say "rendering the built-in default into out/"
    "$BUILD_DIR/apps/motionfx" render --out out
    ;;
test)
    stage "install packages" install_dependencies
    stage "build" build "$BUILD_DIR"
    stage "tests" run_tests "$BUILD_DIR"
    if [ "${MOTIONFX_SKIP_ASAN:-0}" != 1 ]; then
        stage "build (sanitizers)" build "$BUILD_DIR-asan" -DMOTIONFX_SANITIZE=ON
        stage "tests (sanitizers)" run_sanitized_tests
    fi
    stage_table
    say "all tests passed"
    ;;
fuzz)
    seconds=${2:-60}
    if ! [[ "$seconds" =~ ^[0-9]+$ ]] || [ "$seconds" -lt 1 ]; then
        echo "build.sh fuzz: seconds must be a whole number >= 1, got '$seconds'" >&2
        exit 2
    fi
    stage "install packages" install_dependencies "${PACKAGES[@]}" "${FUZZ_PACKAGES[@]}"
    stage "fuzz" fuzz "$seconds"
    stage_table
    ;;
*)
    echo "usage: ./build.sh [run|test|deps|build|fuzz [seconds]]" >&2
    exit 2
    ;;
esac
