"""Parameters: attributes, docs and ranges from the one table; checked assignments; round trips."""

import json
import socket
import subprocess
import time
import urllib.request

import pytest
from conftest import cli

import plantarch


def walk(obj, path):
    for part in path.split(".")[:-1]:
        obj = getattr(obj, "phytomer_parameters" if part == "phytomer" else part)
    return obj, path.split(".")[-1]


def test_node_rule_fields_come_from_the_table_too():
    infos = [i for i in plantarch.parameterInfo(plantarch.ShootParameters()) if ".rule." in i["path"]]
    rule = plantarch.NodeRule()
    assert infos
    for info in infos:
        assert info["doc"] in getattr(plantarch.NodeRule, info["name"]).__doc__
    rule.node_max = 5
    rule.leaf_scale = "min(1, 0.5 + age / 10)"
    with pytest.raises(plantarch.Error, match="rule.leaf_scale"):
        rule.leaf_scale = "min(1, "
    p = plantarch.ShootParameters()
    p.phytomer_parameters.node_rules = [rule]
    assert p.phytomer_parameters.node_rules[0].leaf_scale == "min(1, 0.5 + age / 10)"


def test_every_table_field_is_an_attribute_with_its_doc_unit_and_range():
    params = plantarch.ShootParameters()
    infos = plantarch.parameterInfo(params)
    assert len(infos) > 100
    for info in infos:
        if ".rule." in info["path"]:  # fields of list elements (NodeRule, below)
            continue
        owner, name = walk(params, info["path"])
        cls_attr = getattr(type(owner), name)
        doc = cls_attr.__doc__
        assert info["doc"] in doc, info["path"]
        if info["unit"]:
            assert info["unit"] in doc, info["path"]
        if info["range"]:
            assert info["range"] in doc, info["path"]
        getattr(owner, name)  # readable


def test_no_attribute_outside_the_table():
    infos = plantarch.parameterInfo(plantarch.ShootParameters())
    names = {i["path"].split(".")[0] for i in infos} | {"phytomer_parameters"}
    attrs = {a for a in dir(plantarch.ShootParameters) if not a.startswith("_")}
    methods = {a for a in attrs if callable(getattr(plantarch.ShootParameters, a))}
    assert attrs - methods - names == set()


def test_out_of_range_assignment_raises_the_species_file_message(tmp_path):
    p = plantarch.ShootParameters()
    with pytest.raises(plantarch.Error) as py_error:
        p.phytomer_parameters.petiole.pitch = 200
    assert str(py_error.value) == "petiole.pitch = 200: out of range (valid: -180 to 180)"
    assert py_error.value.parameter == "petiole.pitch"
    assert py_error.value.valid_range == "-180 to 180"
    assert isinstance(py_error.value, ValueError)
    assert p.phytomer_parameters.petiole.pitch == 90  # unchanged
    # The same value in a species file: the same text, after the file's own path prefix.
    bean = plantarch.speciesLibraryDirectory() + "/bean.xml"
    text = open(bean).read()
    start = text.index("<petiole>", text.index('<shoot_type label="trifoliate"'))
    pitch = text.index("<pitch>", start)
    text = text[:pitch] + "<pitch>200</pitch>" + text[text.index("</pitch>", pitch) + 8:]
    bad = tmp_path / "bad.xml"
    bad.write_text(text)
    a = plantarch.PlantArchitecture(plantarch.Context())
    with pytest.raises(plantarch.Error) as file_error:
        a.loadPlantModelFromLibrary(str(bad))
    assert str(file_error.value).endswith(str(py_error.value))


@pytest.mark.parametrize(
    "path,value,fragment",
    [
        ("max_nodes", 0, "max_nodes = 0: out of range (valid: 1 to 100000)"),
        ("max_nodes", 2.5, "not a whole number"),
        ("phyllochron_min", "fast", "not a number or a distribution"),
        ("phytomer.leaf.prototype.shape", "blob", "not a declared value (valid: one of: elliptic"),
        ("phytomer.internode.color", (1, 2), "not three numbers"),
        ("phytomer.internode.color", (0.1, 0.2, 3), "out of range (valid: 0 to 1)"),
        ("vegetative_bud_break_probability_min", plantarch.uniform(0.5, 1.5), "out of range"),
        ("insertion_angle_tip", float("nan"), "not a finite number"),
        ("determinate_shoot_growth", 1, "not True or False"),
        ("child_shoot_types", {"a": 0.5}, "probabilities must sum to 1"),
    ],
)
def test_bad_values_are_rejected_at_once(path, value, fragment):
    p = plantarch.ShootParameters()
    owner, name = walk(p, path)
    before = getattr(owner, name)
    with pytest.raises(plantarch.Error, match=None) as e:
        setattr(owner, name, value)
    assert fragment in str(e.value)
    assert getattr(owner, name) == before


