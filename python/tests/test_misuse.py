"""The module under misuse: threads, re-entry from rules, handles kept too long, bad IDs, the
first numpy call from two threads, and Python exceptions raised inside rules."""

import gc
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time
import traceback

import pytest

import plantarch
from plantarch import _plantarch
from test_rules import species_with_rule


def bean(seed=3):
    a = plantarch.PlantArchitecture(plantarch.Context())
    a.setSeed(seed)
    a.loadPlantModelFromLibrary("bean")
    return a


def run_threads(targets, timeout=300):
    """Runs the functions on threads at once; returns the exceptions they raised. Daemon
    threads and a timeout: a deadlock fails the test instead of hanging it."""
    errors = []
    start = threading.Barrier(len(targets))

    def body(fn):
        try:
            start.wait()
            fn()
        except BaseException as e:  # noqa: B036 - every failure is reported
            errors.append("".join(traceback.format_exception(e)))

    threads = [threading.Thread(target=body, args=(t,), daemon=True) for t in targets]
    for t in threads:
        t.start()
    for t in threads:
        t.join(timeout)
        assert not t.is_alive(), "a thread is still running: deadlock?"
    return errors


# ---- every call is guarded ---------------------------------------------------------------

def bound_functions():
    for cls in (plantarch.PlantArchitecture, plantarch.Context):
        for name, value in vars(cls).items():
            if callable(value) and type(value).__name__ in ("instancemethod", "builtin_function_or_method"):
                yield f"{cls.__name__}.{name}", value
    for name in ("writeOBJ", "writePLY", "writeGLTF", "writeUSDA", "samplePoints", "scan",
                 "writePointCloudPLY", "writeQSM", "readOBJ", "render", "renderDepth"):
        yield name, getattr(_plantarch, name)


def test_every_method_of_the_architecture_and_context_takes_the_lock():
    found = dict(bound_functions())
    assert len(found) > 150  # the wrap saw the classes' methods, not an empty dict
    assert "PlantArchitecture.getMeshArrays" in found  # bound in another file, later
    unguarded = [name for name, fn in found.items() if not _plantarch._guarded(fn)]  # pyright: ignore
    assert unguarded == []


# ---- threads -------------------------------------------------------------------------------

def grown_serially(days):
    a = bean()
    ids = a.buildPlantCanopyFromLibrary((0, 0, 0), (0.4, 0.4), (2, 2), 5)
    for _ in range(days):
        a.advanceTime(1.0)
    return a, ids


def test_threads_growing_and_reading_one_architecture_get_the_serial_result():
    serial, ids = grown_serially(12)
    a = bean()
    assert a.buildPlantCanopyFromLibrary((0, 0, 0), (0.4, 0.4), (2, 2), 5) == ids
    progress = []
    a.setProgressCallback(lambda stage, fraction: progress.append(fraction))  # needs the GIL
    context = a.getContext()
    growing = threading.Event()
    growing.set()
    reads = []

    def grower():
        for _ in range(3):
            a.advanceTime(1.0)

    def reader():
        while growing.is_set():
            mesh = a.getMeshArrays(ids)
            heights = [a.getPlantHeight(p) for p in ids]
            objects = context.getObjectCount()
            state = a.plant(ids[0])
            reads.append((len(mesh["triangles"]), sum(heights), objects, len(state.shoots)))

    def growers_then_stop():
        try:
            assert run_threads([grower] * 4) == []
        finally:
            growing.clear()

    errors = run_threads([growers_then_stop, reader, reader])
    assert errors == []
    assert reads and progress
    for p in ids:
        assert a.getPlantAge(p) == serial.getPlantAge(p) == 17
    assert a.getPlantStructureXML(ids) == serial.getPlantStructureXML(ids)
    assert a.getContext().getTriangleCount() == serial.getContext().getTriangleCount()


def test_threads_building_into_one_architecture_each_get_their_plants():
    a = bean()
    built = []

    def builder(x):
        return lambda: built.append(a.buildPlantCanopyFromLibrary((x, 0, 0), (0.3, 0.3), (2, 1), 10))

    def single(x):
        return lambda: built.append([a.buildPlantInstanceFromLibrary((x, 5, 0), 10)])

    assert run_threads([builder(0), builder(3), single(6), single(9)]) == []
    ids = sorted(p for group in built for p in group)
    assert ids == a.getAllPlantIDs() == list(range(6))
    mesh = a.getMeshArrays()
    assert set(mesh["plant_id"].tolist()) == set(ids)


