"""Import plantarch's glTF files into Blender with their labels as face attributes.

An add-on (File > Import > plantarch glTF (.glb/.gltf)) and a script:

    blender -b --python plantarch_import.py -- FILE.glb [--out FILE.blend] [--split-instances]

The file is imported by Blender's own glTF importer; then every mesh gets plantarch's labels
as integer face attributes (POLYGON domain) plant_id, object_id, organ, leaf_id, shoot_id,
rank and node, age as a float face attribute, and any float columns a physiology season adds
(absorbed_par ...). The organ names, index = organ value, are the mesh's custom property
`organ_labels`. Blender's importer keeps the plant nodes' extras (plantID, species, age,
seed) as the empties' custom properties.

Files written with --nodes organ (an object per organ, labelled by its custom properties;
shared meshes labelled with what their users share, or each organ's own with
--split-instances), --skin (meshes under an armature), --lod (the lower levels hidden, each
object's level its custom property plantarch_lod) and --materials textured import with their labels too; --meshopt files do not
(Blender 3.4 cannot read EXT_meshopt_compression). --instancing gpu files import with each
instance an object (Blender 3.4's importer cannot read EXT_mesh_gpu_instancing: the instances
are expanded first). See docs/formats.md, "Blender".
"""

import base64
import json
import os
import re
import struct
import sys
import warnings

import bpy
import numpy

bl_info = {
    "name": "plantarch glTF import",
    "author": "plantarch",
    "version": (1, 0, 0),
    "blender": (3, 4, 0),
    "location": "File > Import > plantarch glTF (.glb/.gltf)",
    "description": "Imports plantarch's glTF/GLB plants with their labels as face attributes",
    "category": "Import-Export",
}


def apply_numpy_fix():
    """Blender 3.4's glTF importer (Debian 12) calls numpy.bool, an alias of the builtin bool
    that numpy 1.20 deprecated and 1.24 removed (Debian 12 ships 1.24): without it every
    import stops with "module 'numpy' has no attribute 'bool'". Put the alias back; numpy
    versions that have numpy.bool (before 1.24, or 2.x where it is numpy.bool_) are left as
    they are."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # numpy 1.24 warns when numpy.bool is looked up
        if not hasattr(numpy, "bool"):
            numpy.bool = bool


_COMPONENTS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT2": 4, "MAT3": 9, "MAT4": 16}
_ACCESSOR_TYPES = {5120: "i1", 5121: "u1", 5122: "<i2", 5123: "<u2", 5125: "<u4", 5126: "<f4"}
_TABLE_TYPES = {"INT8": "i1", "UINT8": "u1", "INT16": "<i2", "UINT16": "<u2", "INT32": "<i4",
                "UINT32": "<u4", "INT64": "<i8", "UINT64": "<u8", "FLOAT32": "<f4",
                "FLOAT64": "<f8"}
# plantarch's property table columns and the face attributes they become.
_COLUMN_NAMES = {"plant": "plant_id", "object": "object_id", "leaf": "leaf_id",
                 "shoot": "shoot_id"}


class GltfFile:
    """The JSON document and binary buffers of a .glb or .gltf file."""

    def __init__(self, path):
        with open(path, "rb") as f:
            data = f.read()
        self.buffers = []
        if data[:4] == b"glTF":
            offset, chunks = 12, []
            while offset + 8 <= len(data):
                length, kind = struct.unpack_from("<II", data, offset)
                chunks.append((kind, data[offset + 8:offset + 8 + length]))
                offset += 8 + length
            self.doc = json.loads(next(c for k, c in chunks if k == 0x4E4F534A))
            binary = [c for k, c in chunks if k == 0x004E4942]
        else:
            self.doc = json.loads(data)
            binary = []
        for i, buffer in enumerate(self.doc.get("buffers", [])):
            uri = buffer.get("uri")
            if uri is None:
                self.buffers.append(binary[0] if i == 0 and binary else b"")
            elif uri.startswith("data:"):
                self.buffers.append(base64.b64decode(uri.split(",", 1)[1]))
            else:
                with open(os.path.join(os.path.dirname(path), uri), "rb") as f:
                    self.buffers.append(f.read())

    def view(self, index):
        view = self.doc["bufferViews"][index]
        start = view.get("byteOffset", 0)
        return self.buffers[view["buffer"]][start:start + view["byteLength"]], view

    def accessor(self, index):
        """An accessor's values: a numpy array, one row per element."""
        a = self.doc["accessors"][index]
        dtype = numpy.dtype(_ACCESSOR_TYPES[a["componentType"]])
        width = _COMPONENTS[a["type"]]
        if "bufferView" not in a:
            return numpy.zeros((a["count"], width), dtype)
        data, view = self.view(a["bufferView"])
        stride = view.get("byteStride", dtype.itemsize * width)
        start = a.get("byteOffset", 0)
        rows = numpy.lib.stride_tricks.as_strided(
            numpy.frombuffer(data, numpy.uint8, len(data) - start, start),
            (a["count"], dtype.itemsize * width), (stride, 1))
        return numpy.ascontiguousarray(rows).view(dtype).reshape(a["count"], width)

    def labels(self):
        """The property table of plantarch's labels: {column: values per feature}, the organ
        names, and the table's index (None when the file has none)."""
        metadata = self.doc.get("extensions", {}).get("EXT_structural_metadata")
        if not metadata or not metadata.get("propertyTables"):
            return {}, [], None
        schema = metadata.get("schema", {})
        table = metadata["propertyTables"][0]
        properties = schema.get("classes", {}).get(table["class"], {}).get("properties", {})
        columns, organs = {}, []
        for name, column in table.get("properties", {}).items():
            p = properties.get(name, {})
            kind = p.get("componentType")
            if p.get("type") == "ENUM":
                enum = schema["enums"][p["enumType"]]
                kind = enum.get("valueType", "UINT16")
                if name == "organ":
                    organs = [""] * (1 + max(v["value"] for v in enum["values"]))
                    for v in enum["values"]:
                        organs[v["value"]] = v["name"]
            if p.get("type") not in ("SCALAR", "ENUM") or kind not in _TABLE_TYPES:
                continue
            data, _ = self.view(column["values"])
            columns[name] = numpy.frombuffer(data, _TABLE_TYPES[kind], table["count"])
        return columns, organs, 0