def test_random_parameters():
    p = plantarch.ShootParameters()
    p.insertion_angle_tip = plantarch.uniform(40, 60)
    assert p.insertion_angle_tip == plantarch.uniform(40, 60)
    assert str(p.insertion_angle_tip) == "uniform(40, 60)"
    p.gravitropic_curvature = plantarch.normal(10, 2)
    assert p.gravitropic_curvature.kind == "normal" and p.gravitropic_curvature.mean() == 10
    p.tortuosity = plantarch.weibull(1.5, 2)
    assert p.tortuosity.kind == "weibull"
    p.max_nodes = plantarch.uniform(3, 5)  # whole bounds: a whole-number uniform
    assert isinstance(p.max_nodes, plantarch.RandomInt) and (p.max_nodes.min, p.max_nodes.max) == (3, 5)
    p.max_nodes = plantarch.discrete([2, 5, 11])
    assert p.max_nodes.values == [2, 5, 11]
    p.max_nodes = 12
    assert p.max_nodes == 12 and isinstance(p.max_nodes, int)
    with pytest.raises(plantarch.Error):
        plantarch.uniform(5, 1)


def test_groups_are_views_and_copies_are_independent():
    p = plantarch.ShootParameters()
    leaf = p.phytomer_parameters.leaf
    leaf.prototype_scale = 0.2
    assert p.phytomer_parameters.leaf.prototype_scale == pytest.approx(0.2)
    q = p.copy()
    q.phytomer_parameters.leaf.prototype_scale = 0.3
    assert p.phytomer_parameters.leaf.prototype_scale == pytest.approx(0.2)


def test_library_parameters_round_trip_unchanged(arch):
    for label in arch.listShootTypeLabels():
        original = arch.getCurrentShootParameters(label)
        before = plantarch.parameterInfo(original)
        copy = plantarch.ShootParameters()
        for info in before:  # set every field from Python, one by one
            if ".rule." in info["path"]:
                continue
            owner, name = walk(original, info["path"])
            target, _ = walk(copy, info["path"])
            setattr(target, name, getattr(owner, name))
        arch.updateCurrentShootParameters(label, copy)
        after = plantarch.parameterInfo(arch.getCurrentShootParameters(label))
        assert [i["value"] for i in after] == [i["value"] for i in before], label


def test_editing_a_library_species_keeps_its_named_rules():
    # Maize's tassel is its own shoot type and its rules are named; editing the main stem's
    # parameters from Python must not give every node a tassel.
    def build(edit):
        a = plantarch.PlantArchitecture(plantarch.Context())
        a.loadPlantModelFromLibrary("maize")
        if edit:
            for label in a.listShootTypeLabels():
                p = a.getCurrentShootParameters(label)
                p.phytomer_parameters.leaf.prototype_scale = p.phytomer_parameters.leaf.prototype_scale
                a.updateCurrentShootParameters(label, p)
        plant = a.buildPlantInstanceFromLibrary((0, 0, 0), 60)
        return a, plant

    a, p = build(False)
    b, q = build(True)
    assert a.getPlantString(p) == b.getPlantString(q)
    rules = {l: a.getCurrentShootParameters(l).phytomer_parameters.node_rules for l in a.listShootTypeLabels()}
    edited = {l: b.getCurrentShootParameters(l).phytomer_parameters.node_rules for l in b.listShootTypeLabels()}
    assert [len(r) for r in rules.values()] == [len(r) for r in edited.values()]
    assert any(rules.values())  # the species has named rules to keep


def test_phenology_parameters():
    t = plantarch.PhenologyParameters()
    t.time_to_flower_opening = 12
    assert t.to_dict()["time_to_flower_opening"] == 12
    with pytest.raises(plantarch.Error, match="phenology.max_age = -1"):
        t.max_age = -1


def test_parameter_info_is_the_builders_json(arch, tmp_path):
    # One JSON form of the parameter table (parameterInfoJson): the builder's species endpoint
    # and parameterInfo() give the same objects for the same shoot type.
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        port = probe.getsockname()[1]
    server = subprocess.Popen([cli(), "builder", "--port", str(port), "--output", str(tmp_path)],
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        detail = None
        for _ in range(600):
            assert server.poll() is None, "plantarch builder exited"
            try:
                with urllib.request.urlopen(f"http://127.0.0.1:{port}/api/species/bean") as r:
                    detail = json.load(r)
                break
            except OSError:
                time.sleep(0.05)
        assert detail is not None, "plantarch builder did not answer"
    finally:
        server.terminate()
        server.wait()
    assert detail["shoot_types"]
    for label, fields in detail["shoot_types"].items():
        assert plantarch.parameterInfo(arch.getCurrentShootParameters(label)) == fields, label
    keys = ["path", "name", "unit", "doc", "kind", "min", "max", "range", "choices", "entry",
            "probabilities", "value"]
    assert all(list(f) == keys for f in plantarch.parameterInfo(plantarch.ShootParameters()))
