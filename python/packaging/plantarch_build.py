"""plantarch's PEP 517 build backend: builds the Python module with the project's CMake and
packs it into a wheel, using the standard library only (so `pip wheel .` and `pip install .`
work offline with --no-build-isolation).

The module is built in the build folder `scripts/setup.sh` uses (`build/`, Release) when the
interpreter running pip has the same base interpreter that folder was configured for (a venv
made from /usr/bin/python3 does), so a wheel after setup.sh only links and packs. Any other
interpreter gets its own folder, `build/wheel-<tag>/`. `pip ... -C build-dir=DIR` names one.

The wheel holds the package (`plantarch/__init__.py`, the extension, its type stubs and
`py.typed`), the species library (`plantarch/species/`), which the extension finds beside
itself, and the Blender add-on (`plantarch/blender/plantarch_import.py`). The extension links plantarch statically; it needs the shared libraries the project's
Debian packages install (Embree, libzip, OpenMP), as the command-line tool does.
"""

import base64
import csv
import hashlib
import io
import os
import re
import subprocess
import sys
import sysconfig
import zipfile

NAME = "plantarch"
SUMMARY = "Builds and grows 3D plants from a phytomer-based parameter model"
SOURCE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


class BuildError(Exception):
    """A build step failed; pip prints the one line."""


def _version():
    with open(os.path.join(SOURCE, "CMakeLists.txt"), encoding="utf-8") as f:
        match = re.search(r"project\(plantarch VERSION (\d+\.\d+\.\d+)", f.read())
    if not match:
        raise BuildError("CMakeLists.txt names no project version")
    return match.group(1)


def _tag():
    """The wheel's tag for the running interpreter: cp311-cp311-linux_x86_64."""
    impl = {"cpython": "cp"}.get(sys.implementation.name, sys.implementation.name)
    version = f"{sys.version_info.major}{sys.version_info.minor}"
    abi_tag = f"{impl}{version}" + ("d" if sysconfig.get_config_var("Py_DEBUG") else "")
    platform = sysconfig.get_platform().replace("-", "_").replace(".", "_")
    return f"{impl}{version}", abi_tag, platform


def _base_interpreter():
    """The interpreter a venv was made from (itself outside a venv), resolved."""
    base = getattr(sys, "_base_executable", None) or sys.executable
    return os.path.realpath(base)


def _cached(build_dir, key):
    try:
        with open(os.path.join(build_dir, "CMakeCache.txt"), encoding="utf-8") as f:
            for line in f:
                if line.startswith(key + ":"):
                    return line.split("=", 1)[1].strip()
    except OSError:
        pass
    return None


def _build_dir(config_settings):
    given = (config_settings or {}).get("build-dir")
    if given:
        return os.path.abspath(given)
    default = os.path.join(SOURCE, "build")
    configured = _cached(default, "PLANTARCH_PYTHON")
    base = _base_interpreter()
    if configured is None or os.path.realpath(configured) == base:
        return default
    return os.path.join(default, "wheel-" + "-".join(_tag()))


def _run(command, log):
    with open(log, "ab") as out:
        result = subprocess.run(command, stdout=out, stderr=subprocess.STDOUT, check=False)
    if result.returncode != 0:
        with open(log, "rb") as f:
            tail = f.read()[-4000:].decode("utf-8", "replace")
        sys.stderr.write(tail)
        raise BuildError(f"{command[0]} failed (exit {result.returncode}); the log is {log}")


def _build_module(build_dir):
    os.makedirs(build_dir, exist_ok=True)
    log = os.path.join(build_dir, "wheel-build.log")
    with open(log, "wb"):
        pass
    configure = ["cmake", "-S", SOURCE, "-B", build_dir]
    if _cached(build_dir, "CMAKE_BUILD_TYPE") is None:
        configure += ["-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release"]
    if _cached(build_dir, "PLANTARCH_PYTHON") is None:
        configure.append("-DPLANTARCH_PYTHON=" + _base_interpreter())
    if _cached(build_dir, "PLANTARCH_SANITIZE") == "ON":
        raise BuildError(f"{build_dir} is a sanitizer build; a wheel needs a plain one")
    _run(configure, log)
    jobs = str(os.cpu_count() or 1)
    _run(["cmake", "--build", build_dir, "--target", "plantarch_python_package", "-j", jobs], log)
    package = os.path.join(build_dir, "python", NAME)
    if not any(n.startswith("_plantarch") and n.endswith(".so") for n in os.listdir(package)):
        raise BuildError(f"the build left no extension in {package}")
    return package


def _metadata(version):
    with open(os.path.join(SOURCE, "README.md"), encoding="utf-8") as f:
        readme = f.read()
    return (
        "Metadata-Version: 2.1\n"
        f"Name: {NAME}\n"
        f"Version: {version}\n"
        f"Summary: {SUMMARY}\n"
        "Requires-Python: >=3.9\n"
        "Requires-Dist: numpy\n"
        "Description-Content-Type: text/markdown\n"
        "\n" + readme
    )


