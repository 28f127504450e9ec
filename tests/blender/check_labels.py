"""Run by Blender: checks the labels blender/plantarch_import.py puts on a plantarch glTF file.

    blender -b --factory-startup --python check_labels.py -- FILE --addon plantarch_import.py
        registers the add-on and imports FILE through its operator, then checks;
    blender -b SAVED.blend --python check_labels.py -- FILE
        checks a scene the add-on's script mode imported and saved.

What the scene should hold is read from FILE here with json and struct alone (not the add-on's
code): the triangles of each mesh (its name is its organ kind), the plant nodes' plantID and
the size of the property table. Prints one line, "PLANTARCH_LABELS ok ..." or
"PLANTARCH_LABELS FAIL ...", and exits 1 on a failure."""

import base64
import importlib.util
import json
import re
import struct
import sys

import bpy

INT_ATTRIBUTES = ("plant_id", "object_id", "organ", "leaf_id", "shoot_id", "rank", "node")


def read_file(path):
    """The JSON document and the binary buffer of a .glb, or a .gltf with an embedded one."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] != b"glTF":
        doc = json.loads(data)
        return doc, base64.b64decode(doc["buffers"][0]["uri"].split(",", 1)[1])
    length = struct.unpack_from("<I", data, 12)[0]
    return json.loads(data[20:20 + length]), data[20 + length + 8:]


def numbers(doc, binary, view, fmt, count):
    v = doc["bufferViews"][view]
    return struct.unpack_from("<%d%s" % (count, fmt), binary, v.get("byteOffset", 0))


def objects_in_file(doc, binary):
    """Per object ID: its triangles (its _OBJECT_ID on each triangle's first corner), its
    property table row (plant, organ, leaf, shoot, rank, node, age) and the sum of its
    triangles' centres in Blender's axes, relative to its plant."""
    triangles, centres = {}, {}
    for mesh in doc["meshes"]:
        for p in mesh["primitives"]:
            ids = doc["accessors"][p["attributes"]["_OBJECT_ID"]]
            ids = numbers(doc, binary, ids["bufferView"], "f", ids["count"])
            xyz = doc["accessors"][p["attributes"]["POSITION"]]
            xyz = numbers(doc, binary, xyz["bufferView"], "f", 3 * xyz["count"])
            corners = doc["accessors"][p["indices"]]
            corners = numbers(doc, binary, corners["bufferView"], "I", corners["count"])
            for t in range(0, len(corners), 3):
                i = int(ids[corners[t]])
                triangles[i] = triangles.get(i, 0) + 1
                c = centres.setdefault(i, [0.0, 0.0, 0.0])
                for k in corners[t:t + 3]:  # glTF's y up is Blender's z up: (x, -z, y)
                    c[0] += xyz[3 * k] / 3
                    c[1] -= xyz[3 * k + 2] / 3
                    c[2] += xyz[3 * k + 1] / 3
    table = doc["extensions"]["EXT_structural_metadata"]["propertyTables"][0]
    columns = {}
    for name, fmt in (("plant", "i"), ("object", "I"), ("organ", "B"), ("leaf", "i"),
                      ("shoot", "i"), ("rank", "i"), ("node", "i"), ("age", "f")):
        columns[name] = numbers(doc, binary, table["properties"][name]["values"], fmt,
                                table["count"])
    rows = {}
    for i, object_id in enumerate(columns["object"]):
        rows[object_id] = tuple(columns[name][i] for name in
                                ("plant", "organ", "leaf", "shoot", "rank", "node", "age"))
    return triangles, rows, centres


def expected(doc):
    """Triangles per organ kind, the plant IDs per mesh node, the organ table, the objects."""
    nodes, meshes = doc["nodes"], doc["meshes"]
    table = doc["extensions"]["EXT_structural_metadata"]
    enum = table["schema"]["enums"]["organ_kind"]["values"]
    organs = [v["name"] for v in sorted(enum, key=lambda v: v["value"])]
    triangles, plant_of = {}, {}  # plant_of: (plant node name, mesh name) -> plant ID

    def walk(i, plant, plant_name):
        node = nodes[i]
        if "plantID" in node.get("extras", {}):
            plant, plant_name = node["extras"]["plantID"], node["name"]
        if "mesh" in node:
            mesh = meshes[node["mesh"]]
            n = sum(doc["accessors"][p["indices"]]["count"] // 3 for p in mesh["primitives"])
            triangles[mesh["name"]] = triangles.get(mesh["name"], 0) + n
            plant_of[(plant_name, mesh["name"])] = plant
        for c in node.get("children", []):
            walk(c, plant, plant_name)

    for root in doc["scenes"][doc.get("scene", 0)]["nodes"]:
        walk(root, -1, "scene")
    return triangles, plant_of, organs, table["propertyTables"][0]["count"]


def values(mesh, name):
    return [d.value for d in mesh.attributes[name].data]


def face_rows(mesh):
    """Per face: its object_id and its labels in the order of the file's rows."""
    ids = values(mesh, "object_id")
    labels = zip(*(values(mesh, name) for name in ("plant_id", "organ", "leaf_id", "shoot_id",
                                                    "rank", "node", "age")))
    return zip(ids, labels)


def check(path):
    doc, binary = read_file(path)
    triangles, plant_of, organs, objects = expected(doc)
    object_triangles, rows, file_centres = objects_in_file(doc, binary)
    centres = {}
    object_faces, wrong_rows = {}, 0
    problems = []
    faces = {}  # organ name -> faces Blender holds with that organ value
    plants, object_ids, total = set(), set(), 0
    for obj in bpy.data.objects:
        if obj.type != "MESH":
            continue
        mesh, kind = obj.data, re.sub(r"\.\d{3,}$", "", obj.name)
        total += sum(len(p.vertices) - 2 for p in mesh.polygons)
        for name in INT_ATTRIBUTES + ("age",):
            a = mesh.attributes.get(name)
            want = "FLOAT" if name == "age" else "INT"
            if a is None or a.domain != "FACE" or a.data_type != want:
                problems.append("%s: %s is %s, not a %s face attribute" % (
                    obj.name, name, a and (a.domain, a.data_type), want))
        if problems:
            break
        if list(mesh.get("organ_labels", [])) != organs:
            problems.append("%s: organ_labels %s, the file's %s" % (
                obj.name, list(mesh.get("organ_labels", [])), organs))
        organ = values(mesh, "organ")
        for value in organ:
            faces[organs[value]] = faces.get(organs[value], 0) + 1
        if set(organ) != {organs.index(kind) if kind in organs else None}:
            problems.append("%s: organ values %s on a %s mesh" % (obj.name, sorted(set(organ)),
                                                                   kind))
        plant = values(mesh, "plant_id")
        parent = re.sub(r"\.\d{3,}$", "", obj.parent.name) if obj.parent else ""
        want = plant_of.get((parent, kind), "none: no such mesh in the file")
        if set(plant) != {want}:
            problems.append("%s: plant_id %s, the file's %s" % (obj.name, sorted(set(plant)), want))
        if (obj.parent.get("plantID", -1) if obj.parent else None) != want:
            problems.append("%s: custom property plantID %s" % (obj.parent.name,
                                                                obj.parent.get("plantID")))
        leaf = values(mesh, "leaf_id")
        if (min(leaf) >= 0) != (kind == "leaf") or (max(leaf) >= 0) != (kind == "leaf"):
            problems.append("%s: leaf_id %d to %d on a %s mesh" % (obj.name, min(leaf), max(leaf),
                                                                    kind))
        plants.update(plant)
        object_ids.update(values(mesh, "object_id"))
        for (object_id, labels), face in zip(face_rows(mesh), mesh.polygons):
            object_faces[object_id] = object_faces.get(object_id, 0) + 1
            wrong_rows += rows.get(object_id) != labels
            c = centres.setdefault(object_id, [0.0, 0.0, 0.0])
            for k in range(3):
                c[k] += face.center[k]
    want_total = sum(triangles.values())
    if total != want_total:
        problems.append("%d triangles, the file's %d" % (total, want_total))
    if faces != triangles:
        problems.append("faces per organ %s, the file's %s" % (faces, triangles))
    if plants != set(plant_of.values()):
        problems.append("plant_id values %s, the file's %s" % (sorted(plants),
                                                               sorted(set(plant_of.values()))))
    if len(object_ids) != objects:
        problems.append("%d object IDs, the file's %d objects" % (len(object_ids), objects))
    if object_faces != object_triangles:
        differ = [i for i in object_triangles if object_faces.get(i) != object_triangles[i]]
        problems.append("faces per object_id differ from the file's for %d objects, e.g. %s" % (
            len(differ), differ[:3]))
    misplaced = [i for i in file_centres if i not in centres or
                 max(abs(a - b) for a, b in zip(centres[i], file_centres[i])) >
                 1e-5 * object_triangles[i]]  # sums of float32 centres: 1e-5 m a face
    if misplaced:
        problems.append("the faces of %d objects are not where the file has them, e.g. %s" % (
            len(misplaced), misplaced[:3]))
    if wrong_rows:
        problems.append("%d faces whose labels are not their object's row in the file" % wrong_rows)
    if problems:
        print("PLANTARCH_LABELS FAIL " + "; ".join(problems[:5]))
        return 1
    print("PLANTARCH_LABELS ok %d triangles, %d objects, plants %s, faces per organ %s" % (
        total, len(object_ids), sorted(plants), json.dumps(faces, sort_keys=True)))
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
    return check(path)


sys.exit(main())
