#!/bin/sh
# The README's picture of the program's OpenVDB smoke in a third-party reader: the kick's foot
# smoke on a sparse 256^3 domain written frame by frame with --vdb-up z, the built-in fighter
# exported as glTF, both imported into Blender (Debian's `blender`, not part of the set-up) and
# rendered with Cycles on the CPU by docs/vdb_blender.py. Run from the project root after a build.
set -eu
motionfx=${MOTIONFX:-build/apps/motionfx}
out=${OUT:-out/vdb_blender}
frame=20
mkdir -p "$out"
out=$(cd "$out" && pwd)
sed 's/"radius": 0.08}/"radius": 0.08, "domain": "sparse"}/' docs/scenes/smoke.json > "$out/scene.json"
"$motionfx" render "$out/scene.json" --out "$out/frames" --vdb "$out/vdb" --vdb-up z
"$motionfx" export-fighter "$out/fighter.gltf"
blender -b -P docs/vdb_blender.py -- "$out/fighter.gltf" \
    "$out/vdb/foot_smoke_$(printf %04d $frame).vdb" "$PWD/docs/images/vdb_blender.png" "$frame"
