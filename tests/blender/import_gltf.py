"""Run by Blender (blender -b --factory-startup --python import_gltf.py -- FILE): imports a
glTF file with Blender's own importer and prints one JSON line with what it holds: triangles,
mesh objects, the names of the mesh attributes (labels show up as attributes), for a skinned
file its armatures and bones, and for an animated file the triangles shown at each frame."""

import json
import sys

import bpy
import numpy

# Debian 12's Blender 3.4 glTF importer still uses numpy.bool, which Debian's numpy 1.24 no
# longer has; the alias is the builtin bool it stood for.
if not hasattr(numpy, "bool"):
    numpy.bool = bool

path = sys.argv[sys.argv.index("--") + 1]
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=path)
triangles = 0
meshes = 0
attributes = set()
for obj in bpy.data.objects:
    if obj.type != "MESH":
        continue
    meshes += 1
    mesh = obj.data
    triangles += sum(len(p.vertices) - 2 for p in mesh.polygons)
    attributes.update(a.name for a in mesh.attributes)
report = {"triangles": triangles, "meshes": meshes, "attributes": sorted(attributes)}

# Textured materials (--materials textured): images Blender decoded, and the materials whose
# node tree samples one, with a normal map among them, and those reading part of an atlas.
images = [i for i in bpy.data.images if i.size[0] > 0]
if images:
    nodes = [m.node_tree.nodes for m in bpy.data.materials if m.use_nodes and m.node_tree]
    report["images"] = len(images)
    report["textured_materials"] = sum(1 for n in nodes if any(x.type == "TEX_IMAGE" for x in n))
    report["normal_mapped"] = sum(1 for n in nodes if any(x.type == "NORMAL_MAP" for x in n))
    # Parts of a texture atlas (KHR_texture_transform): a Mapping node before the textures.
    report["transformed"] = sum(1 for n in nodes if any(x.type == "MAPPING" for x in n))

# Skins: the armatures, their bones, the meshes an armature deforms, and the world box of every
# mesh vertex as Blender places it (armatures applied).
armatures = [o for o in bpy.data.objects if o.type == "ARMATURE"]
if armatures:
    graph = bpy.context.evaluated_depsgraph_get()
    low, high = [float("inf")] * 3, [float("-inf")] * 3
    for obj in bpy.data.objects:
        if obj.type != "MESH":
            continue
        evaluated = obj.evaluated_get(graph)
        for v in evaluated.to_mesh().vertices:
            w = evaluated.matrix_world @ v.co
            low = [min(a, b) for a, b in zip(low, w)]
            high = [max(a, b) for a, b in zip(high, w)]
        evaluated.to_mesh_clear()
    report["armatures"] = len(armatures)
    report["bones"] = sum(len(a.data.bones) for a in armatures)
    report["skinned"] = sum(1 for o in bpy.data.objects if o.type == "MESH" and
                            any(m.type == "ARMATURE" and m.object for m in o.modifiers))
    report["box"] = low + high


def shown_triangles():
    """Triangles of the meshes drawn now: world scale not zero."""
    bpy.context.view_layer.update()
    n = 0
    for obj in bpy.data.objects:
        if obj.type == "MESH" and abs(obj.matrix_world.determinant()) > 0:
            n += sum(len(p.vertices) - 2 for p in obj.data.polygons)
    return n


# An animation as Blender plays it: the triangles shown at each key of its actions (the last
# key ends the animation and is no frame of its own).
keys = sorted({k.co[0] for action in bpy.data.actions for curve in action.fcurves
               for k in curve.keyframe_points})
if keys:
    frames = []
    for key in keys[:-1]:
        whole = int(key // 1)
        bpy.context.scene.frame_set(whole, subframe=key - whole)
        frames.append(shown_triangles())
    report["frames"] = frames
print("PLANTARCH " + json.dumps(report))
