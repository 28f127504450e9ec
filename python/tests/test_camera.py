"""Cameras and labels in pictures: a fixed camera frames every age alike, its matrices project
a point onto the pixel that shows it at the depth the depth image gives, mask IDs decode to the
objects COCO annotates, and the command line reads plant files and writes the same camera."""

import json
from typing import Any
import subprocess

import numpy as np
import pytest

import plantarch
from conftest import cli


def bean(age):
    a = plantarch.PlantArchitecture(plantarch.Context())
    a.setSeed(4)
    a.loadPlantModelFromLibrary("bean")
    a.buildPlantInstanceFromLibrary((0, 0, 0), age)
    return a


FIXED: dict[str, Any] = dict(eye=(0.8, -0.9, 0.6), target=(0, 0, 0.15))


def test_a_fixed_camera_frames_every_age_alike_and_auto_framing_does_not():
    young, old = bean(10).getContext(), bean(40).getContext()
    assert plantarch.renderCamera(young, **FIXED) == plantarch.renderCamera(old, **FIXED)
    assert plantarch.renderCamera(young) != plantarch.renderCamera(old)


def project(camera, point):
    k, w = np.array(camera["K"]), np.array(camera["world_to_camera"])
    c = w @ np.append(np.asarray(point, float), 1.0)
    uvw = k @ c[:3]
    return uvw[0] / uvw[2], uvw[1] / uvw[2], c[2]


def test_the_matrices_project_a_point_onto_the_pixel_that_shows_it():
    context = plantarch.Context()
    # A 2 cm square facing the camera, centred on a known point, and a second one elsewhere.
    centre = np.array([0.1, 0.05, 0.3])
    corners = centre + np.array([[-0.01, 0, -0.01], [0.01, 0, -0.01], [0.01, 0, 0.01],
                                 [-0.01, 0, 0.01]])
    square = context.addObject(corners, [[0, 1, 2], [0, 2, 3]])
    context.addObject(corners + [0.3, 0.2, 0.0], [[0, 1, 2], [0, 2, 3]])
    view: dict[str, Any] = dict(width=320, height=240, eye=(0.1, -1.0, 0.3), target=(0.1, 0.0, 0.3),
                fov=20.0, ground=False)
    camera = plantarch.renderCamera(context, 320, 240, fov=20.0, eye=view["eye"],
                                    target=view["target"])
    u, v, z = project(camera, centre)
    assert 0 < u < 319 and 0 < v < 239
    ids = plantarch.objectIDsFromLabelImage(plantarch.render(context, mode="object", **view))
    assert ids.shape == (240, 320) and ids.dtype == np.int64
    assert ids[round(v), round(u)] == square
    assert ids[0, 0] == -1  # nothing there
    depth = plantarch.renderDepth(context, **view)
    assert depth[round(v), round(u)] == pytest.approx(z, rel=1e-4)
    assert z == pytest.approx(1.05, rel=1e-6)  # the eye is 1.05 m in front, along y
    # Every pixel showing the square projects back within the square's corners' pixels.
    us, vs = zip(*[project(camera, c)[:2] for c in corners])
    rows, cols = np.nonzero(ids == square)
    assert cols.min() >= min(us) - 1 and cols.max() <= max(us) + 1
    assert rows.min() >= min(vs) - 1 and rows.max() <= max(vs) + 1


def test_mask_ids_are_the_object_ids_coco_annotates():
    a = bean(30)
    context = a.getContext()
    image = plantarch.render(context, width=200, height=150, mode="object", **FIXED)
    ids = plantarch.objectIDsFromLabelImage(image)
    coco = json.loads(plantarch.cocoAnnotations(context, image, "bean.png"))
    annotated = {ann["object_id"]: ann["area"] for ann in coco["annotations"]}
    seen, counts = np.unique(ids[ids >= 0], return_counts=True)
    assert annotated == dict(zip(seen.tolist(), counts.tolist()))
    assert set(annotated) <= set(context.getAllObjectIDs())
    r, g, b = (int(c) for c in image[ids >= 0][0])
    assert plantarch.objectIDFromLabelColor(r, g, b) == int(ids[ids >= 0][0])
    assert plantarch.objectIDFromLabelColor(0, 0, 0) is None


