"""Editors trust the type stubs: pyright (installed from npm by scripts/test.sh) reports no
error on the Python blocks of docs/python.md and docs/pyhelios.md, nor on these tests."""

import json
import os
import pathlib
import re
import shutil
import subprocess
import sys

import plantarch
from conftest import REPO

PYRIGHT = REPO / "tests" / "js" / "node_modules" / ".bin" / "pyright"


def test_pyright_finds_no_error_in_the_docs_and_tests(tmp_path):
    assert PYRIGHT.exists(), "pyright is not installed: run scripts/test.sh"
    for doc in ("python.md", "pyhelios.md"):
        blocks = re.findall(r"```python\n(.*?)```", (REPO / "docs" / doc).read_text(), re.S)
        assert blocks
        (tmp_path / (doc.replace(".", "_") + ".py")).write_text("\n".join(blocks))
    tests = tmp_path / "tests"
    shutil.copytree(REPO / "python" / "tests", tests,
                    ignore=shutil.ignore_patterns("__pycache__"))
    module_dir = pathlib.Path(plantarch.__file__).resolve().parents[1]
    (tmp_path / "pyrightconfig.json").write_text(json.dumps({
        "include": [str(tmp_path)],
        "extraPaths": [str(module_dir), str(tests)],
        "pythonVersion": "%d.%d" % sys.version_info[:2],
        "typeCheckingMode": "basic",
    }))
    env = {k: v for k, v in os.environ.items() if k != "LD_PRELOAD"}
    run = subprocess.run([str(PYRIGHT), "--project", str(tmp_path / "pyrightconfig.json"),
                          "--pythonpath", sys.executable, "--outputjson"],
                         capture_output=True, text=True, env=env, timeout=600)
    report = json.loads(run.stdout)
    errors = [f"{d['file']}:{d['range']['start']['line'] + 1}: {d['message']}"
              for d in report["generalDiagnostics"] if d["severity"] == "error"]
    assert errors == [], "\n".join(errors)
    assert report["summary"]["filesAnalyzed"] >= 15