def test_two_architectures_sharing_a_context_take_turns():
    def pair(context):
        archs = []
        for seed in (1, 2):
            a = plantarch.PlantArchitecture(context)
            a.setSeed(seed)
            a.loadPlantModelFromLibrary("bean")
            a.buildPlantInstanceFromLibrary((seed, 0, 0), 5)
            archs.append(a)
        return archs

    serial = pair(plantarch.Context())
    for a in serial:
        for _ in range(6):
            a.advanceTime(2.0)
    context = plantarch.Context()
    archs = pair(context)
    sizes = []

    def grow(a):
        return lambda: [a.advanceTime(2.0) for _ in range(6)]

    def read():
        for _ in range(20):
            sizes.append(len(context.getMeshArrays()["triangles"]))

    assert run_threads([grow(archs[0]), grow(archs[1]), read]) == []
    assert len(sizes) == 20
    for a, b in zip(archs, serial):
        assert a.getPlantStructureXML(a.getAllPlantIDs()) == b.getPlantStructureXML(b.getAllPlantIDs())


def test_a_waiting_thread_lets_python_run():
    a = bean()
    a.buildPlantCanopyFromLibrary((0, 0, 0), (0.3, 0.3), (3, 3), 5)
    ticks, counts = [], []
    started = threading.Event()

    def progress(stage, fraction):  # runs on the growing thread, with the GIL
        started.set()
        ticks.append(fraction)

    a.setProgressCallback(progress)

    def waiter():  # waits for the growth with the GIL released, or the callback deadlocks
        assert started.wait(120)
        counts.append(a.getContext().getObjectCount())

    assert run_threads([lambda: a.advanceTime(40.0), waiter]) == []
    assert ticks[-1] == 1.0 and counts[0] > 0


def test_ctrl_c_stops_a_wait_for_another_threads_call():
    a = bean()
    a.buildPlantCanopyFromLibrary((0, 0, 0), (0.3, 0.3), (2, 2), 5)
    started, interrupted = threading.Event(), threading.Event()

    def progress(stage, fraction):  # holds the growth until the main thread was interrupted
        started.set()
        deadline = time.monotonic() + 30
        while not interrupted.is_set() and time.monotonic() < deadline:
            time.sleep(0.01)

    a.setProgressCallback(progress)
    grower = threading.Thread(target=lambda: a.advanceTime(5.0), daemon=True)

    def ctrl_c():
        assert started.wait(60)
        time.sleep(0.5)  # the main thread is waiting for the lock by now
        os.kill(os.getpid(), signal.SIGINT)

    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    t0 = time.monotonic()
    try:
        grower.start()
        threading.Thread(target=ctrl_c, daemon=True).start()
        assert started.wait(60)
        with pytest.raises(KeyboardInterrupt):
            a.getContext().getObjectCount()
    finally:
        interrupted.set()
        signal.signal(signal.SIGINT, previous)
    assert time.monotonic() - t0 < 20  # not only once the growth was over (30 s)
    grower.join(120)
    assert not grower.is_alive() and a.getPlantAge(0) == 10


# ---- re-entry --------------------------------------------------------------------------------

def architecture_with_rule(tmp_path, rule, name="misuse"):
    a = plantarch.PlantArchitecture(plantarch.Context())
    a.registerPhytomerCreationFunction(name, rule)
    a.loadPlantModelFromLibrary(species_with_rule(tmp_path, name))
    return a


@pytest.mark.parametrize("call", ["advanceTime", "deletePlantInstance", "getPlantHeight",
                                  "getContext", "contextObjectCount"])
def test_a_rule_calling_its_own_architecture_is_refused(tmp_path, call):
    holder = {}

    def rule(ctx):
        a = holder["a"]
        if call == "advanceTime":
            a.advanceTime(1.0)
        elif call == "deletePlantInstance":
            a.deletePlantInstance(0)
        elif call == "getPlantHeight":
            a.getPlantHeight(0)
        elif call == "getContext":
            a.getContext()
        else:
            holder["context"].getObjectCount()

    a = architecture_with_rule(tmp_path, rule)
    holder["a"], holder["context"] = a, a.getContext()
    with pytest.raises(plantarch.Error) as e:
        a.buildPlantInstanceFromLibrary((0, 0, 0), 20)
    method = "Context.getObjectCount" if call == "contextObjectCount" else f"PlantArchitecture.{call}"
    assert str(e.value).startswith(f"{method}: called from inside a rule while "
                                   "PlantArchitecture.buildPlantInstanceFromLibrary is running")
    assert "\n" not in str(e.value)
    # The refusal left the lock free: the architecture is usable (the rule now does nothing).
    a.registerPhytomerCreationFunction("misuse", lambda ctx: None)
    assert a.buildPlantInstanceFromLibrary((1, 0, 0), 20) >= 0


