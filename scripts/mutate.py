#!/usr/bin/python3
"""Mutation testing of plantarch: does the test suite notice a bug a user would notice?

Each mutation in scripts/mutations.toml is one small edit of one file (a sign flipped, a
parameter ignored, a field dropped from a file format). For each one this tool edits a scratch
copy of the repository's HEAD, rebuilds it incrementally, runs ctest until the first failing
test, and puts the file back. A mutation is

  caught        some test failed (or timed out): the suite notices the bug;
  survived      every test passed: no test holds the behaviour the mutation breaks;
  build-failed  the edit does not compile: an error in the list, not a catch.

    /usr/bin/python3 scripts/mutate.py --list            # check every mutation applies
    /usr/bin/python3 scripts/mutate.py                   # all of them: an hour or more
    /usr/bin/python3 scripts/mutate.py --only ID,ID --markdown results.md

Run by hand; not part of ctest. See docs/testing.md, "Mutation testing".
"""

import argparse
import datetime
import os
import re
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
DEFAULT_LIST = REPO / "scripts" / "mutations.toml"
AREAS = ("growth", "phenology", "collision", "io", "exporters", "cli", "library")
FIELDS = ("id", "area", "file", "find", "replace", "simulates")
STATUSES = ("caught", "survived", "build-failed", "builds", "not run")
MARKER = ".plantarch-mutate"  # marks a --build-dir folder as this tool's


class ListError(Exception):
    """A problem with the mutation list (exit status 2)."""


@dataclass
class Mutation:
    id: str
    area: str
    file: str
    find: str
    replace: str
    simulates: str


@dataclass
class Result:
    mutation: Mutation
    status: str = "not run"  # caught, survived, build-failed
    test: str = ""  # first failing test, or the first compiler error
    build_seconds: float = 0.0
    test_seconds: float = 0.0
    notes: list = field(default_factory=list)


# ---- the list ----------------------------------------------------------------------------


def load_mutations(path):
    try:
        with open(path, "rb") as f:
            data = tomllib.load(f)
    except OSError as e:
        raise ListError(f"{path}: cannot read: {e.strerror}")
    except tomllib.TOMLDecodeError as e:
        raise ListError(f"{path}: {e}")
    unknown = sorted(set(data) - {"mutation"})
    if unknown:
        raise ListError(f"{path}: unknown top-level key '{unknown[0]}' (valid: [[mutation]])")
    entries = data.get("mutation", [])
    if not isinstance(entries, list) or not entries:
        raise ListError(f"{path}: no [[mutation]] entries")
    mutations, seen = [], set()
    for n, entry in enumerate(entries, 1):
        where = f"{path}: mutation {n}"
        if isinstance(entry.get("id"), str):
            where += f" ({entry['id']})"
        for key in entry:
            if key not in FIELDS:
                raise ListError(f"{where}: unknown key '{key}' (valid: {', '.join(FIELDS)})")
        for key in FIELDS:
            value = entry.get(key)
            if not isinstance(value, str) or (key != "replace" and not value.strip()):
                raise ListError(f"{where}: '{key}' must be a non-empty string")
        m = Mutation(**{k: entry[k] for k in FIELDS})
        if not re.fullmatch(r"[A-Za-z0-9][A-Za-z0-9-]*", m.id):
            raise ListError(f"{where}: id '{m.id}' must be letters, digits and '-'")
        if m.id in seen:
            raise ListError(f"{where}: duplicate id '{m.id}'")
        seen.add(m.id)
        if m.area not in AREAS:
            raise ListError(f"{where}: area '{m.area}' (valid: {', '.join(AREAS)})")
        if m.find == m.replace:
            raise ListError(f"{where}: 'replace' is the same text as 'find'")
        if "\n" in m.simulates:
            raise ListError(f"{where}: 'simulates' must be one line")
        mutations.append(m)
    return mutations


def select(mutations, only):
    if not only:
        return mutations
    wanted = [w.strip() for w in only.split(",") if w.strip()]
    ids = {m.id for m in mutations}
    for w in wanted:
        if w not in ids:
            raise ListError(f"--only: no mutation '{w}' in the list")
    return [m for m in mutations if m.id in wanted]


