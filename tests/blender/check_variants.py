"""Run by Blender: checks the labels blender/plantarch_import.py puts on a variant of a plantarch
glTF file (--nodes organ, --instancing gpu, --skin, --lod, --materials textured).

    blender -b --factory-startup --python check_variants.py -- FILE --addon plantarch_import.py
        registers the add-on and imports FILE through its operator, then checks;
    blender -b SAVED.blend --python check_variants.py -- FILE [--split]
        checks a scene the add-on's script mode imported and saved (--split: with
        --split-instances, so that every mesh must carry object_id on its faces).

What the scene should hold is read from FILE here with json and struct alone (not the add-on's
code): the triangles of every object of the full level (from its node's extras with a node per
organ, else from _OBJECT_ID on each triangle's first corner), each object's organ, the images
and the skins. Blender must hold the same triangles per object and the same organs, every mesh
labelled with plant_id and organ face attributes and each object's ID on its faces or, for an
organ sharing its mesh, as its custom property objectID. Prints one line, "PLANTARCH_LABELS ok
..." or "PLANTARCH_LABELS FAIL ...", and exits 1 on a failure."""

import base64
import importlib.util
import json
import struct
import sys

import bpy
from mathutils import Vector

_FORMATS = {5120: "b", 5121: "B", 5122: "h", 5123: "H", 5125: "I", 5126: "f"}