def test_a_rule_on_a_canopy_worker_thread_is_refused_too(tmp_path):
    holder = {}
    a = architecture_with_rule(tmp_path, lambda ctx: holder["a"].advanceTime(1.0))
    holder["a"] = a
    with pytest.raises(plantarch.Error, match="PlantArchitecture.advanceTime: called from inside "
                       "a rule while PlantArchitecture.buildPlantCanopyFromLibrary is running"):
        a.buildPlantCanopyFromLibrary((0, 0, 0), (0.3, 0.3), (3, 3), 20)
    assert a.getContext().getObjectCount() == 0


def test_the_progress_callback_calling_its_architecture_is_refused():
    a = bean()
    a.setProgressCallback(lambda stage, fraction: a.getAllPlantIDs())
    with pytest.raises(plantarch.Error, match="PlantArchitecture.getAllPlantIDs: called from "
                       "inside a progress callback while PlantArchitecture.(build|advance)"):
        a.buildPlantInstanceFromLibrary((0, 0, 0), 5)
        a.advanceTime(5.0)


def test_a_rule_may_use_another_architecture(tmp_path):
    other = bean()
    heights = []

    def rule(ctx):
        if not heights:
            p = other.buildPlantInstanceFromLibrary((0, 0, 0), 10)
            heights.append(other.getPlantHeight(p))

    a = architecture_with_rule(tmp_path, rule)
    a.buildPlantInstanceFromLibrary((0, 0, 0), 20)
    assert heights and heights[0] > 0


# ---- handles ---------------------------------------------------------------------------------

def test_state_and_phytomers_outlive_their_plant():
    a = bean()
    p = a.buildPlantInstanceFromLibrary((0, 0, 0), 30)
    state = a.plant(p)
    shoot = state.shoots[0]
    phytomer = shoot.phytomers[0]
    length = phytomer.internode.internode_length
    a.advanceTime(10.0)  # the plant grows; the copy does not
    assert len(a.plant(p).shoots[0].phytomers) >= len(shoot.phytomers)
    a.deletePlantInstance(p)
    del a, state, shoot
    gc.collect()
    assert phytomer.internode.internode_length == length
    assert phytomer.petioles[0].leaves[0].leaf_scale > 0


def test_a_rule_context_kept_after_the_rule_raises(tmp_path):
    kept = []

    def rule(ctx):
        if not kept:
            kept.append((ctx, ctx.phytomer, ctx.shoot))
        ctx.phytomer.scaleLeaves(0.5)

    a = architecture_with_rule(tmp_path, rule)
    p = a.buildPlantInstanceFromLibrary((0, 0, 0), 30)
    ctx, phytomer, shoot = kept[0]
    for attribute in ("phytomer", "shoot", "nodeIndex", "plantAge", "rank"):
        with pytest.raises(plantarch.Error, match="valid only during the call"):
            getattr(ctx, attribute)
    a.deletePlantInstance(p)
    gc.collect()
    assert phytomer.petioles[0].petiole_length > 0 and shoot.rank >= 0  # copies: still readable


def test_a_plant_handle_after_its_plant_is_deleted():
    a = bean()
    p = a.buildPlantInstanceFromLibrary((0, 0, 0), 20)
    plant = a.getPlant(p)
    assert "leaves" in repr(plant)
    a.deletePlantInstance(p)
    assert repr(plant) == f"<plantarch.Plant {p}: no longer in its PlantArchitecture>"
    with pytest.raises(plantarch.Error, match="plantID"):
        plant.statistics()


def test_mesh_arrays_outlive_plants_architecture_and_context():
    a = bean()
    p = a.buildPlantInstanceFromLibrary((0, 0, 0), 20)
    mesh = a.getMeshArrays(p)
    context_mesh = a.getContext().getMeshArrays()
    total = float(mesh["vertices"].sum())
    a.deletePlantInstance(p)
    del a
    gc.collect()
    assert float(mesh["vertices"].sum()) == total
    assert len(context_mesh["triangles"]) == len(mesh["triangles"])