def _base_name(name):
    """A Blender name without the ".001" that keeps names unique."""
    return re.sub(r"\.\d{3,}$", "", name)


def _match_nodes(gltf, new_objects):
    """The Blender object made for each glTF node of the default scene and of its lower
    levels of detail: ({node: object}, {node: level}), found by walking both trees from the
    roots and matching children by name. Levels (MSFT_lod, --lod) are 1, 2 ... for the nodes
    of each lower level; Blender 3.4 makes them as trees of their own at the scene's root."""
    nodes = gltf.doc.get("nodes", [])
    scene = gltf.doc.get("scenes", [{}])[gltf.doc.get("scene", 0)]
    found = {}

    def match(indices, candidates):
        by_name = {}
        for obj in candidates:
            by_name.setdefault(_base_name(obj.name), []).append(obj)
        for i in indices:
            name = nodes[i].get("name", "")
            objs = by_name.get(name) or by_name.get(_base_name(name)) or []
            if len(objs) != 1:
                continue  # not made (a node without content) or not told apart: skip
            found[i] = objs[0]
            kids = [o for o in objs[0].children if o in new_objects]
            match(nodes[i].get("children", []), kids)

    roots = [o for o in new_objects if o.parent not in new_objects]
    match(scene.get("nodes", []), roots)
    levels = {}

    def mark(i, level):
        levels[i] = level
        for c in nodes[i].get("children", []):
            mark(c, level)

    for i in list(found):
        for level, lod in enumerate(nodes[i].get("extensions", {}).get("MSFT_lod", {})
                                    .get("ids", []), 1):
            match([lod], roots)
            mark(lod, level)
    # Skinned meshes (--skin) are nodes at the scene's root in the file, but Blender's
    # importer puts them under the armature it makes of their skin: the object of the node
    # above the skin's skeleton root. Find them among that object's children by name.
    parent_of = {c: i for i, n in enumerate(nodes) for c in n.get("children", [])}
    skins = gltf.doc.get("skins", [])
    for i, node in enumerate(nodes):
        if i in found or "mesh" not in node or node.get("skin") is None:
            continue
        skin = skins[node["skin"]]
        root = skin.get("skeleton", skin["joints"][0] if skin.get("joints") else None)
        armature = found.get(parent_of.get(root)) or found.get(root)
        if armature is None:
            continue
        name = node.get("name", "")
        objs = [o for o in armature.children if o in new_objects and o.type == "MESH" and
                _base_name(o.name) in (name, _base_name(name))]
        if len(objs) == 1:
            found[i] = objs[0]
    return found, levels