def read_file(path):
    """The JSON document and the binary buffer of a .glb, or a .gltf with an embedded one."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] != b"glTF":
        doc = json.loads(data)
        return doc, base64.b64decode(doc["buffers"][0]["uri"].split(",", 1)[1])
    length = struct.unpack_from("<I", data, 12)[0]
    return json.loads(data[20:20 + length]), data[20 + length + 8:]


def accessor(doc, binary, index):
    """The values of a tightly packed accessor, as plantarch writes them (first component)."""
    a = doc["accessors"][index]
    width = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}[a["type"]]
    view = doc["bufferViews"][a["bufferView"]]
    values = struct.unpack_from("<%d%s" % (a["count"] * width, _FORMATS[a["componentType"]]),
                                binary, view.get("byteOffset", 0) + a.get("byteOffset", 0))
    return values[::width]


def expected(doc, binary, level):
    """Per object ID its triangles and organ name at a level of detail (0: the full one, the
    scene's nodes; k: the k-th of each node's MSFT_lod ids); the organ names of the file."""
    metadata = doc["extensions"]["EXT_structural_metadata"]
    enum = metadata["schema"]["enums"]["organ_kind"]["values"]
    organs = [v["name"] for v in sorted(enum, key=lambda v: v["value"])]
    table = metadata["propertyTables"][0]
    rows = {}
    if table["count"]:
        objects = accessor_of_table(doc, binary, table, "object", "I")
        kinds = accessor_of_table(doc, binary, table, "organ", "B")
        rows = {o: organs[k] for o, k in zip(objects, kinds)}
    triangles, organ_of = {}, {}
    nodes = doc["nodes"]

    def walk(i):
        node = nodes[i]
        extras = node.get("extras", {})
        if "EXT_mesh_gpu_instancing" in node.get("extensions", {}):  # --instancing gpu
            for p in doc["meshes"][node["mesh"]]["primitives"]:
                n = doc["accessors"][p["indices"]]["count"] // 3
                for oid in extras["objectIDs"]:
                    triangles[oid] = triangles.get(oid, 0) + n
                    organ_of[oid] = extras.get("organ")
        elif "mesh" in node:
            for p in doc["meshes"][node["mesh"]]["primitives"]:
                n = doc["accessors"][p["indices"]]["count"] // 3
                if "objectID" in extras and "_OBJECT_ID" not in p["attributes"]:
                    oid = extras["objectID"]
                    triangles[oid] = triangles.get(oid, 0) + n
                    organ_of[oid] = extras.get("organ")
                    continue
                ids = accessor(doc, binary, p["attributes"]["_OBJECT_ID"])
                corners = accessor(doc, binary, p["indices"])
                for t in range(0, len(corners), 3):
                    oid = int(ids[corners[t]])
                    triangles[oid] = triangles.get(oid, 0) + 1
                    organ_of[oid] = rows.get(oid)
        for c in node.get("children", []):
            walk(c)

    roots = doc["scenes"][doc.get("scene", 0)]["nodes"]
    if level:
        roots = [n["extensions"]["MSFT_lod"]["ids"][level - 1] for n in nodes
                 if "MSFT_lod" in n.get("extensions", {})]
    for root in roots:
        walk(root)
    return triangles, organ_of, organs


def accessor_of_table(doc, binary, table, name, fmt):
    view = doc["bufferViews"][table["properties"][name]["values"]]
    return struct.unpack_from("<%d%s" % (table["count"], fmt), binary, view.get("byteOffset", 0))


def face_values(mesh, name):
    a = mesh.attributes.get(name)
    if a is None or a.domain != "FACE" or a.data_type != "INT":
        return None
    return [d.value for d in a.data]


def check_level(doc, binary, level, meshes, split, problems):
    """Compares the Blender meshes of one level of detail with the file's; returns the
    triangles, objects, meshes labelled by their faces and sharing a mesh, faces per organ."""
    triangles, organ_of, organs = expected(doc, binary, level)
    faces, organ_seen, wrong_organ = {}, {}, 0
    shared = own = 0
    where = "level %d: " % level if level else ""
    for obj in meshes:
        mesh = obj.data
        plant, organ = face_values(mesh, "plant_id"), face_values(mesh, "organ")
        ids = face_values(mesh, "object_id")
        if plant is None or organ is None:
            problems.append("%s%s: no plant_id or organ face attribute" % (where, obj.name))
            continue
        if ids is None and (split or "objectID" not in obj):
            problems.append("%s: no object_id on its faces%s" % (
                obj.name, "" if split else " nor an objectID property"))
            continue
        if ids is None:
            shared += 1
            ids = [obj["objectID"]] * len(mesh.polygons)
        else:
            own += 1
        labels = list(mesh.get("organ_labels", []))
        if labels != organs:
            problems.append("%s: organ_labels %s, the file's %s" % (obj.name, labels, organs))
            continue
        for i, k in zip(ids, organ):
            faces[i] = faces.get(i, 0) + 1
            wrong_organ += organs[k] != organ_of.get(i)
            organ_seen[organs[k]] = organ_seen.get(organs[k], 0) + 1
    total = sum(faces.values())
    if total != sum(triangles.values()):
        problems.append("%s%d triangles, the file's %d" % (where, total,
                                                           sum(triangles.values())))
    if faces != triangles:
        differ = [i for i in triangles if faces.get(i) != triangles[i]]
        problems.append("%sfaces per object differ from the file's for %d objects, e.g. %s" % (
            where, len(differ), differ[:3]))
    if wrong_organ:
        problems.append("%s%d faces whose organ is not their object's" % (where, wrong_organ))
    return total, len(faces), own, shared, organ_seen


def world_box(meshes):
    """The world box of some mesh objects: (low corner, high corner)."""
    lo, hi = Vector((1e30,) * 3), Vector((-1e30,) * 3)
    for o in meshes:
        for corner in o.bound_box:
            w = o.matrix_world @ Vector(corner)
            lo, hi = Vector(map(min, lo, w)), Vector(map(max, hi, w))
    return lo, hi


def check(path, split):
    doc, binary = read_file(path)
    problems = []
    meshes = [o for o in bpy.data.objects if o.type == "MESH"]
    levels = 1 + max((len(n["extensions"]["MSFT_lod"]["ids"]) for n in doc["nodes"]
                      if "MSFT_lod" in n.get("extensions", {})), default=0)
    found = [check_level(doc, binary, k, [o for o in meshes if o.get("plantarch_lod", 0) == k],
                         split, problems) for k in range(levels)]
    total, objects, own, shared, organ_seen = found[0]
    if any(o.get("plantarch_lod", 0) >= levels for o in meshes):
        problems.append("meshes of a level the file does not have")
    # Each lower level stands where the full one does (within 5 % of its size).
    bpy.context.view_layer.update()
    full = world_box([o for o in meshes if o.get("plantarch_lod", 0) == 0])
    size = (full[1] - full[0]).length
    for k in range(1, levels):
        box = world_box([o for o in meshes if o.get("plantarch_lod", 0) == k])
        off = max((box[0] - full[0]).length, (box[1] - full[1]).length)
        if off > 0.05 * size:
            problems.append("level %d stands %.3f m away from the full level" % (k, off))
    images = [i for i in bpy.data.images if i.type == "IMAGE" and i.size[0] > 0]
    if len(images) < len(doc.get("images", [])):
        problems.append("%d images, the file's %d" % (len(images), len(doc["images"])))
    armatures = [o for o in bpy.data.objects if o.type == "ARMATURE"]
    if len(armatures) != len(doc.get("skins", [])):
        problems.append("%d armatures, the file's %d skins" % (len(armatures),
                                                                len(doc.get("skins", []))))
    if doc.get("skins") and any(not any(m.type == "ARMATURE" for m in o.modifiers)
                                for o in meshes):
        problems.append("a mesh without its armature modifier")
    if problems:
        print("PLANTARCH_LABELS FAIL " + "; ".join(problems[:5]))
        return 1
    lower = "".join(", level %d: %d triangles of %d objects" % (k, f[0], f[1])
                    for k, f in enumerate(found) if k)
    print("PLANTARCH_LABELS ok %d triangles, %d objects in %d meshes (%d labelled by their "
          "faces, %d sharing a mesh)%s, %d images, %d armatures, faces per organ %s" % (
              total, objects, len(meshes), own, shared, lower, len(images), len(armatures),
              json.dumps(organ_seen, sort_keys=True)))
    return 0


def main():
    args = sys.argv[sys.argv.index("--") + 1:]
    path = args[0]
    if "--addon" in args:
        bpy.ops.wm.read_factory_settings(use_empty=True)
        spec = importlib.util.spec_from_file_location(
            "plantarch_import", args[args.index("--addon") + 1])
        addon = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(addon)
        addon.register()
        if "FINISHED" not in bpy.ops.import_scene.plantarch_gltf(filepath=path):
            print("PLANTARCH_LABELS FAIL the add-on's operator did not finish")
            return 1
    return check(path, "--split" in args)


sys.exit(main())