def check_applies(m, text):
    """Raises ListError unless the mutation's text occurs exactly once in `text`."""
    if text is None:
        raise ListError(f"mutation {m.id}: file {m.file} is not in the repository")
    count = text.count(m.find)
    if count != 1:
        raise ListError(f"mutation {m.id}: the text to find occurs {count} times in {m.file} "
                        f"(it must occur exactly once)")


def head_file(path):
    """The file's text at HEAD (what a run mutates), or None."""
    r = subprocess.run(["git", "-C", str(REPO), "show", f"HEAD:{path}"], capture_output=True)
    return r.stdout.decode("utf-8") if r.returncode == 0 else None


def list_mutations(mutations):
    problems = []
    print(f"{'ID':30} {'area':10} {'file':34} check")
    for m in mutations:
        try:
            check_applies(m, head_file(m.file))
            state = "applies"
        except ListError as e:
            problems.append(str(e))
            state = "REFUSED"
        print(f"{m.id:30} {m.area:10} {m.file:34} {state}")
        print(f"    {m.simulates}")
    print(f"{len(mutations)} mutations, {len(problems)} refused (checked against HEAD)")
    for p in problems:
        print(p, file=sys.stderr)
    return 2 if problems else 0


# ---- processes ---------------------------------------------------------------------------


def run(cmd, cwd=None, env=None, timeout=None):
    """Runs `cmd` in its own process group; returns (status, output, seconds, timed_out).

    On a timeout or an interrupt the whole group (ninja's compilers, ctest's tests) ends."""
    start = time.monotonic()
    with tempfile.TemporaryFile() as out:
        p = subprocess.Popen(cmd, cwd=cwd, env=env, stdout=out, stderr=subprocess.STDOUT,
                             stdin=subprocess.DEVNULL, start_new_session=True)
        timed_out = False
        try:
            status = p.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            end_group(p)
            status, timed_out = None, True
        except BaseException:
            end_group(p)
            raise
        out.seek(0)
        text = out.read().decode("utf-8", errors="replace")
    return status, text, time.monotonic() - start, timed_out


def end_group(p):
    for sig, wait in ((signal.SIGTERM, 10), (signal.SIGKILL, 30)):
        try:
            os.killpg(p.pid, sig)
        except ProcessLookupError:
            return
        try:
            p.wait(timeout=wait)
            return
        except subprocess.TimeoutExpired:
            pass


def git(tree, *args):
    r = subprocess.run(["git", "-C", str(tree), *args], capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"git {' '.join(args)} failed: {r.stderr.strip()}")
    return r.stdout


# ---- the scratch copy --------------------------------------------------------------------