def _place_levels(gltf, found, levels):
    """Puts each lower level of detail where the glTF places it (instead of the node whose
    MSFT_lod lists it: under that node's parent, with its transform), hidden, each object
    with its level as the custom property plantarch_lod."""
    nodes = gltf.doc.get("nodes", [])
    parent_of = {c: i for i, n in enumerate(nodes) for c in n.get("children", [])}
    for i, full in list(found.items()):
        for lod in nodes[i].get("extensions", {}).get("MSFT_lod", {}).get("ids", []):
            obj = found.get(lod)
            if obj is None:
                continue
            obj.parent = found.get(parent_of.get(i))
            obj.matrix_parent_inverse.identity()
            obj.matrix_basis = full.matrix_basis.copy()
    bpy.context.view_layer.update()  # world matrices of the moved levels
    for i, level in levels.items():
        obj = found.get(i)
        if obj is not None:
            obj["plantarch_lod"] = level
            obj.hide_viewport = obj.hide_render = True
            obj.hide_set(True)


def _vertex_features(gltf, mesh_index):
    """Per vertex of the Blender mesh the importer made of a glTF mesh, the feature ID (the
    property table row) or, without one, the per-vertex labels. Blender's importer keeps
    each primitive's vertices that its triangles use, in index order, primitive after
    primitive (without "merge vertices"). Returns {name: values per vertex}, or None where
    a primitive is not plantarch's (no labels, or not triangles)."""
    per_vertex = {}
    for prim in gltf.doc["meshes"][mesh_index]["primitives"]:
        attributes = prim.get("attributes", {})
        if "POSITION" not in attributes:
            continue
        if prim.get("mode", 4) != 4:
            return None
        count = gltf.doc["accessors"][attributes["POSITION"]]["count"]
        if "indices" in prim:
            used = numpy.unique(gltf.accessor(prim["indices"]).ravel())
        else:
            used = numpy.arange(count)
        features = prim.get("extensions", {}).get("EXT_mesh_features", {}).get("featureIds")
        names = {}
        if features and "attribute" in features[0]:
            names["feature"] = "_FEATURE_ID_%d" % features[0]["attribute"]
        for name, attribute in (("plant", "_PLANT_ID"), ("object", "_OBJECT_ID"),
                                ("organ", "_ORGAN")):
            names[name] = attribute
        for key, attribute in names.items():
            if attribute not in attributes:
                continue
            values = gltf.accessor(attributes[attribute])[:, 0][used]
            per_vertex.setdefault(key, []).append(numpy.rint(values).astype(numpy.int64))
    if not per_vertex or len({len(v) for v in per_vertex.values()}) != 1:
        return None
    return {k: numpy.concatenate(v) for k, v in per_vertex.items()}


def _set_face_attribute(mesh, name, values, kind):
    old = mesh.attributes.get(name)
    if old is not None:
        mesh.attributes.remove(old)
    attribute = mesh.attributes.new(name, kind, "FACE")
    if kind == "INT":
        attribute.data.foreach_set("value", values.astype(numpy.int32))
    else:
        attribute.data.foreach_set("value", values.astype(numpy.float32))