# ---- bad IDs ---------------------------------------------------------------------------------

@pytest.mark.parametrize("call", [
    lambda a, c: a.getPlant(2**40),
    lambda a, c: a.getPlant(7),
    lambda a, c: a.getPlantHeight(-1),
    lambda a, c: a.advanceTime(1.0, 2**40),
    lambda a, c: a.advanceTime(1.0, [0, 2**40]),
    lambda a, c: a.getMeshArrays(2**40),
    lambda a, c: a.getMeshArrays([-3]),
    lambda a, c: a.deletePlantInstance(99),
    lambda a, c: a.getShootNodeCount(0, 2**33),
    lambda a, c: a.getPlantStructureXML([2**40]),
    lambda a, c: a.writePlantStructureXML(2**40, "never.xml"),
    lambda a, c: c.getObjectMesh(2**40),
    lambda a, c: c.getMeshArrays([2**40]),
    lambda a, c: plantarch.writeQSM(a, "never.csv", [2**40]),
])
def test_bad_ids_are_plantarch_errors(call):
    a = bean()
    a.buildPlantInstanceFromLibrary((0, 0, 0), 10)
    with pytest.raises(plantarch.Error) as e:
        call(a, a.getContext())
    assert "\n" not in str(e.value) and "ID" in (e.value.parameter or str(e.value))
    assert not os.path.exists("never.xml") and not os.path.exists("never.csv")


# ---- numpy -----------------------------------------------------------------------------------

def test_two_threads_first_numpy_calls_do_not_deadlock():
    script = textwrap.dedent("""
        import sys, threading
        import plantarch
        assert "numpy" in sys.modules  # imported with the module, before any thread
        a = plantarch.PlantArchitecture(plantarch.Context())
        a.loadPlantModelFromLibrary("bean")
        a.buildPlantInstanceFromLibrary((0, 0, 0), 10)
        b = plantarch.PlantArchitecture(plantarch.Context())
        b.loadPlantModelFromLibrary("bean")
        b.buildPlantInstanceFromLibrary((0, 0, 0), 10)
        out = []
        start = threading.Barrier(4)
        def first(arch):
            start.wait()
            out.append(len(arch.getMeshArrays()["vertices"]))
            out.append(arch.getPlantBasePosition(0).z)
        threads = [threading.Thread(target=first, args=(x,)) for x in (a, b, a, b)]
        for t in threads: t.start()
        for t in threads: t.join()
        assert len(out) == 8, out
        print("ok")
    """)
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(p for p in sys.path if p)
    for _ in range(3):
        done = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True,
                              text=True, timeout=240)
        assert done.returncode == 0, done.stderr
        assert done.stdout.strip() == "ok"


# ---- Python exceptions from rules ------------------------------------------------------------

class RuleFailed(Exception):
    pass


def frames(error):
    return [f.name for f in traceback.extract_tb(error.__traceback__)]


@pytest.mark.parametrize("kind", [KeyboardInterrupt, RuleFailed])
def test_an_exception_raised_in_a_rule_arrives_as_itself(tmp_path, kind):
    def raising_rule(ctx):
        raise kind("from the rule")

    a = architecture_with_rule(tmp_path, raising_rule)
    with pytest.raises(kind, match="from the rule") as e:
        a.buildPlantInstanceFromLibrary((0, 0, 0), 20)
    assert "raising_rule" in frames(e.value)
    # From a canopy's worker threads too, with the plant it stopped as a note.
    with pytest.raises(kind, match="from the rule") as e:
        a.buildPlantCanopyFromLibrary((0, 0, 0), (0.3, 0.3), (2, 2), 20)
    assert "raising_rule" in frames(e.value)
    assert any("building canopy plant" in n for n in getattr(e.value, "__notes__", []))
    assert a.getContext().getObjectCount() == 0
    # And from advanceTime.
    a.registerPhytomerCreationFunction("misuse", lambda ctx: None)
    p = a.buildPlantInstanceFromLibrary((0, 0, 0), 5)
    a.registerPhytomerCreationFunction("misuse", raising_rule)
    with pytest.raises(kind, match="from the rule"):
        a.advanceTime(20.0, p)
