"""Procedural textures from Python: textured glTF, USD (.usda beside its PNGs, .usdz package),
OBJ and pictures, the leaves' texture atlas read through texture transforms in each, and
texture sizes refused with plantarch.Error."""

import math
import pathlib
import struct
import zipfile
import zlib

import pytest

import plantarch
import usda
from conftest import glb_json




def test_textured_glb_embeds_maps_and_flat_is_the_default(bean, tmp_path):
    ctx = bean.getContext()
    plantarch.writeGLTF(ctx, str(tmp_path / "flat.glb"), architecture=bean)
    plantarch.writeGLTF(ctx, str(tmp_path / "tex.glb"), architecture=bean,
                        appearance="textured", texture_size=64)
    assert "images" not in glb_json(tmp_path / "flat.glb")
    doc = glb_json(tmp_path / "tex.glb")
    assert doc["images"] and all(i["mimeType"] == "image/png" for i in doc["images"])
    leaf = [m for m in doc["materials"] if m.get("name") == "leaf"
            and "baseColorTexture" in m["pbrMetallicRoughness"]]
    assert leaf and all(m["alphaMode"] == "MASK" and "normalTexture" in m for m in leaf)


def test_usda_and_usdz(bean, tmp_path):
    ctx = bean.getContext()
    plantarch.writeUSDA(ctx, str(tmp_path / "bean.usda"), appearance="textured", texture_size=32,
                        atlas=False)
    layer, prims = usda.read(tmp_path / "bean.usda")  # the text parses
    (root,) = prims
    looks = [c for c in root.children if c.name == "Looks"]
    assert looks and looks[0].children
    pngs = sorted(p.name for p in tmp_path.glob("bean_*.png"))
    assert "bean_leaf_0_basecolor.png" in pngs and "bean_bark_0_normal.png" in pngs
    plantarch.writeUSDA(ctx, str(tmp_path / "bean.usdz"), appearance="textured", texture_size=32,
                        atlas=False)
    with zipfile.ZipFile(tmp_path / "bean.usdz") as z:
        assert z.testzip() is None
        infos = z.infolist()
        assert infos[0].filename == "bean.usda"
        assert all(i.compress_type == zipfile.ZIP_STORED for i in infos)
        raw = (tmp_path / "bean.usdz").read_bytes()
        for i in infos:
            name_length, extra_length = struct.unpack_from("<HH", raw, i.header_offset + 26)
            assert (i.header_offset + 30 + name_length + extra_length) % 64 == 0, i.filename
        assert "leaf_0_basecolor.png" in z.namelist()
        assert b"@./leaf_0_basecolor.png@" in z.read("bean.usda")


def test_obj_maps_and_textured_render(bean, tmp_path):
    ctx = bean.getContext()
    plantarch.writeOBJ(ctx, str(tmp_path / "bean.obj"), appearance="textured", texture_size=32,
                       atlas=False)
    mtl = (tmp_path / "bean.mtl").read_text()
    assert "map_Kd bean_leaf_0_basecolor.png" in mtl and "map_d bean_leaf_0_alpha.png" in mtl
    flat = plantarch.render(ctx, width=96, height=72)
    textured = plantarch.render(ctx, width=96, height=72, appearance="textured", texture_size=64)
    assert flat.shape == textured.shape and (flat != textured).any()