def _label_mesh(mesh, per_vertex, columns, organs):
    """Puts the labels on the faces of one Blender mesh; returns the names added."""
    if len(mesh.vertices) != len(next(iter(per_vertex.values()))):
        return []  # not the vertices the importer makes of this glTF mesh: leave it
    loop_start = numpy.empty(len(mesh.polygons), numpy.int32)
    mesh.polygons.foreach_get("loop_start", loop_start)
    loop_vertex = numpy.empty(len(mesh.loops), numpy.int32)
    mesh.loops.foreach_get("vertex_index", loop_vertex)
    first = loop_vertex[loop_start]  # an object's labels are the same on all its vertices
    values = {}
    if "feature" in per_vertex and columns:
        rows = per_vertex["feature"][first]
        for name, column in columns.items():
            values[_COLUMN_NAMES.get(name, name)] = column[rows]
    else:
        for name in ("plant", "object", "organ"):
            if name in per_vertex:
                values[_COLUMN_NAMES.get(name, name)] = per_vertex[name][first]
    for name, v in values.items():
        _set_face_attribute(mesh, name, v, "FLOAT" if v.dtype.kind == "f" else "INT")
    if organs and "organ" in values:
        mesh["organ_labels"] = organs
    return sorted(values)


# A node's extras (a file written with --nodes organ) and the face attributes they fill.
_EXTRAS = (("plantID", "plant_id", "INT"), ("objectID", "object_id", "INT"),
           ("leaf", "leaf_id", "INT"), ("shoot", "shoot_id", "INT"), ("rank", "rank", "INT"),
           ("node", "node", "INT"), ("age", "age", "FLOAT"))


def _label_from_extras(mesh, extras, organs):
    """Puts one organ's labels, from its node's extras, on every face of its own mesh;
    returns the names added (none when the extras are not an organ's)."""
    if "objectID" not in extras or not mesh.polygons:
        return []
    faces, added = len(mesh.polygons), []
    for key, name, kind in _EXTRAS:
        if isinstance(extras.get(key), (int, float)):
            _set_face_attribute(mesh, name, numpy.full(faces, extras[key]), kind)
            added.append(name)
    if extras.get("organ") in organs:
        _set_face_attribute(mesh, "organ", numpy.full(faces, organs.index(extras["organ"])),
                            "INT")
        mesh["organ_labels"] = organs
        added.append("organ")
    return added


# The per-instance labels of --instancing gpu and the extras keys of an organ node.
_INSTANCE_LABELS = (("_OBJECT_ID", "objectID", int), ("_SHOOT", "shoot", int),
                    ("_RANK", "rank", int), ("_NODE", "node", int), ("_LEAF", "leaf", int),
                    ("_AGE", "age", float), ("_FEATURE_ID_0", "feature", int))
_INSTANCING = ("EXT_mesh_gpu_instancing", "EXT_instance_features")


def expand_instances(gltf):
    """Blender 3.4's importer cannot read EXT_mesh_gpu_instancing (--instancing gpu): turns
    each instancing node of `gltf` into a node per instance under it, placed by the instance's
    translation, rotation and scale and labelled in its extras as an organ node of
    --instancing shared is (the mesh shared). Returns whether the file had any."""
    nodes = gltf.doc.get("nodes", [])
    found = False
    for node in list(nodes):
        extension = node.get("extensions", {}).get("EXT_mesh_gpu_instancing")
        if extension is None:
            continue
        found = True
        values = {k: gltf.accessor(i) for k, i in extension["attributes"].items()}
        count = len(next(iter(values.values())))
        extras = node.get("extras", {})
        names = extras.get("instances", [])
        children = []
        for i in range(count):
            child = {"name": names[i] if i < len(names) else "%s_%d" % (node.get("name"), i),
                     "mesh": node["mesh"]}
            for key in ("TRANSLATION", "ROTATION", "SCALE"):
                if key in values:
                    child[key.lower()] = [float(v) for v in values[key][i]]
            labels = {k: extras[k] for k in ("plantID", "organ") if k in extras}
            for attribute, key, kind in _INSTANCE_LABELS:
                if attribute in values:
                    labels[key] = kind(values[attribute][i][0])
            child["extras"] = labels
            nodes.append(child)
            children.append(len(nodes) - 1)
        del node["mesh"]
        for name in _INSTANCING:
            node["extensions"].pop(name, None)
        if not node["extensions"]:
            del node["extensions"]
        node["children"] = node.get("children", []) + children
    if found:
        for key in ("extensionsUsed", "extensionsRequired"):
            kept = [e for e in gltf.doc.get(key, []) if e not in _INSTANCING]
            if kept:
                gltf.doc[key] = kept
            else:
                gltf.doc.pop(key, None)
    return found


