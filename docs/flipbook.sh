#!/usr/bin/env bash
# Makes the README's flipbook pictures and figures ("Flipbooks for game engines") with the program
# itself, and prints the measurements quoted there. Look at every picture before committing it.
#   docs/flipbook.sh [path/to/motionfx]   (default: build/apps/motionfx)
set -euo pipefail
cd "$(dirname "$0")/.."
MOTIONFX=${1:-build/apps/motionfx}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
images=docs/images

# The built-in scene's effects, all of them, 24 cells of 128 pixels: the sheet over the preview's
# background, and its motion vectors.
"$MOTIONFX" bake --grid 6x4 --cell 128 --out "$work/all" >/dev/null
cp "$work/all/preview.png" "$images/bake_sheet.png"
cp "$work/all/motion.png" "$images/bake_motion.png"
echo "$images/bake_sheet.png, bake_motion.png <- motionfx bake --grid 6x4 --cell 128"

# The hero smoke's six-way maps and their check against direct light (128-pixel cells).
"$MOTIONFX" bake --effects "energy smoke" --grid 8x6 --cell 128 --range 3:50 --six-way \
    --evaluate 4 --motion none --out "$work/six" >/dev/null
cp "$work/six/six_way_preview.png" "$images/bake_six_way.png"
cp "$work/six/six_way_check.png" "$images/bake_six_way_check.png"
echo "$images/bake_six_way.png, bake_six_way_check.png <- the energy smoke, --six-way --evaluate 4"

# The figures: every frame baked (256-pixel cells), played at a quarter of the rate; the smoke
# with both kinds of motion vectors and its six-way check, then the slash's ribbons.
echo "== the energy smoke, scene frames 3 to 50, one a cell"
"$MOTIONFX" bake --effects "energy smoke" --grid 8x6 --cell 256 --range 3:50 --six-way \
    --evaluate 4 --out "$work/smoke" 2>/dev/null | grep -E "played at|six-way blend"
echo "== the slash arc, scene frames 27 to 50, one a cell"
"$MOTIONFX" bake --effects "slash arc" --grid 6x4 --cell 256 --range 27:50 --evaluate 4 \
    --out "$work/slash" 2>/dev/null | grep -E "played at"
