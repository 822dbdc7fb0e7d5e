#!/usr/bin/env bash
# One entry point for set-up, build and run on Debian 12 (as root, or as a user with sudo).
#
#   ./build.sh run    install missing packages, build, render the built-in default into out/
#   ./build.sh test   install missing packages, build, run the whole test suite (ctest), then
#                     build and run it again with AddressSanitizer + UndefinedBehaviorSanitizer
#   ./build.sh deps   only install the missing packages
#   ./build.sh build  install and build (build/), nothing else
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
    libopenvdb-dev libboost-iostreams-dev python3-openvdb
)

say() { printf '\n== %s\n' "$*"; }

install_dependencies() {
    local missing=()
    for package in "${PACKAGES[@]}"; do
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

# build DIR [extra cmake arguments...]
build() {
    local dir=$1
    shift
    say "configuring and building in $dir"
    cmake -S "$ROOT" -B "$dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo "$@"
    cmake --build "$dir" -j "$JOBS"
}

run_tests() {
    local dir=$1
    shift
    say "running the tests in $dir"
    # Each test is a process of its own; two at a time on the 2-core CI machine.
    ctest --test-dir "$dir" --output-on-failure -j "$JOBS" --timeout 600 "$@"
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
    build "$BUILD_DIR"
    say "rendering the built-in default into out/"
    "$BUILD_DIR/apps/motionfx" render --out out
    ;;
test)
    install_dependencies
    build "$BUILD_DIR"
    run_tests "$BUILD_DIR"
    if [ "${MOTIONFX_SKIP_ASAN:-0}" != 1 ]; then
        build "$BUILD_DIR-asan" -DMOTIONFX_SANITIZE=ON
        # The long numerical solver runs (thousands of steps of arithmetic on fixed-size arrays,
        # no input from outside) take most of the sanitizer pass's time and run in the normal
        # pass above; everything else, bad-input tests included, runs under the sanitizers (the
        # sparse solver's host code too: its short tests grow, refuse and rebuild the same way).
        ASAN_EXCLUDE='^FluidStability/|^Scenarios/|TaylorGreen|^SparseSolverTest[.].*For(100|2000)Steps'

        # The loader unloads the Vulkan driver and the validation layer before exit, which leaves
        # LeakSanitizer unable to tell their memory from ours. Preloading both keeps them mapped:
        # lavapipe's memory then stays reachable, and the validation layer's own leaks are
        # suppressed by name (tests/sanitizers/lsan.supp). Any other leak fails the test.
        LD_PRELOAD="$(g++ -print-file-name=libasan.so) libVkLayer_khronos_validation.so libvulkan_lvp.so" \
        ASAN_OPTIONS=abort_on_error=1:detect_leaks=1 \
        LSAN_OPTIONS="suppressions=$ROOT/tests/sanitizers/lsan.supp:print_suppressions=0" \
        UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
            run_tests "$BUILD_DIR-asan" -E "$ASAN_EXCLUDE"
    fi
    say "all tests passed"
    ;;
*)
    echo "usage: ./build.sh [run|test|deps|build]" >&2
    exit 2
    ;;
esac
