"""Run by Blender (blender -b --factory-startup --python import_gltf.py -- FILE): imports a
glTF file with Blender's own importer and prints one JSON line with what it holds: triangles,
mesh objects, and the names of the mesh attributes (labels show up as attributes)."""

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
print("PLANTARCH " + json.dumps({"triangles": triangles, "meshes": meshes,
                                 "attributes": sorted(attributes)}))
