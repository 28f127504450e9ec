"""Python functions as rules, the progress callback, Ctrl-C, and errors."""

import os
import re
import signal

import pytest

import plantarch


def species_with_rule(tmp_path, name):
    """The bean's file with its trifoliate phytomers naming a creation function."""
    text = open(plantarch.speciesLibraryDirectory() + "/bean.xml").read()
    marker = '<shoot_type label="trifoliate"'
    head, tail = text.split(marker, 1)
    body, rest = tail.split("</shoot_type>", 1)
    body = body.replace("</phytomer>", f"<phytomer_creation_function>{name}</phytomer_creation_function></phytomer>", 1)
    path = tmp_path / "bean_rule.xml"
    path.write_text(head + marker + body + "</shoot_type>" + rest)
    return str(path)


def test_a_python_creation_rule_named_in_a_species_file_changes_the_plant(tmp_path):
    seen = []

    def no_branches(ctx):
        seen.append((ctx.nodeIndex, ctx.rank))
        ctx.phytomer.killVegetativeBuds()

    plain = plantarch.PlantArchitecture(plantarch.Context())
    plain.loadPlantModelFromLibrary("bean")
    p = plain.buildPlantInstanceFromLibrary((0, 0, 0), 40)

    a = plantarch.PlantArchitecture(plantarch.Context())
    a.registerPhytomerCreationFunction("no_branches", no_branches)
    a.loadPlantModelFromLibrary(species_with_rule(tmp_path, "no_branches"))
    q = a.buildPlantInstanceFromLibrary((0, 0, 0), 40)
    assert seen, "the rule was never called"
    assert plain.getShootCount(p) > 2
    # Trifoliate shoots make no branches: only the base stem's own shoots remain.
    assert a.getShootCount(q) < plain.getShootCount(p)
    assert all(s["rank"] <= 1 for s in a.getPlant(q).shoot_tree())


def test_a_python_rule_that_scales_leaves_does_what_the_leaf_scale_rule_does(tmp_path):
    def half(ctx):  # unifoliate shoots inherit the function, not the trifoliate's node rules
        if ctx.shoot.shoot_type_label == "trifoliate":
            ctx.phytomer.scaleLeaves(0.5)

    def grown(species, rule):
        a = plantarch.PlantArchitecture(plantarch.Context())
        a.registerPhytomerCreationFunction("half", rule)
        a.loadPlantModelFromLibrary(species)
        return a, a.buildPlantInstanceFromLibrary((0, 0, 0), 30)

    a, small = grown(species_with_rule(tmp_path, "half"), half)
    b, full = grown(species_with_rule(tmp_path, "half"), lambda ctx: None)
    assert a.getPlantLeafArea(small) < 0.6 * b.getPlantLeafArea(full)
    # The same with the species file's own rule: the same plant.
    text = open(plantarch.speciesLibraryDirectory() + "/bean.xml").read()
    head, tail = text.split('<shoot_type label="trifoliate"', 1)
    tail = tail.replace("</node_rules>", "<rule><leaf_scale>0.5</leaf_scale></rule></node_rules>", 1)
    assert "<leaf_scale>0.5</leaf_scale>" in tail
    path = tmp_path / "bean_leaf_scale.xml"
    path.write_text(head + '<shoot_type label="trifoliate"' + tail)
    c, by_rule = grown(str(path), lambda ctx: None)
    assert c.getPlantString(by_rule) == a.getPlantString(small)


