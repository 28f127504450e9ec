"""scripts/plot_physiology.py: the season plot of docs/physiology.md, from a real series,
and one clear line for a file that is not a series."""

import pathlib
import subprocess
import sys

from conftest import REPO, cli

SCRIPT = REPO / "scripts" / "plot_physiology.py"


def plot(*args):
    return subprocess.run([sys.executable, str(SCRIPT), *map(str, args)], capture_output=True,
                          text=True)


def test_the_guides_plot_command_draws_a_series(tmp_path):
    doc = (REPO / "docs" / "physiology.md").read_text()
    assert "python3 scripts/plot_physiology.py out/season.csv -o out/season.png" in doc
    series = tmp_path / "season.csv"
    done = subprocess.run([cli(), "canopy", "bean", "--count", "2x1", "--from", "20", "--age",
                           "23", "--carbon", "--nitrogen", "--fertilise", "20:0.5",
                           "--location", "38.54,-121.74", "--start", "2026-06-01",
                           "--light-every", "6", "--series", str(series)],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    for name, extra in [("all.png", []), ("one.svg", ["--plant", "1"])]:
        out = tmp_path / name
        r = plot(series, "-o", out, "--title", "test", *extra)
        assert r.returncode == 0, r.stderr
        data = out.read_bytes()
        assert len(data) > 10000
        assert data.startswith(b"\x89PNG") if name.endswith(".png") else b"<svg" in data[:2000]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["all.png", "one.svg", "season.csv"]


def test_a_file_that_is_not_a_series_gets_one_line(tmp_path):
    weather = tmp_path / "w.csv"
    weather.write_text("time,par,air_temperature\n2026-06-01T12:00,1000,25\n")
    bad = tmp_path / "bad.csv"
    series_header = ("plant,age,days,leaf_area,absorbed_par,temperature,input,maintenance,"
                     "growth,growth_respiration,root_growth,losses,sugar,starch,shoots_pruned,"
                     "buds_aborted,nitrogen_available,nitrogen_in_leaves,nitrogen_uptake,"
                     "nitrogen_remobilised,nitrogen_lost,nitrogen_to_fruit,nitrogen_shed,"
                     "nitrogen_stress\n")
    bad.write_text(series_header + "0,1,1,0,0,20,nan" + ",0" * 17 + "\n")
    cases = [
        ([weather, "-o", tmp_path / "x.png"], "not a physiology series"),
        ([tmp_path / "missing.csv", "-o", tmp_path / "x.png"], "cannot read"),
        ([bad, "-o", tmp_path / "x.png"], "bad.csv:2: a value that is not finite"),
        ([weather, "-o", tmp_path / "x.txt"], "give a .png, .svg or .pdf name"),
        ([pathlib.Path("/dev/zero"), "-o", tmp_path / "x.png"], "not a regular file"),
        ([tmp_path, "-o", tmp_path / "x.png"], "not a regular file"),
    ]
    for args, message in cases:
        r = plot(*args)
        assert r.returncode != 0
        assert message in r.stderr, r.stderr
        assert r.stderr.count("\n") == 1, r.stderr
    assert not (tmp_path / "x.png").exists() and not (tmp_path / "x.txt").exists()