def test_glb_atlas_one_image_per_kind_with_transforms(bean, tmp_path):
    ctx = bean.getContext()
    plantarch.writeGLTF(ctx, str(tmp_path / "atlas.glb"), appearance="textured", texture_size=32)
    plantarch.writeGLTF(ctx, str(tmp_path / "own.glb"), appearance="textured", texture_size=32,
                        atlas=False)
    atlas, own = glb_json(tmp_path / "atlas.glb"), glb_json(tmp_path / "own.glb")
    assert "KHR_texture_transform" not in own.get("extensionsUsed", [])
    assert "KHR_texture_transform" in atlas["extensionsUsed"]
    assert "KHR_texture_transform" in atlas["extensionsRequired"]
    leaves = [m for m in atlas["materials"] if m.get("name") == "leaf"]
    assert len(leaves) >= 2
    # Every map of a leaf reads the atlas (one image per kind) through the same transform.
    infos = [[m["pbrMetallicRoughness"]["baseColorTexture"],
              m["pbrMetallicRoughness"]["metallicRoughnessTexture"],
              m["normalTexture"], m["occlusionTexture"]] for m in leaves]
    sources = {kind: {atlas["textures"][i[kind]["index"]]["source"] for i in infos}
               for kind in range(4)}
    assert all(len(s) == 1 for s in sources.values())
    transforms = [[i["extensions"]["KHR_texture_transform"] for i in info] for info in infos]
    assert all(all(t == ts[0] for t in ts) for ts in transforms)
    parts = {tuple(ts[0]["offset"]) for ts in transforms}
    assert len(parts) >= 2  # the leaf colours in different parts
    for ts in transforms:
        assert all(0 <= o < 1 and 0 < s < 1 for o, s in zip(ts[0]["offset"], ts[0]["scale"]))
    # The atlas replaces the leaves' own images: fewer images, and bark keeps its own.
    assert len(atlas["images"]) < len(own["images"])
    bark = [m for m in atlas["materials"] if m.get("name") == "bark"]
    assert bark and "extensions" not in bark[0]["pbrMetallicRoughness"]["baseColorTexture"]


def test_usda_atlas_transform_network(bean, tmp_path):
    ctx = bean.getContext()
    plantarch.writeUSDA(ctx, str(tmp_path / "bean.usda"), appearance="textured", texture_size=32)
    _, (root,) = usda.read(tmp_path / "bean.usda")
    looks = root.child("Looks")
    transformed = 0
    for material in looks.children:
        shaders = {c.name: c for c in material.children}
        if "Transform" not in shaders:
            continue
        transformed += 1
        path = f"</plantarch/Looks/{material.name}"
        t = shaders["Transform"]
        assert t.attributes["info:id"]["value"] == "UsdTransform2d"
        assert t.attributes["inputs:in.connect"]["value"] == path + "/TexCoord.outputs:result>"
        scale, translation = (t.attributes["inputs:scale"]["value"],
                              t.attributes["inputs:translation"]["value"])
        assert all(0 < s < 1 for s in scale) and all(0 <= x < 1 for x in translation)
        for name in ("BaseColor", "Normal", "ORM"):
            texture = shaders[name].attributes
            assert texture["inputs:st.connect"]["value"] == path + "/Transform.outputs:result>"
            assert "atlas_" in texture["inputs:file"]["value"]
    assert transformed >= 2
    pngs = sorted(p.name for p in tmp_path.glob("bean_*.png"))
    assert "bean_atlas_basecolor.png" in pngs and "bean_bark_0_basecolor.png" in pngs
    assert not any(p.startswith("bean_leaf_") for p in pngs)


def test_obj_atlas_offsets_and_scales(bean, tmp_path):
    ctx = bean.getContext()
    plantarch.writeOBJ(ctx, str(tmp_path / "bean.obj"), appearance="textured", texture_size=32)
    mtl = (tmp_path / "bean.mtl").read_text()
    lines = [l.split() for l in mtl.splitlines() if l.startswith(("map_", "norm"))]
    atlas = [l for l in lines if l[-1].startswith("bean_atlas_")]
    assert atlas and all(l[1] == "-o" and l[4] == "-s" and len(l) == 8 for l in atlas)
    assert all(0 < float(x) < 1 for l in atlas for x in l[5:7])
    assert (tmp_path / "bean_atlas_basecolor.png").exists()
    own = [l for l in lines if not l[-1].startswith("bean_atlas_")]
    assert own and all(len(l) == 2 for l in own)  # bark and stems: no transform


