"""Graphics writers under threads and hostile targets: two threads writing one Context at once
get the bytes a lone writer gets; a writer racing a growing plant writes the plant as it stood
before or after the growth step, never a mixture; a FIFO as the target is a plantarch.Error and
stays a FIFO."""
import os
import threading

import pytest

import plantarch

from test_misuse import bean, run_threads


def grown(days=30):
    a = bean()
    a.buildPlantInstanceFromLibrary((0, 0, 0), days)
    return a


def write(a, path, **kw):
    if str(path).endswith(".usda"):
        plantarch.writeUSDA(a.getContext(), str(path), architecture=a, **kw)
    else:
        plantarch.writeGLTF(a.getContext(), str(path), architecture=a, **kw)
    return open(path, "rb").read()


VARIANTS = [
    ("organs.glb", dict(nodes="organ", appearance="textured", texture_size=16)),
    ("organs.usda", dict(nodes="organ", appearance="textured", texture_size=16)),
    ("skin.glb", dict(skin=True)),
    ("lod.glb", dict(lod="reduced,cards", meshopt=True)),
]


def test_two_threads_writing_one_context_get_the_lone_writers_bytes(tmp_path):
    a = grown()
    (tmp_path / "alone").mkdir()
    (tmp_path / "threads").mkdir()
    # The same names in two folders: a USD file names its texture images after itself.
    alone = {name: write(a, tmp_path / "alone" / name, **kw) for name, kw in VARIANTS}
    got = {}

    def job(name, kw):
        return lambda: got.__setitem__(name, write(a, tmp_path / "threads" / name, **kw))

    errors = run_threads([job(name, kw) for name, kw in VARIANTS])
    assert errors == []
    assert got == alone
    assert sorted(os.listdir(tmp_path / "threads")) == sorted(os.listdir(tmp_path / "alone"))


def test_a_writer_racing_growth_writes_the_plant_before_or_after(tmp_path):
    a = grown(20)
    before = write(a, tmp_path / "before.glb", nodes="organ")
    twin = grown(20)
    twin.advanceTime(2.0)
    after = write(twin, tmp_path / "after.glb", nodes="organ")
    assert before != after
    for k in range(3):
        a = grown(20)
        path = tmp_path / f"race{k}.glb"
        errors = run_threads([lambda: a.advanceTime(2.0),
                              lambda: plantarch.writeGLTF(a.getContext(), str(path),
                                                          architecture=a, nodes="organ")])
        assert errors == []
        assert open(path, "rb").read() in (before, after)


def test_a_fifo_as_target_is_an_error_and_stays_a_fifo(tmp_path):
    a = grown(10)
    fifo = tmp_path / "p.glb"
    os.mkfifo(fifo)
    with pytest.raises(plantarch.Error, match="is a FIFO, not a file"):
        plantarch.writeGLTF(a.getContext(), str(fifo), nodes="organ")
    assert os.path.exists(fifo) and not os.path.isfile(fifo)
    assert sorted(os.listdir(tmp_path)) == ["p.glb"]
