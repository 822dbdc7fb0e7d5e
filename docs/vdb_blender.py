# Renders a frame of motionfx's OpenVDB smoke with Blender, beside the fighter, both taken in as an
# artist would (File > Import > glTF, Add > Volume > Import OpenVDB): the picture in the README's
# "Smoke as OpenVDB". Run by docs/vdb_blender.sh:
#   blender -b -P docs/vdb_blender.py -- FIGHTER.gltf SMOKE.vdb OUT.png FRAME
# The .vdb is written with --vdb-up z, so it lines up with Blender's glTF import without a
# transform; the camera is the scene's (docs/scenes/smoke.json), turned the same way.
import math
import os
import sys

import bpy
import numpy
from mathutils import Vector

# Debian's Blender 3.4 glTF importer still says numpy.bool, which Debian's numpy 1.24 dropped.
if "bool" not in numpy.__dict__:
    numpy.bool = bool

gltf, vdb, out, frame = sys.argv[sys.argv.index("--") + 1:][:4]
frame = int(frame)

bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
scene.render.fps = 30  # the scene's; the glTF importer keys its clips at this rate

bpy.ops.import_scene.gltf(filepath=gltf)
kick = next(a for a in bpy.data.actions if a.name.startswith("roundhouse_kick"))
for ob in scene.objects:
    if ob.type == "ARMATURE":
        ob.animation_data_create()
        ob.animation_data.action = kick
        for track in list(ob.animation_data.nla_tracks):
            ob.animation_data.nla_tracks.remove(track)
start = int(kick.frame_range[0])
scene.frame_set(start + frame)

bpy.ops.object.volume_import(filepath=vdb, directory=os.path.dirname(vdb),
                             files=[{"name": os.path.basename(vdb)}])
smoke = next(ob for ob in scene.objects if ob.type == "VOLUME")
material = bpy.data.materials.new("motionfx smoke")
material.use_nodes = True
nodes, links = material.node_tree.nodes, material.node_tree.links
nodes.clear()
output = nodes.new("ShaderNodeOutputMaterial")
volume = nodes.new("ShaderNodeVolumePrincipled")
density = nodes.new("ShaderNodeAttribute")
density.attribute_name = "density"
colour = nodes.new("ShaderNodeAttribute")
colour.attribute_name = "colour"
scale = nodes.new("ShaderNodeMath")
scale.operation = "MULTIPLY"
scale.inputs[1].default_value = 40.0  # pigment alpha to extinction per metre
links.new(density.outputs["Fac"], scale.inputs[0])
links.new(scale.outputs["Value"], volume.inputs["Density"])
links.new(colour.outputs["Color"], volume.inputs["Color"])
links.new(volume.outputs["Volume"], output.inputs["Volume"])
smoke.data.materials.append(material)

bpy.ops.mesh.primitive_plane_add(size=8.0, location=(0.0, 0.0, 0.0))
floor = bpy.context.active_object
floor_material = bpy.data.materials.new("floor")
floor_material.diffuse_color = (0.32, 0.34, 0.38, 1.0)
floor_material.use_nodes = True
floor_material.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (
    0.32, 0.34, 0.38, 1.0)
floor.data.materials.append(floor_material)


def z_up(p):  # the scene's y-up point as Blender's glTF import turns it
    return Vector((p[0], -p[2], p[1]))


eye, target = z_up((2.0, 1.35, 2.7)), z_up((0.05, 0.88, 0.0))
camera_data = bpy.data.cameras.new("camera")
camera_data.sensor_fit = "VERTICAL"
camera_data.angle = math.radians(40.0)
camera = bpy.data.objects.new("camera", camera_data)
scene.collection.objects.link(camera)
camera.location = eye
camera.rotation_euler = (target - eye).to_track_quat("-Z", "Y").to_euler()
scene.camera = camera

sun_data = bpy.data.lights.new("key", type="SUN")
sun_data.energy = 3.0
sun = bpy.data.objects.new("key", sun_data)
scene.collection.objects.link(sun)
sun.rotation_euler = (math.radians(50.0), 0.0, math.radians(30.0))
scene.world = bpy.data.worlds.new("sky")
scene.world.color = (0.18, 0.2, 0.24)

scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = 48
scene.cycles.use_denoising = False
scene.render.resolution_x, scene.render.resolution_y = 640, 360
scene.render.filepath = out
bpy.ops.render.render(write_still=True)
print("rendered", out, "frame", scene.frame_current, "volume grids:",
      [g.name for g in smoke.data.grids])