def test_atlas_render_matches_separate_images(bean):
    ctx = bean.getContext()
    with_atlas = plantarch.render(ctx, width=96, height=72, appearance="textured",
                                  texture_size=64)
    without = plantarch.render(ctx, width=96, height=72, appearance="textured", texture_size=64,
                               atlas=False)
    assert abs(with_atlas.astype(int) - without.astype(int)).mean() < 0.5


@pytest.mark.parametrize("size", [0, -8, 100, 8, 8192, 2**40, 2**70, math.nan, 64.0, "64", True])
def test_bad_texture_sizes_are_plantarch_errors(bean, tmp_path, size):
    with pytest.raises(plantarch.Error, match="texture"):
        plantarch.writeGLTF(bean.getContext(), str(tmp_path / "x.glb"), appearance="textured",
                            texture_size=size)
    assert not list(tmp_path.iterdir())


def test_unknown_appearance_is_a_plantarch_error(bean, tmp_path):
    with pytest.raises(plantarch.Error, match="flat, textured"):
        plantarch.writeUSDA(bean.getContext(), str(tmp_path / "x.usda"), appearance="shiny")


def _png_pixels(data):
    """Rows of byte tuples (one per pixel) of an 8-bit, non-interlaced PNG."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    at, idat = 8, b""
    while at < len(data):
        (length,), kind = struct.unpack_from(">I", data, at), data[at + 4:at + 8]
        body = data[at + 8:at + 8 + length]
        if kind == b"IHDR":
            width, height, depth, color = struct.unpack_from(">IIBB", body)
            assert depth == 8
        elif kind == b"IDAT":
            idat += body
        at += 12 + length
    channels = {0: 1, 2: 3, 4: 2, 6: 4}[color]
    raw, stride = zlib.decompress(idat), width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        start = y * (stride + 1)
        kind, line = raw[start], bytearray(raw[start + 1:start + 1 + stride])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b, c = previous[i], previous[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[x * channels:(x + 1) * channels]) for x in range(width)])
        previous = line
    return rows


def _glb_image(path, doc, texture):
    """The decoded image of a texture of a .glb."""
    data = pathlib.Path(path).read_bytes()
    (json_length,) = struct.unpack_from("<I", data, 12)
    binary = 20 + json_length + 8
    view = doc["bufferViews"][doc["images"][doc["textures"][texture]["source"]]["bufferView"]]
    start = binary + view.get("byteOffset", 0)
    return _png_pixels(data[start:start + view["byteLength"]])


def test_glb_atlas_parts_hold_the_texels_of_the_separate_images(bean, tmp_path):
    # glTF's own reading: texture coordinates (u, t) through KHR_texture_transform onto the
    # atlas sample the very texels (u, t) samples in the leaf's separate image.
    ctx = bean.getContext()
    plantarch.writeGLTF(ctx, str(tmp_path / "atlas.glb"), appearance="textured", texture_size=32)
    plantarch.writeGLTF(ctx, str(tmp_path / "own.glb"), appearance="textured", texture_size=32,
                        atlas=False)
    atlas, own = glb_json(tmp_path / "atlas.glb"), glb_json(tmp_path / "own.glb")
    checked = 0
    for mine, theirs in zip(atlas["materials"], own["materials"]):
        for where in ("baseColorTexture", "metallicRoughnessTexture"):
            info = mine["pbrMetallicRoughness"].get(where, {})
            if "extensions" not in info:
                continue
            t = info["extensions"]["KHR_texture_transform"]
            big = _glb_image(tmp_path / "atlas.glb", atlas, info["index"])
            small = _glb_image(tmp_path / "own.glb", own,
                               theirs["pbrMetallicRoughness"][where]["index"])
            n, width, height = len(small), len(big[0]), len(big)
            for y in range(n):
                for x in range(n):
                    u, v = (x + 0.5) / n, (y + 0.5) / n
                    bx = int((t["offset"][0] + t["scale"][0] * u) * width)
                    by = int((t["offset"][1] + t["scale"][1] * v) * height)
                    assert big[by][bx] == small[y][x], (where, x, y)
            checked += 1
    assert checked >= 4