class Scratch:
    """A clone of HEAD in `root`/tree, built in `root`/tree/build.

    The build sits inside the copy as in a checkout: the programs find the species library
    next to their folder. The clone shares the repository's objects (git clone --shared) and
    registers nothing in the repository. ccache's base directory is `root`, so compiler
    command lines name files relative to the build folder, as in a checkout's build/, and a
    later run in the same --build-dir finds every object file again."""

    def __init__(self, root, keep_build, jobs, exclude, log_dir):
        self.root = root
        self.tree = root / "tree"
        self.build = self.tree / "build"
        self.keep_build = keep_build
        self.jobs = jobs
        self.exclude = exclude
        self.log_dir = log_dir
        self.env = dict(os.environ, CCACHE_BASEDIR=str(root), OMP_NUM_THREADS=str(jobs))

    def empty_tree(self):
        """Removes the copy's files, all but a kept build."""
        if not self.tree.exists():
            return
        for child in self.tree.iterdir():
            if self.keep_build and child.name == "build":
                continue
            if child.is_dir() and not child.is_symlink():
                shutil.rmtree(child)
            else:
                child.unlink()

    def create(self):
        self.empty_tree()  # a run that was killed may have left its files
        sha = git(REPO, "rev-parse", "HEAD").strip()
        clone = self.root / "clone"
        shutil.rmtree(clone, ignore_errors=True)
        subprocess.run(["git", "clone", "--quiet", "--shared", "--no-checkout", str(REPO),
                        str(clone)], check=True)
        self.tree.mkdir(exist_ok=True)
        os.rename(clone / ".git", self.tree / ".git")  # the tree may hold a kept build/
        shutil.rmtree(clone)
        git(self.tree, "checkout", "--quiet", "--force", "--detach", sha)
        return sha

    def remove(self):
        if self.keep_build:
            self.empty_tree()
            shutil.rmtree(self.root / "clone", ignore_errors=True)
        else:
            shutil.rmtree(self.root, ignore_errors=True)

    def log(self, name, text):
        if self.log_dir:
            (self.log_dir / f"{name}.log").write_text(text)

    def configure(self):
        status, out, _, _ = run(["cmake", "-S", str(self.tree), "-B", str(self.build), "-G",
                                 "Ninja", "-DCMAKE_BUILD_TYPE=Release",
                                 "-DCMAKE_CXX_COMPILER_LAUNCHER=ccache",
                                 "-DPLANTARCH_BUILD_BENCH=OFF"], env=self.env)
        self.log("configure", out)
        if status != 0:
            raise RuntimeError("cmake configure failed:\n" + tail(out))

    def compile(self, name):
        status, out, seconds, _ = run(
            ["nice", "cmake", "--build", str(self.build), "--parallel", str(self.jobs)],
            env=self.env)
        self.log(f"{name}.build", out)
        return status == 0, out, seconds

    def ctest(self, name, timeout, stop_on_failure=True, include=None, exclude=None):
        cmd = ["nice", "ctest", "--test-dir", str(self.build), "-j", str(self.jobs),
               "--timeout", str(max(1, int(timeout)))]
        if stop_on_failure:
            cmd.append("--stop-on-failure")
        if include:
            cmd += ["-R", include]
        excludes = "|".join(e for e in (self.exclude, exclude) if e)
        if excludes:
            cmd += ["-E", excludes]
        status, out, seconds, timed_out = run(cmd, env=self.env, timeout=timeout + 120)
        self.log(name, out)
        return status, out, seconds, timed_out

    def slow_tests(self, seconds):
        """Tests whose average time in earlier runs is at least `seconds` (ctest's cost data)."""
        costs = self.build / "Testing" / "Temporary" / "CTestCostData.txt"
        slow = []
        if seconds > 0 and costs.exists():
            for line in costs.read_text().splitlines():
                if line.strip() == "---":
                    break
                parts = line.split()
                if len(parts) == 3 and float(parts[2]) >= seconds:
                    slow.append(parts[0])
        return slow

    def test(self, name, timeout, slow_seconds):
        """Runs the suite until the first failure, quick tests first.

        ctest starts the slowest tests first; a mutation that a quick test catches would wait
        for them. So the tests that took `slow_seconds` or more before run in a second round,
        only when every quick test passed."""
        slow = self.slow_tests(slow_seconds)
        if not slow:
            return self.ctest(f"{name}.test", timeout)
        names = "^(" + "|".join(re.sub(r"([][.*+?^$()|\\])", r"\\\1", n) for n in slow) + ")$"
        status, out, seconds, timed_out = self.ctest(f"{name}.test", timeout, exclude=names)
        if status != 0 or timed_out:
            return status, out, seconds, timed_out
        status2, out2, seconds2, timed_out2 = self.ctest(f"{name}.slow-tests",
                                                         max(1.0, timeout - seconds),
                                                         include=names)
        return status2, out + out2, seconds + seconds2, timed_out2

    def clean(self):
        r = subprocess.run(["git", "-C", str(self.tree), "diff", "--quiet"])
        return r.returncode == 0


def tail(text, lines=30):
    return "\n".join(text.rstrip().splitlines()[-lines:])


TEST_LINE = re.compile(r"^\s*\d+/\d+\s+Test\s+#\d+:\s+(\S+)\s+\.*\s*(.*?)\s+[\d.]+\s+sec\s*$")


def first_failure(ctest_output):
    """The name of the first test ctest reported as not passing, or ''."""
    for line in ctest_output.splitlines():
        m = TEST_LINE.match(line)
        if m and not re.search(r"Passed|Skipped|Disabled", m.group(2)):
            return m.group(1)
    after = ctest_output.split("The following tests FAILED:", 1)
    if len(after) == 2:
        m = re.search(r"\d+\s+-\s+(\S+)", after[1])
        if m:
            return m.group(1)
    return ""