def test_camera_arguments_are_checked():
    context = bean(10).getContext()
    with pytest.raises(plantarch.Error, match="a target needs an eye"):
        plantarch.render(context, target=(0, 0, 0))
    with pytest.raises(plantarch.Error, match="eye and target coincide"):
        plantarch.renderCamera(context, eye=(1, 1, 1), target=(1, 1, 1))
    with pytest.raises(plantarch.Error, match="eye"):
        plantarch.render(context, eye=(1, 2))
    with pytest.raises(plantarch.Error, match="a label image is height x width x 3"):
        plantarch.objectIDsFromLabelImage(np.zeros((4, 4), np.uint8))


def test_the_command_line_renders_plant_files_and_writes_the_same_camera(tmp_path):
    subprocess.run([cli(), "--seed", "4", "build", "bean", "--age", "30", "-o",
                    str(tmp_path / "bean.xml"), "-o", str(tmp_path / "bean.obj")],
                   check=True, capture_output=True)
    for name in ("bean.xml", "bean.obj"):
        subprocess.run([cli(), "render", str(tmp_path / name), "-o", str(tmp_path / (name + ".png")),
                        "--width", "200", "--height", "150", "--eye", "0.8,-0.9,0.6",
                        "--target", "0,0,0.15", "--label", "object",
                        "--camera-json", str(tmp_path / (name + ".json"))],
                       check=True, capture_output=True)
    assert (tmp_path / "bean.xml.png").read_bytes() == (tmp_path / "bean.obj.png").read_bytes()
    written = json.loads((tmp_path / "bean.xml.json").read_text())
    ours = plantarch.renderCamera(bean(30).getContext(), 200, 150, **FIXED)
    assert np.allclose(written["K"], ours["K"]) and np.allclose(written["world_to_camera"],
                                                                ours["world_to_camera"])
    bad = subprocess.run([cli(), "render", str(tmp_path / "bean.xml.json"), "-o",
                          str(tmp_path / "x.png")], capture_output=True, text=True)
    assert bad.returncode == 2
    assert bad.stderr.strip().endswith(
        "(valid: .obj, .ply, .glb or .gltf (geometry), .xml (a plant structure or <helios> file), "
        ".txt (plant strings, with --species))")
    assert not (tmp_path / "x.png").exists()


def test_build_pictures_take_a_fixed_camera_labels_and_write_the_camera(tmp_path):
    view = ["--eye", "0.8,-0.9,0.6", "--target", "0,0,0.15", "--image-size", "200x150",
            "--camera-json"]
    for age in ("20", "40"):
        subprocess.run([cli(), "--seed", "4", "build", "bean", "--age", age, "-o",
                        str(tmp_path / f"bean{age}.png"), "-o", str(tmp_path / f"bean{age}.obj"),
                        "--label", "object"] + view, check=True, capture_output=True)
    young = json.loads((tmp_path / "bean20.camera.json").read_text())
    old = json.loads((tmp_path / "bean40.camera.json").read_text())
    assert young == old  # one framing for every age
    assert young["width"] == 200 and young["height"] == 150
    # The mask's IDs are objects of the plant, as render draws the same scene from its OBJ.
    ids = plantarch.objectIDsFromLabelImage(plantarch.readImage(str(tmp_path / "bean40.png")))
    context = plantarch.Context()
    objects = set(plantarch.readOBJ(context, str(tmp_path / "bean40.obj")))
    assert 0 < len(set(ids[ids >= 0].tolist())) and set(ids[ids >= 0].tolist()) <= objects
    ours = plantarch.renderCamera(bean(40).getContext(), 200, 150, **FIXED)
    assert np.allclose(old["K"], ours["K"]) and np.allclose(old["world_to_camera"],
                                                            ours["world_to_camera"])
    for bad, says in ((["--label", "leaves"], "--label = leaves: unknown label mode (valid: "
                                               "organ, object)"),
                      (["--target", "1,2,3"], "--target requires --eye")):
        run = subprocess.run([cli(), "build", "bean", "--age", "5", "-o",
                              str(tmp_path / "x.png")] + bad, capture_output=True, text=True)
        assert run.returncode == 2 and run.stderr.strip() == "plantarch: " + says
    assert not (tmp_path / "x.png").exists()
