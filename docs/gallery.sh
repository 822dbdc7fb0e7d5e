#!/usr/bin/env bash
# Makes the README's pictures of scenes with the program itself: the gallery
# (docs/images/gallery/*.png: one frame of each scene in docs/scenes/gallery/ and of the default
# scene, docs/scenes/hero.json, at 400x225), the default scene's frame at the top (640x360), the
# versus scene's frames (docs/images/versus/, 320x180, and one at 640x360) and the one-effect scenes of "The effects, one at a time" (docs/images/effect_*.png, 480x270). Look
# at every picture before committing it.
#   docs/gallery.sh [path/to/motionfx]   (default: build/apps/motionfx)
set -euo pipefail
cd "$(dirname "$0")/.."
MOTIONFX=${1:-build/apps/motionfx}
out=docs/images/gallery
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# picture name, scene file, frame (30 fps: 12 is the kick's strike, 44 the slash's upswing)
shots=(
    "before_kick docs/scenes/gallery/before.json 12"
    "after_kick docs/scenes/hero.json 12"
    "before_slash docs/scenes/gallery/before.json 44"
    "after_slash docs/scenes/hero.json 44"
    "style_lit docs/scenes/gallery/style_lit.json 40"
    "style_toon docs/scenes/gallery/style_toon.json 40"
    "smoke_smoke docs/scenes/gallery/smoke_smoke.json 20"
    "smoke_fire docs/scenes/gallery/smoke_fire.json 20"
    "smoke_energy docs/scenes/gallery/smoke_energy.json 20"
    "smoke_cel docs/scenes/gallery/smoke_cel.json 20"
    "smoke_cartoon docs/scenes/gallery/smoke_cartoon.json 20"
    "smoke_plain_30 docs/scenes/gallery/smoke_smoke.json 30"
    "smoke_turbulence docs/scenes/gallery/smoke_turbulence.json 30"
    "ribbon_camera docs/scenes/gallery/ribbon_camera.json 40"
    "ribbon_blade docs/scenes/gallery/ribbon_blade.json 40"
    "ribbon_tube docs/scenes/gallery/ribbon_tube.json 40"
    "ribbon_sheet docs/scenes/gallery/ribbon_sheet.json 40"
    "texture_stretch docs/scenes/gallery/texture_stretch.json 40"
    "texture_per_segment docs/scenes/gallery/texture_per_segment.json 40"
    "texture_tiled docs/scenes/gallery/texture_tiled.json 40"
    "texture_distance docs/scenes/gallery/texture_distance.json 40"
    "texture_erosion docs/scenes/gallery/texture_erosion.json 44"
    "volume_rim docs/scenes/gallery/volume_rim.json 12"
    "particles_life docs/scenes/gallery/particles_life.json 42"
)
# picture, scene file, frame, size
shot() {
    "$MOTIONFX" render "$2" --size "$4" --frames $(($3 + 1)) --out "$work/$1" >/dev/null
    cp "$work/$1/$(printf 'frame_%04d.png' "$3")" "$1.png"
    echo "$1.png <- $2, frame $3"
}
for entry in "${shots[@]}"; do
    read -r name scene frame <<<"$entry"
    shot "$out/$name" "$scene" "$frame" 400x225
done
shot docs/images/default_scene_frame44 docs/scenes/hero.json 44 640x360
for effect in lines:20 blur:20 particles:20 smoke:20 afterimage:20 swept:12 shell:16; do
    shot "docs/images/effect_${effect%%:*}" "docs/scenes/${effect%%:*}.json" "${effect##*:}" 480x270
done
# The versus scene as frames of its video (README "Hits"): one render at 320x180, six frames (the
# kick coming, the hit, the hit-stop's sparks, the rival knocked back, the slash).
"$MOTIONFX" render docs/scenes/versus.json --size 320x180 --frames 45 --out "$work/versus" >/dev/null
mkdir -p docs/images/versus
for f in 8 11 13 17 40 44; do
    cp "$work/versus/$(printf 'frame_%04d.png' "$f")" "docs/images/versus/frame_$f.png"
    echo "docs/images/versus/frame_$f.png <- docs/scenes/versus.json, frame $f"
done
shot docs/images/versus_frame13 docs/scenes/versus.json 13 640x360
# The viewer with its parameter panel (README "The parameter panel"), under a virtual X server.
xvfb-run -a -s "-screen 0 1400x1100x24" "$MOTIONFX" view --size 1280x1000 --quit-after 41 \
    --screenshot-panel --screenshot docs/images/view_panel.png >/dev/null
echo "docs/images/view_panel.png <- motionfx view (built-in default, frame 41, panel shown)"