def _write_glb(gltf, path):
    """`gltf` (its first buffer as the binary chunk) as a .glb file."""
    doc = dict(gltf.doc)
    binary = gltf.buffers[0] if gltf.buffers else b""
    if doc.get("buffers"):
        first = {k: v for k, v in doc["buffers"][0].items() if k != "uri"}
        first["byteLength"] = len(binary)
        doc["buffers"] = [first] + doc["buffers"][1:]
    text = json.dumps(doc).encode()
    text += b" " * (-len(text) % 4)
    binary += b"\0" * (-len(binary) % 4)
    chunks = struct.pack("<II", len(text), 0x4E4F534A) + text
    if binary:
        chunks += struct.pack("<II", len(binary), 0x004E4942) + binary
    with open(path, "wb") as f:
        f.write(struct.pack("<III", 0x46546C67, 2, 12 + len(chunks)) + chunks)


def _import(filepath, gltf, importer_options):
    """Blender's importer on the file, or on a copy with the instances expanded beside it (in
    the temporary folder where the file's folder cannot be written)."""
    if not expand_instances(gltf):
        return bpy.ops.import_scene.gltf(filepath=str(filepath), **importer_options)
    import tempfile
    try:
        handle, copy = tempfile.mkstemp(suffix=".glb", dir=os.path.dirname(os.path.abspath(
            filepath)))
    except OSError:
        handle, copy = tempfile.mkstemp(suffix=".glb")
    os.close(handle)
    try:
        _write_glb(gltf, copy)
        return bpy.ops.import_scene.gltf(filepath=copy, **importer_options)
    finally:
        os.remove(copy)


def load(filepath, split_instances=False, **importer_options):
    """Imports a plantarch glTF/GLB file into the current scene with Blender's importer and
    adds the labels; returns a summary: {"meshes", "labelled", "triangles", "attributes"}.

    A file written with --nodes organ has an object per organ, its labels (plantID,
    objectID, organ, leaf, shoot, node, rank, age) its custom properties. Organs of one shape
    share one mesh (instancing): its faces get the labels all its users share (plant_id,
    organ); with `split_instances`, each such object gets a mesh of its own (a copy) whose
    faces carry all of its labels. A file written with --instancing gpu is imported so too:
    Blender 3.4 cannot read EXT_mesh_gpu_instancing, so each instance becomes an object (on a
    copy of the file beside it, removed after the import)."""
    apply_numpy_fix()
    before = set(bpy.data.objects)
    gltf = GltfFile(filepath)
    result = _import(filepath, gltf, importer_options)  # instances expanded
    if "FINISHED" not in result:
        raise RuntimeError("%s: Blender's glTF importer failed" % filepath)
    new_objects = set(o for o in bpy.data.objects if o not in before)
    columns, organs, _ = gltf.labels()
    nodes = gltf.doc.get("nodes", [])
    summary = {"meshes": 0, "labelled": 0, "triangles": 0, "attributes": set()}
    done = set()
    found, levels = _match_nodes(gltf, new_objects)
    _place_levels(gltf, found, levels)
    matched = sorted(found.items())
    users = {}
    for index, obj in matched:
        if obj.type == "MESH" and "mesh" in nodes[index]:
            users[obj.data] = users.get(obj.data, 0) + 1
    for index, obj in matched:
        extras = nodes[index].get("extras", {})
        for key, value in extras.items():
            if isinstance(value, (int, float, str)):
                obj[key] = value  # as Blender's importer does: kept in case it stops
        if obj.type != "MESH" or "mesh" not in nodes[index]:
            continue
        summary["meshes"] += 1
        if index not in levels:  # the full level's
            summary["triangles"] += sum(len(p.vertices) - 2 for p in obj.data.polygons)
        per_vertex = _vertex_features(gltf, nodes[index]["mesh"])
        # An organ's node whose mesh has no per-vertex object IDs (a shared one): its labels
        # are its extras.
        organ_node = "objectID" in extras and not (per_vertex and "object" in per_vertex)
        if organ_node and users[obj.data] > 1 and split_instances:
            users[obj.data] -= 1
            obj.data = obj.data.copy()  # a mesh of its own, for its own labels
            users[obj.data] = 1
        if obj.data in done:
            summary["labelled"] += 1
            continue
        added = _label_mesh(obj.data, per_vertex, columns, organs) if per_vertex else []
        if organ_node and users[obj.data] == 1:
            added = sorted(set(added) | set(_label_from_extras(obj.data, extras, organs)))
        if added:
            done.add(obj.data)
            summary["labelled"] += 1
            summary["attributes"].update(added)
    summary["attributes"] = sorted(summary["attributes"])
    return summary