def first_error(build_output):
    for line in build_output.splitlines():
        if "error:" in line or "Error:" in line or "FAILED:" in line:
            return line.strip()[:200]
    return tail(build_output, 1)[:200]


# ---- the run -----------------------------------------------------------------------------


def mutate_one(scratch, m, timeout, slow_seconds, build_only=False):
    r = Result(m)
    path = scratch.tree / m.file
    original = path.read_bytes()
    text = original.decode("utf-8")
    check_applies(m, text)
    try:
        path.write_bytes(text.replace(m.find, m.replace, 1).encode("utf-8"))
        ok, out, r.build_seconds = scratch.compile(m.id)
        if not ok:
            r.status, r.test = "build-failed", first_error(out)
            return r
        if build_only:
            r.status = "builds"
            return r
        status, out, r.test_seconds, timed_out = scratch.test(m.id, timeout, slow_seconds)
        if timed_out:
            r.status, r.test = "caught", "(whole run timed out)"
        elif status == 0:
            r.status = "survived"
        else:
            r.status, r.test = "caught", first_failure(out) or "(ctest failed, no test named)"
            if "***Timeout" in out:
                r.notes.append("a test timed out")
        return r
    finally:
        # The original bytes, with a new modification time: the next build must recompile the
        # file (ccache returns the object it compiled before the edit).
        path.write_bytes(original)
        if not scratch.clean():
            raise RuntimeError(f"mutation {m.id}: the scratch copy differs from HEAD after "
                               f"putting {m.file} back")


def print_table(results):
    print()
    print(f"{'ID':30} {'area':10} {'result':13} {'build s':>8} {'test s':>8}  first failing test")
    for r in results:
        print(f"{r.mutation.id:30} {r.mutation.area:10} {r.status:13} {r.build_seconds:8.0f} "
              f"{r.test_seconds:8.0f}  {r.test}{''.join(f' ({n})' for n in r.notes)}")
    counts = {s: sum(r.status == s for r in results)
              for s in STATUSES}
    print(", ".join(f"{n} {s}" for s, n in counts.items() if n))


def md_cell(text):
    return text.replace("|", "\\|").replace("\n", " ")


def write_markdown(path, results, sha, command, started, minutes):
    counts = {s: sum(r.status == s for r in results)
              for s in STATUSES}
    lines = [
        f"Run of {started:%Y-%m-%d %H:%M}, commit `{sha[:12]}`, {minutes:.0f} min: "
        f"`{command}`",
        "",
        ", ".join(f"{n} {s}" for s, n in counts.items() if n) + ".",
        "",
        "| ID | area | what it simulates | result | first test that caught it |",
        "|---|---|---|---|---|",
    ]
    for r in results:
        caught_by = f"`{r.test}`" if r.status == "caught" and r.test else md_cell(r.test)
        lines.append(f"| `{r.mutation.id}` | {r.mutation.area} | {md_cell(r.mutation.simulates)} "
                     f"| {r.status} | {caught_by} |")
    Path(path).write_text("\n".join(lines) + "\n")


def scratch_root(build_dir):
    if build_dir is None:
        return Path(tempfile.mkdtemp(prefix="plantarch-mutate-")), False
    root = Path(build_dir).resolve()
    if root.exists() and any(root.iterdir()) and not (root / MARKER).exists():
        raise ListError(f"--build-dir {root}: not empty and not made by this tool")
    root.mkdir(parents=True, exist_ok=True)
    (root / MARKER).write_text("scratch folder of scripts/mutate.py\n")
    return root, True