def test_a_python_rule_cannot_put_a_plant_out_of_its_ranges(tmp_path):
    """Every trait a rule sets is held to the plant state table's range, as a plant file's
    value is; bookkeeping fields and the lists cannot be set at all."""

    def attempt(change):
        def rule(ctx):
            pt = ctx.phytomer.petioles[0]
            change(ctx.phytomer, pt)

        a = plantarch.PlantArchitecture(plantarch.Context())
        a.registerPhytomerCreationFunction("hostile", rule)
        a.loadPlantModelFromLibrary(species_with_rule(tmp_path, "hostile"))
        return lambda: a.buildPlantInstanceFromLibrary((0, 0, 0), 30)

    cases = [
        (lambda ph, pt: setattr(pt.leaves[0], "leaf_scale", float("nan")), "leaf_scale = nan: out of range"),
        (lambda ph, pt: setattr(ph.internode, "internode_length", 1e30), "internode_length = 1e+30: out of range"),
        (lambda ph, pt: setattr(pt, "petiole_pitch", "steep"), "petiole_pitch = 'steep': not a number"),
        (lambda ph, pt: setattr(pt.vegetative_buds[0], "shoot_type_label", "a b"), "not a label"),
        (lambda ph, pt: setattr(pt.vegetative_buds[0], "state", 3), "not a BudState"),
        (lambda ph, pt: ph.scaleLeaves(float("inf")), "factor = inf: not a finite number"),
        (lambda ph, pt: ph.scaleLeaves(1e30), "makes leaf_scale"),
    ]
    for change, message in cases:
        with pytest.raises(plantarch.Error, match=re.escape(message)):
            attempt(change)()
    for change in (lambda ph, pt: setattr(pt.leaves[0], "leaf_ID", 7),
                   lambda ph, pt: setattr(pt, "leaves", []),
                   lambda ph, pt: setattr(ph, "petioles", []),
                   lambda ph, pt: setattr(ph, "age", 3.0)):
        with pytest.raises(AttributeError):
            attempt(change)()


def test_plant_state_attributes_are_the_plant_files_elements(tmp_path):
    """The Python attributes of the plant state come from the table that writes plant files:
    every element of a written plant names an attribute of its object (a list's element: the
    list, in the plural)."""
    import xml.etree.ElementTree as ET

    a = plantarch.PlantArchitecture(plantarch.Context())
    a.loadPlantModelFromLibrary("bean")
    p = a.buildPlantInstanceFromLibrary((0, 0, 0), 70)
    a.enableEpicormicChildShoots(p, "trifoliate", 0.1)
    root = ET.fromstring(a.getPlantStructureXML([p]))
    state = a.plant(p)
    shoot = next(s for s in state.shoots if any(pt.floral_buds for ph in s.phytomers for pt in ph.petioles))
    phytomer = next(ph for ph in shoot.phytomers if ph.petioles[0].floral_buds)
    petiole = phytomer.petioles[0]
    objects = {
        "plant_instance": state, "shoot": shoot, "phytomer": phytomer, "internode": phytomer.internode,
        "petiole": petiole, "leaf": petiole.leaves[0], "vegetative_bud": shoot.apical_bud,
        "floral_bud": petiole.floral_buds[0], "epicormic_shoots": state.epicormic_shoots,
    }
    grouped = {"peduncle"}  # elements that group fields of their own object

    def plural(element):
        return element[:-1] + "ves" if element.endswith("leaf") else element + "s"

    def structure(element):  # not into the parameters, which have elements of the same names
        yield element
        for child in element:
            if child.tag not in ("shoot_type", "phenology"):
                yield from structure(child)

    checked = set()
    for element in structure(root):
        obj = objects.get(element.tag)
        if obj is None:
            continue
        children = [c for c in element if c.tag not in grouped] + [
            g for c in element if c.tag in grouped for g in c]
        for child in children:
            if child.tag in ("random_generator", "phenology", "shoot_type"):
                continue  # the plant's generator is its own; parameters are bound from their table
            owner = phytomer if (element.tag, child.tag) == ("internode", "petiole") else obj
            name = plural(child.tag) if child.tag in (
                "shoot", "phytomer", "petiole", "leaf", "vegetative_bud", "floral_bud",
                "terminal_floral_bud", "flower") else child.tag
            assert hasattr(owner, name), f"<{element.tag}><{child.tag}>: no {type(owner).__name__}.{name}"
            checked.add((element.tag, child.tag))
    assert len(checked) > 90
    assert hasattr(state, "shoot_types") and hasattr(state, "phenology")


def test_a_python_callback_runs_daily(tmp_path):
    days = set()
    text = open(species_with_rule(tmp_path, "x")).read().replace(
        "phytomer_creation_function>x<", "phytomer_callback_function>daily<")
    text = text.replace("</phytomer_creation_function>", "</phytomer_callback_function>")
    path = tmp_path / "bean_daily.xml"
    path.write_text(text)
    a = plantarch.PlantArchitecture(plantarch.Context())
    a.registerPhytomerCallbackFunction("daily", lambda ctx: days.add(int(ctx.plantAge)))
    a.loadPlantModelFromLibrary(str(path))
    a.buildPlantInstanceFromLibrary((0, 0, 0), 20)
    assert len(days) >= 15