class _Wheel:
    """A wheel being written: every file is recorded with its hash for RECORD."""

    def __init__(self, path):
        self.zip = zipfile.ZipFile(path, "w", compression=zipfile.ZIP_DEFLATED)
        self.records = []

    def add(self, name, data, executable=False):
        info = zipfile.ZipInfo(name, date_time=(1980, 1, 1, 0, 0, 0))
        info.compress_type = zipfile.ZIP_DEFLATED
        info.external_attr = (0o755 if executable else 0o644) << 16
        self.zip.writestr(info, data)
        digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
        self.records.append((name, f"sha256={digest}", str(len(data))))

    def add_file(self, name, path):
        with open(path, "rb") as f:
            self.add(name, f.read(), executable=os.access(path, os.X_OK) and name.endswith(".so"))

    def close(self, record_name):
        out = io.StringIO()
        writer = csv.writer(out, lineterminator="\n")
        for row in self.records:
            writer.writerow(row)
        writer.writerow((record_name, "", ""))
        info = zipfile.ZipInfo(record_name, date_time=(1980, 1, 1, 0, 0, 0))
        info.compress_type = zipfile.ZIP_DEFLATED
        info.external_attr = 0o644 << 16
        self.zip.writestr(info, out.getvalue())
        self.zip.close()


def _package_files(package):
    """(name in the wheel, path) of the built package, the Blender add-on and the species
    library, sorted."""
    files = []
    for entry in sorted(os.listdir(package)):
        path = os.path.join(package, entry)
        if os.path.isfile(path) and (entry.endswith((".py", ".pyi", ".so")) or entry == "py.typed"):
            files.append((f"{NAME}/{entry}", path))
    # The Blender add-on (not a module of the package: it runs inside Blender).
    addon = os.path.join(SOURCE, "blender", "plantarch_import.py")
    files.append((f"{NAME}/blender/plantarch_import.py", addon))
    species = os.path.join(SOURCE, "species")
    for root, dirs, names in os.walk(species):
        dirs.sort()
        for entry in sorted(names):
            path = os.path.join(root, entry)
            if os.path.isfile(path):
                rel = os.path.relpath(path, species).replace(os.sep, "/")
                files.append((f"{NAME}/species/{rel}", path))
    return files


# ---- PEP 517 hooks ------------------------------------------------------------------------


def get_requires_for_build_wheel(config_settings=None):
    return []


def get_requires_for_build_sdist(config_settings=None):
    return []


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    version = _version()
    package = _build_module(_build_dir(config_settings))
    tag = "-".join(_tag())
    name = f"{NAME}-{version}-{tag}.whl"
    dist_info = f"{NAME}-{version}.dist-info"
    os.makedirs(wheel_directory, exist_ok=True)
    final = os.path.join(wheel_directory, name)
    partial = final + ".part"
    try:
        wheel = _Wheel(partial)
        for arcname, path in _package_files(package):
            wheel.add_file(arcname, path)
        wheel.add(f"{dist_info}/METADATA", _metadata(version).encode())
        wheel.add(
            f"{dist_info}/WHEEL",
            (
                "Wheel-Version: 1.0\n"
                "Generator: plantarch_build\n"
                "Root-Is-Purelib: false\n"
                f"Tag: {tag}\n"
            ).encode(),
        )
        wheel.close(f"{dist_info}/RECORD")
        os.replace(partial, final)
    finally:
        if os.path.exists(partial):
            os.remove(partial)
    return name


def build_sdist(sdist_directory, config_settings=None):
    """The tracked files of the source tree (git ls-files) as name-version.tar.gz."""
    import tarfile

    version = _version()
    root = f"{NAME}-{version}"
    listed = subprocess.run(
        ["git", "-C", SOURCE, "ls-files", "-z"], capture_output=True, check=False
    )
    if listed.returncode != 0:
        raise BuildError("an sdist is made from a git checkout (git ls-files failed)")
    names = sorted(n for n in listed.stdout.decode().split("\0") if n)
    os.makedirs(sdist_directory, exist_ok=True)
    name = f"{root}.tar.gz"
    final = os.path.join(sdist_directory, name)
    partial = final + ".part"
    try:
        with tarfile.open(partial, "w:gz") as tar:
            for entry in names:
                path = os.path.join(SOURCE, entry)
                if os.path.isfile(path):
                    info = tar.gettarinfo(path, f"{root}/{entry}")
                    info.mtime, info.uid, info.gid, info.uname, info.gname = 0, 0, 0, "", ""
                    with open(path, "rb") as f:
                        tar.addfile(info, f)
            pkg_info = _metadata(version).encode()
            info = tarfile.TarInfo(f"{root}/PKG-INFO")
            info.size = len(pkg_info)
            tar.addfile(info, io.BytesIO(pkg_info))
        os.replace(partial, final)
    finally:
        if os.path.exists(partial):
            os.remove(partial)
    return name