def run_mutations(args, mutations):
    started = datetime.datetime.now()
    t0 = time.monotonic()
    command = "scripts/mutate.py " + " ".join(shlex.quote(a) for a in sys.argv[1:])
    root, keep = scratch_root(args.build_dir)
    log_dir = Path(args.log_dir).resolve() if args.log_dir else None
    if log_dir:
        log_dir.mkdir(parents=True, exist_ok=True)
    scratch = Scratch(root, keep, args.jobs, args.exclude, log_dir)
    results = [Result(m) for m in mutations]
    sha = ""
    interrupted = False
    try:
        sha = scratch.create()
        print(f"scratch copy of {sha[:12]} in {scratch.tree}", flush=True)
        for m in mutations:  # refuse before spending an hour on the build
            check_applies(m, (scratch.tree / m.file).read_text())
        scratch.configure()
        ok, out, seconds = scratch.compile("baseline")
        if not ok:
            raise RuntimeError("HEAD does not build:\n" + tail(out))
        print(f"built in {seconds:.0f} s", flush=True)
        timeout = args.timeout
        if not args.skip_baseline and not args.build_only:
            status, out, seconds, timed_out = scratch.ctest("baseline.test", timeout or 3600,
                                                            stop_on_failure=False)
            if status != 0 or timed_out:
                raise RuntimeError(f"the unmutated suite fails ({first_failure(out) or 'timeout'})"
                                   f": fix that first\n" + tail(out))
            print(f"baseline: every test passes in {seconds:.0f} s", flush=True)
            timeout = timeout or max(300.0, 3.0 * seconds)
        timeout = timeout or 3600.0
        for i, m in enumerate(mutations):
            print(f"[{i + 1}/{len(mutations)}] {m.id}: {m.simulates}", flush=True)
            results[i] = mutate_one(scratch, m, timeout, args.slow, args.build_only)
            r = results[i]
            print(f"    {r.status} {r.test} (build {r.build_seconds:.0f} s, tests "
                  f"{r.test_seconds:.0f} s)", flush=True)
    except KeyboardInterrupt:
        interrupted = True
        print("\ninterrupted: removing the scratch copy", file=sys.stderr)
    finally:
        scratch.remove()
    print_table(results)
    if args.markdown:
        write_markdown(args.markdown, results, sha, command, started, (time.monotonic() - t0) / 60)
        print(f"wrote {args.markdown}")
    if interrupted:
        return 130
    return 1 if any(r.status == "build-failed" for r in results) else 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--list", action="store_true",
                        help="check that every mutation applies to HEAD and print them")
    parser.add_argument("--only", metavar="ID,ID", help="run only these mutations")
    parser.add_argument("--mutations", default=str(DEFAULT_LIST), metavar="FILE",
                        help="mutation list (default scripts/mutations.toml)")
    parser.add_argument("--build-dir", metavar="DIR",
                        help="keep the scratch build in DIR, so the next run with DIR rebuilds "
                             "from ccache (default: a temporary folder, removed)")
    parser.add_argument("--jobs", type=int, default=2, metavar="N",
                        help="build and test jobs (default 2)")
    parser.add_argument("--timeout", type=float, metavar="SECONDS",
                        help="per mutation test run (default 3 x the baseline's time, >= 300)")
    parser.add_argument("--exclude", default="^format$", metavar="REGEX",
                        help="ctest -E: tests not run (default '^format$': edits need not be "
                             "clang-format clean)")
    parser.add_argument("--slow", type=float, default=5.0, metavar="SECONDS",
                        help="tests that took this long before run after all quicker ones "
                             "passed (default 5; 0: one ctest run)")
    parser.add_argument("--skip-baseline", action="store_true",
                        help="do not run the unmutated suite first")
    parser.add_argument("--build-only", action="store_true",
                        help="only check that each mutation compiles (no tests)")
    parser.add_argument("--markdown", metavar="FILE", help="also write the table as Markdown")
    parser.add_argument("--log-dir", metavar="DIR",
                        help="keep every build and ctest output there, one file per step")
    args = parser.parse_args()
    if args.jobs < 1:
        parser.error("--jobs must be at least 1")

    def terminate(signum, frame):
        raise KeyboardInterrupt

    signal.signal(signal.SIGTERM, terminate)
    try:
        mutations = select(load_mutations(args.mutations), args.only)
        if args.list:
            return list_mutations(mutations)
        return run_mutations(args, mutations)
    except ListError as e:
        print(f"mutate.py: {e}", file=sys.stderr)
        return 2
    except RuntimeError as e:
        print(f"mutate.py: {e}", file=sys.stderr)
        return 3


if __name__ == "__main__":
    sys.exit(main())