def test_an_exception_in_a_rule_reaches_python_as_itself(tmp_path):
    def broken(ctx):
        raise KeyError("my rule failed")

    a = plantarch.PlantArchitecture(plantarch.Context())
    a.registerPhytomerCreationFunction("broken", broken)
    a.loadPlantModelFromLibrary(species_with_rule(tmp_path, "broken"))
    with pytest.raises(KeyError, match="my rule failed"):
        a.buildPlantInstanceFromLibrary((0, 0, 0), 30)
    # In a canopy too, with the plant it stopped as a note, and nothing is left behind.
    with pytest.raises(KeyError, match="my rule failed") as e:
        a.buildPlantCanopyFromLibrary((0, 0, 0), (0.3, 0.3), (2, 2), 30)
    assert "plantarch: building canopy plant 0 failed: KeyError: 'my rule failed'" in e.value.__notes__
    assert a.getContext().getObjectCount() == 0


def test_progress_callback_and_stopping_a_canopy():
    a = plantarch.PlantArchitecture(plantarch.Context())
    a.loadPlantModelFromLibrary("bean")
    seen = []
    a.setProgressCallback(lambda stage, fraction: seen.append((stage, fraction)))
    a.buildPlantCanopyFromLibrary((0, 0, 0), (0.3, 0.3), (4, 4), 20)
    assert seen[-1] == ("building", 1.0)
    assert [f for _, f in seen] == sorted(f for _, f in seen)

    def stop(stage, fraction):
        if fraction > 0.2:
            raise RuntimeError("enough")

    objects = a.getContext().getObjectCount()
    a.setProgressCallback(stop)
    with pytest.raises(RuntimeError, match="enough"):
        a.buildPlantCanopyFromLibrary((5, 0, 0), (0.3, 0.3), (4, 4), 20)
    assert a.getContext().getObjectCount() == objects  # all or nothing
    a.setProgressCallback(None)
    assert len(a.buildPlantCanopyFromLibrary((5, 0, 0), (0.3, 0.3), (2, 2), 20)) == 4


def test_ctrl_c_stops_a_long_canopy_build_cleanly():
    a = plantarch.PlantArchitecture(plantarch.Context())
    a.loadPlantModelFromLibrary("bean")
    # Ctrl-C once the build is under way: sent from the first progress report after the
    # start (a timer could fire before the build starts or, on a busy machine, after it ends).
    sent, reports = [], []

    def progress(stage, fraction):
        reports.append((stage, round(fraction, 3)))
        if fraction > 0 and not sent:
            sent.append((stage, fraction))
            os.kill(os.getpid(), signal.SIGINT)

    a.setProgressCallback(progress)
    # Python turns Ctrl-C into KeyboardInterrupt only if SIGINT was not ignored when it
    # started; a background job of a non-interactive shell starts with it ignored.
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        a.buildPlantCanopyFromLibrary((0, 0, 0), (0.3, 0.3), (40, 40), 50)
    except KeyboardInterrupt:
        pass
    else:
        pytest.fail(f"no KeyboardInterrupt: interrupt sent at {sent}, {len(reports)} progress "
                    f"reports, first {reports[:4]}, last {reports[-4:]}")
    finally:
        signal.signal(signal.SIGINT, previous)
    assert sent  # the interrupt came during the build
    assert reports[-1][1] < 1  # and stopped it before its end
    assert a.getContext().getObjectCount() == 0
    assert a.getAllPlantIDs() == []


def test_errors_are_plantarch_errors_with_one_line():
    a = plantarch.PlantArchitecture(plantarch.Context())
    with pytest.raises(plantarch.Error) as e:
        a.loadPlantModelFromLibrary("no_such_plant")
    assert "\n" not in str(e.value) and "no_such_plant" in str(e.value)
    with pytest.raises(plantarch.Error, match="plantID"):
        a.getPlantHeight(12)
    a.loadPlantModelFromLibrary("bean")
    with pytest.raises(plantarch.Error, match="plantarch.Error|age|range"):
        a.buildPlantInstanceFromLibrary((0, 0, 0), -5)
    with pytest.raises(plantarch.Error, match="not three numbers"):
        a.enableAttractionPoints([(0, 0)])
    with pytest.raises(TypeError):
        a.setSeed(-1)


