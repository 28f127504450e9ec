# Imports a textured OBJ (--materials textured) with Blender's own OBJ importer, headless, and
# prints one line "PLANTARCH {json}": per material the image files its nodes sample and the
# location and scale of its Mapping nodes, which Blender makes from the .mtl's -o and -s.
# Usage: blender -b --factory-startup --python import_obj_maps.py -- FILE.obj
import json
import sys

import bpy

path = sys.argv[sys.argv.index("--") + 1]
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.wm.obj_import(filepath=path)
report = {}
for m in bpy.data.materials:
    if not m.use_nodes or not m.node_tree:
        continue
    nodes = m.node_tree.nodes
    report[m.name] = {
        "images": sorted({n.image.name for n in nodes if n.type == "TEX_IMAGE" and n.image}),
        "mappings": sorted({(round(n.inputs["Location"].default_value[0], 5),
                             round(n.inputs["Location"].default_value[1], 5),
                             round(n.inputs["Scale"].default_value[0], 5),
                             round(n.inputs["Scale"].default_value[1], 5))
                            for n in nodes if n.type == "MAPPING"}),
    }
print("PLANTARCH " + json.dumps(report))