class ImportPlantarchGltf(bpy.types.Operator):
    """Import a plantarch glTF/GLB file with its labels as face attributes"""

    bl_idname = "import_scene.plantarch_gltf"
    bl_label = "Import plantarch glTF"
    bl_options = {"REGISTER", "UNDO"}

    filepath: bpy.props.StringProperty(subtype="FILE_PATH")
    filter_glob: bpy.props.StringProperty(default="*.glb;*.gltf", options={"HIDDEN"})
    split_instances: bpy.props.BoolProperty(
        name="Split instances",
        description="Give each organ that shares its mesh (a file written with --nodes organ) "
        "a mesh of its own, so that its faces carry all its labels",
        default=False)

    def execute(self, context):
        try:
            summary = load(self.filepath, split_instances=self.split_instances)
        except (OSError, ValueError, KeyError, RuntimeError) as e:
            self.report({"ERROR"}, "plantarch: %s" % e)
            return {"CANCELLED"}
        self.report({"INFO"}, "plantarch: %d meshes, %d labelled, %d triangles" %
                    (summary["meshes"], summary["labelled"], summary["triangles"]))
        return {"FINISHED"}

    def invoke(self, context, event):
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}


def _menu(self, context):
    self.layout.operator(ImportPlantarchGltf.bl_idname, text="plantarch glTF (.glb/.gltf)")


def register():
    apply_numpy_fix()
    bpy.utils.register_class(ImportPlantarchGltf)
    bpy.types.TOPBAR_MT_file_import.append(_menu)


def unregister():
    bpy.types.TOPBAR_MT_file_import.remove(_menu)
    bpy.utils.unregister_class(ImportPlantarchGltf)


def main(argv):
    """blender -b --python plantarch_import.py -- FILE.glb [--out FILE.blend]
    [--split-instances]: imports FILE into an empty scene and saves it when --out is given."""
    args = argv[argv.index("--") + 1:] if "--" in argv else []
    split = "--split-instances" in args
    args = [a for a in args if a != "--split-instances"]
    out = None
    if "--out" in args:
        at = args.index("--out")
        out = args[at + 1] if at + 1 < len(args) else None
        if out is None:
            print("plantarch_import: --out needs a .blend file name", file=sys.stderr)
            return 2
        del args[at:at + 2]
    if len(args) != 1:
        print("usage: blender -b --python plantarch_import.py -- FILE.glb [--out FILE.blend] "
              "[--split-instances]", file=sys.stderr)
        return 2
    path = args[0]
    if not os.path.isfile(path):
        print("plantarch_import: %s: no such file" % path, file=sys.stderr)
        return 2
    bpy.ops.wm.read_factory_settings(use_empty=True)
    try:
        summary = load(path, split_instances=split)
    except (OSError, ValueError, KeyError, RuntimeError) as e:
        print("plantarch_import: %s: %s" % (path, e), file=sys.stderr)
        return 2
    print("plantarch_import: %s: %d meshes (%d labelled), %d triangles, face attributes %s"
          % (path, summary["meshes"], summary["labelled"], summary["triangles"],
             ", ".join(summary["attributes"]) or "none"))
    if out:
        bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(out))
    return 0


if __name__ == "__main__":
    status = main(sys.argv)
    if status:
        sys.exit(status)