def test_a_leaf_prototype_written_in_python(arch):
    import numpy as np

    calls = []

    def square_leaf(params, leaflet):
        calls.append(leaflet)
        positions = np.array([[0, -0.2, 0], [1, -0.2, 0], [1, 0.2, 0], [0, 0.2, 0]], np.float32)
        mesh = plantarch.Mesh(positions, np.array([[0, 1, 2], [0, 2, 3]], np.uint32))
        return [(mesh, plantarch.Material(color=(0.1, 0.5, 0.1)))]

    arch.registerLeafPrototype("square", square_leaf)
    assert arch.hasLeafPrototype("square")
    for label in arch.listShootTypeLabels():
        p = arch.getCurrentShootParameters(label)
        p.phytomer_parameters.leaf.prototype.prototype_function = "square"
        arch.updateCurrentShootParameters(label, p)
    plant = arch.buildPlantInstanceFromLibrary((0, 0, 0), 30)
    assert calls
    leaves = arch.getPlantObjectIDs(plant, plantarch.OrganKind.leaf)
    ctx = arch.getContext()
    assert leaves and all(ctx.getObjectMesh(o).triangleCount() == 2 for o in leaves)
    arch.registerLeafPrototype("broken", lambda params, leaflet: 42)
    p = arch.getCurrentShootParameters("trifoliate")
    p.phytomer_parameters.leaf.prototype.prototype_function = "broken"
    arch.updateCurrentShootParameters("trifoliate", p)
    with pytest.raises(plantarch.Error, match="must return a Mesh"):
        arch.buildPlantInstanceFromLibrary((1, 0, 0), 30)


def test_bud_actions_from_python_do_what_the_species_rules_do(tmp_path):
    """The bean's three bud rules taken out of its file and done by a Python creation function
    with the phytomer's killFloralBuds / killVegetativeBuds grow the same plant, byte for
    byte: the Python actions are the rules' own."""
    text = open(plantarch.speciesLibraryDirectory() + "/bean.xml").read()
    rules = re.findall(r"\s*<rule>(?:(?!</rule>).)*?remove_(?:floral|vegetative)_buds.*?</rule>",
                       text, re.S)
    assert len(rules) == 3
    for rule in rules:
        text = text.replace(rule, "", 1)
    path = tmp_path / "bean_python_buds.xml"
    path.write_text(text.replace(
        "</node_rules>\n    </phytomer>\n  </shoot_type>",
        "</node_rules>\n      <phytomer_creation_function>buds</phytomer_creation_function>\n"
        "    </phytomer>\n  </shoot_type>", 1))

    calls = []

    def buds(ctx):
        if ctx.shoot.shoot_type_label != "trifoliate":
            return
        calls.append(ctx.nodeIndex)
        if ctx.rank <= 1 and ctx.nodeIndex <= 5:
            ctx.phytomer.killFloralBuds()
        if ctx.nodeIndex >= 6 or ctx.rank >= 2:
            ctx.phytomer.killVegetativeBuds()

    def grown(species, rule=None):
        a = plantarch.PlantArchitecture(plantarch.Context())
        a.setSeed(5)
        if rule:
            a.registerPhytomerCreationFunction("buds", rule)
        a.loadPlantModelFromLibrary(species)
        p = a.buildPlantInstanceFromLibrary((0, 0, 0), 60)
        plantarch.writePLY(a.getContext(), str(tmp_path / "plant.ply"))
        return a, p, a.getPlantString(p), (tmp_path / "plant.ply").read_bytes()

    a, p, string, ply = grown("bean")
    b, q, string_py, ply_py = grown(str(path), buds)
    assert calls, "the function was never called"
    def floral_buds(arch, plant):
        return [fb for s in arch.plant(plant).shoots for ph in s.phytomers
                for pt in ph.petioles for fb in pt.floral_buds]

    assert a.getShootCount(p) > 3  # branches
    assert any(fb.stage != plantarch.FloralStage.bud for fb in floral_buds(a, p))  # flowers
    assert string_py == string
    assert ply_py == ply
    # A floral bud killed by the Python call is removed, as the rule leaves it.
    dead = [fb.stage for fb in floral_buds(b, q) if fb.state == plantarch.BudState.dead]
    assert dead and set(dead) == {plantarch.FloralStage.removed}
