#!/usr/bin/env bash
# Makes the README's gallery (docs/images/gallery/*.png) with the program itself: one frame of
# each scene in docs/scenes/gallery/ and of the default scene (docs/scenes/hero.json), at
# 400x225. Look at every picture before committing it.
#   docs/gallery.sh [path/to/motionfx]   (default: build/apps/motionfx)
set -euo pipefail
cd "$(dirname "$0")/.."
MOTIONFX=${1:-build/apps/motionfx}
out=docs/images/gallery
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# picture name, scene file, frame (30 fps: 12 is the kick's strike, 40 the slash's cut)
shots=(
    "before_kick docs/scenes/gallery/before.json 12"
    "after_kick docs/scenes/hero.json 12"
    "before_slash docs/scenes/gallery/before.json 40"
    "after_slash docs/scenes/hero.json 40"
    "style_lit docs/scenes/gallery/style_lit.json 40"
    "style_toon docs/scenes/gallery/style_toon.json 40"
    "smoke_smoke docs/scenes/gallery/smoke_smoke.json 20"
    "smoke_fire docs/scenes/gallery/smoke_fire.json 20"
    "smoke_energy docs/scenes/gallery/smoke_energy.json 20"
    "smoke_cel docs/scenes/gallery/smoke_cel.json 20"
    "ribbon_camera docs/scenes/gallery/ribbon_camera.json 40"
    "ribbon_blade docs/scenes/gallery/ribbon_blade.json 40"
    "ribbon_tube docs/scenes/gallery/ribbon_tube.json 40"
    "volume_rim docs/scenes/gallery/volume_rim.json 12"
    "particles_life docs/scenes/gallery/particles_life.json 42"
)
for shot in "${shots[@]}"; do
    read -r name scene frame <<<"$shot"
    "$MOTIONFX" render "$scene" --size 400x225 --frames $((frame + 1)) --out "$work/$name" >/dev/null
    cp "$work/$name/$(printf 'frame_%04d.png' "$frame")" "$out/$name.png"
    echo "$out/$name.png <- $scene, frame $frame"
done
