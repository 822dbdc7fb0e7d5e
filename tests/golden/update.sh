#!/usr/bin/env bash
# Remakes the golden images from the program itself: the last frame of each docs/scenes/NAME.json
# at 160x90. Review every changed picture by eye before committing it.
#   tests/golden/update.sh [path/to/motionfx]   (default: build/apps/motionfx)
set -euo pipefail
cd "$(dirname "$0")/../.."
MOTIONFX=${1:-build/apps/motionfx}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for name in none lines blur particles smoke all afterimage swept shell; do
    "$MOTIONFX" render "docs/scenes/$name.json" --size 160x90 --out "$work/$name" >/dev/null
    last=$(ls "$work/$name"/frame_*.png | sort | tail -n 1)
    cp "$last" "tests/golden/$name.png"
    echo "tests/golden/$name.png <- $last"
done
