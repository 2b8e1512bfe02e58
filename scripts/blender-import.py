# Imports a glTF binary into an empty Blender scene (headless) and reports what arrived: every
# mesh object, whether its material's base colour is an image texture with pixels, and the
# animations. With --render, renders the import with Cycles on the CPU from a camera that
# frames it, for docs/fracture.md.
#
#   blender -b --factory-startup --python scripts/blender-import.py -- FILE.glb \
#       [--render OUT.png --res WxH --samples N --time SECONDS \
#        --camera X,Y,Z --look-at X,Y,Z --fov DEG]   (camera in glTF's y-up coordinates)
#
# Prints one line `LAZYSOLID_BLENDER {json}` (Blender prints much else).
import json
import math
import sys

import numpy

# Blender 3.4's glTF importer still uses numpy.bool, which numpy 1.24 (Debian 12) removed.
if not hasattr(numpy, "bool"):
    numpy.bool = numpy.bool_

import bpy
import mathutils

args = sys.argv[sys.argv.index("--") + 1:]
path = args[0]
opts = dict(zip(args[1::2], args[2::2]))

bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=path)

meshes = [o for o in bpy.data.objects if o.type == "MESH"]
textured = []
for o in meshes:
    images = []
    for slot in o.material_slots:
        if slot.material and slot.material.use_nodes:
            for node in slot.material.node_tree.nodes:
                if node.type == "TEX_IMAGE" and node.image and node.image.size[0] > 0:
                    images.append(node.image.name)
    if images:
        textured.append(o.name)
report = {
    "file": path,
    "meshes": len(meshes),
    "textured_meshes": len(textured),
    "images": sum(1 for i in bpy.data.images if i.size[0] > 0),
    "animations": len(bpy.data.actions),
    "triangles": sum(sum(len(p.vertices) - 2 for p in o.data.polygons) for o in meshes),
}

keys = [k.co[0] for a in bpy.data.actions for c in a.fcurves for k in c.keyframe_points]
report["first_key_frame"] = min(keys) if keys else None
report["fps"] = bpy.context.scene.render.fps


def gltf_point(text):
    # A point in glTF's (lazysolid's) y-up coordinates, in Blender's z-up ones.
    x, y, z = (float(v) for v in text.split(","))
    return mathutils.Vector((x, -z, y))


if "--render" in opts:
    scene = bpy.context.scene
    if "--time" in opts and keys:
        # glTF time t (seconds) is frame first + t * fps in the import.
        f = min(keys) + float(opts["--time"]) * scene.render.fps
        scene.frame_set(int(f), subframe=f - int(f))
    bpy.context.view_layer.update()
    lo = mathutils.Vector((1e30, 1e30, 1e30))
    hi = -lo
    for o in meshes:
        for corner in o.bound_box:
            p = o.matrix_world @ mathutils.Vector(corner)
            lo = mathutils.Vector(map(min, lo, p))
            hi = mathutils.Vector(map(max, hi, p))
    centre = (lo + hi) / 2
    size = max((hi - lo).length, 1e-6)
    camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    scene.collection.objects.link(camera)
    if "--camera" in opts:
        camera.location = gltf_point(opts["--camera"])
        target = gltf_point(opts["--look-at"])
        camera.data.sensor_fit = "VERTICAL"
        camera.data.angle_y = math.radians(float(opts.get("--fov", "40")))
    else:
        camera.location = centre + mathutils.Vector((-1.1, -1.3, 0.9)) * size
        target = centre
        camera.data.lens = 40
    camera.rotation_euler = (target - camera.location).to_track_quat("-Z", "Y").to_euler()
    scene.camera = camera
    sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", type="SUN"))
    sun.data.energy = 3.0
    sun.rotation_euler = (0.6, 0.2, -0.8)
    scene.collection.objects.link(sun)
    world = bpy.data.worlds.new("world")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs[0].default_value = (0.15, 0.18, 0.25, 1)
    scene.world = world
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = int(opts.get("--samples", "16"))
    scene.cycles.use_denoising = False  # Debian's Blender is built without OpenImageDenoise
    width, height = (int(v) for v in opts.get("--res", "320x240").split("x"))
    scene.render.resolution_x = width
    scene.render.resolution_y = height
    scene.render.resolution_percentage = 100
    scene.render.filepath = opts["--render"]
    bpy.ops.render.render(write_still=True)
    report["render"] = opts["--render"]

print("LAZYSOLID_BLENDER " + json.dumps(report), flush=True)
