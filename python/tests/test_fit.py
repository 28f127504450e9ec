"""Calibration to field data from Python (plantarch.fitSpecies) and the convergence plot of its
report (scripts/plot_fit.py)."""

import json
import pathlib
import subprocess
import sys

import pytest

import plantarch
from conftest import REPO

SCRIPT = REPO / "scripts" / "plot_fit.py"
TARGET = {
    "plantarch_fit": 1,
    "parameters": [{"path": "trifoliate.internode_length_max", "lower": 0.015, "upper": 0.04}],
    "seeds": [1, 2],
    "optimizer": {"max_evaluations": 8},
    "ages": [{"age": 15, "height": {"value": 0.1, "sd": 0.01}}],
}


def test_fit_species_returns_the_fit_and_calls_back(tmp_path):
    target = tmp_path / "t.json"
    target.write_text(json.dumps(TARGET))
    seen = []
    r = plantarch.fitSpecies("bean", str(target),
                             onImprovement=lambda n, f, values: seen.append((n, f, values)))
    assert r["paths"] == ["shoot_types.trifoliate.internode_length_max"]
    assert r["start"] == [0.025]
    assert len(r["evaluations"]) <= 8
    assert seen and seen[0][0] == 1 and seen[-1][1] == r["objective"]
    assert r["objective"] <= r["start_objective"]
    assert r["residuals"][0]["statistic"] == "height"
    assert "<internode_length_max>" in r["species_xml"]
    assert json.loads(r["report"])["plantarch_fit_report"] == 1
    # The same with two threads.
    again = plantarch.fitSpecies("bean", str(target), threads=2)
    assert again["fitted"] == r["fitted"] and again["objective"] == r["objective"]


def test_a_bad_target_raises_one_line(tmp_path):
    target = tmp_path / "t.json"
    target.write_text(json.dumps(TARGET).replace("\"seeds\"", "\"sedes\""))
    with pytest.raises(plantarch.Error, match="unknown key, did you mean 'seeds'"):
        plantarch.fitSpecies("bean", str(target))
    with pytest.raises(plantarch.Error, match="is a directory, not a fit target file"):
        plantarch.fitSpecies("bean", str(tmp_path))


def test_a_python_exception_in_the_callback_ends_the_fit(tmp_path):
    target = tmp_path / "t.json"
    target.write_text(json.dumps(TARGET))

    def stop(n, f, values):
        raise KeyError("stop here")

    with pytest.raises(KeyError, match="stop here"):
        plantarch.fitSpecies("bean", str(target), onImprovement=stop)


def plot(*args):
    return subprocess.run([sys.executable, str(SCRIPT), *map(str, args)], capture_output=True,
                          text=True)


def test_the_report_is_drawn_and_bad_reports_get_one_line(tmp_path):
    pytest.importorskip("matplotlib")
    target = tmp_path / "t.json"
    target.write_text(json.dumps(TARGET))
    report = tmp_path / "report.json"
    report.write_text(plantarch.fitSpecies("bean", str(target))["report"])
    out = tmp_path / "c.png"
    r = plot(report, "-o", out)
    assert r.returncode == 0, r.stderr
    assert out.read_bytes().startswith(b"\x89PNG") and out.stat().st_size > 10000
    bad = tmp_path / "bad.json"
    bad.write_text("{\"x\": 1}")
    for args, message in [([bad, "-o", out], "not a fit report"),
                          ([tmp_path / "none.json", "-o", out], "cannot read"),
                          ([tmp_path, "-o", out], "not a regular file"),
                          ([report, "-o", tmp_path / "c.txt"], "give a .png, .svg or .pdf name")]:
        r = plot(*args)
        assert r.returncode != 0
        assert message in r.stderr, r.stderr
        assert r.stderr.count("\n") == 1, r.stderr


def test_point_clouds_are_read_and_bad_ones_get_one_line(tmp_path):
    xyz = tmp_path / "scan.xyz"
    xyz.write_text("# x y z\n0 0 0\n0.1 0.2 0.3 extra columns\n")
    points = plantarch.readPointCloudFile(str(xyz))
    assert len(points) == 2 and abs(points[1].z - 0.3) < 1e-6
    xyz.write_text("0 0 0\n0.1 nan 0.3\n")
    with pytest.raises(plantarch.Error, match="scan.xyz:2: '0.1 nan 0.3': expected three numbers"):
        plantarch.readPointCloudFile(str(xyz))
