"""The Python module against the C++ headers: every public method of PlantArchitecture and
Context is bound under its own name or listed in python/unbound-methods.txt with where Python
has it or why not."""

import pathlib
import re

import pytest

import plantarch

REPO = pathlib.Path(__file__).resolve().parents[2]
CLASSES = [("PlantArchitecture", "include/plantarch/PlantArchitecture.h"),
           ("Context", "include/plantarch/Context.h")]
SPECIFIERS = re.compile(r"^(?:(?:static|virtual|explicit|inline|constexpr|\[\[nodiscard\]\])\s+)*")
METHOD = re.compile(r"^(?:[\w:<>,\*&\s]+?[\s\*&])?(\w+)\s*\(")


def public_methods(header, cls):
    """Names of the public member functions declared in `cls`'s body (constructors and
    operators left out), read from the header text."""
    text = (REPO / header).read_text()
    match = re.search(r"\nclass " + cls + r"\b[^;{]*\{(.*?)\n\};", text, re.S)
    assert match, f"class {cls} not found in {header}"
    body = re.sub(r"//[^\n]*", "", match.group(1))
    names, public, depth = set(), False, 0
    for line in body.splitlines():
        s = line.strip()
        if depth == 0 and re.match(r"(public|private|protected)\s*:", s):
            public = s.startswith("public")
            continue
        if depth == 0 and public and not s.startswith(("using", "friend", "struct", "class",
                                                       "enum", "template")):
            m = METHOD.match(SPECIFIERS.sub("", s))
            if m and m.group(1) not in (cls, "operator"):
                names.add(m.group(1))
        depth += s.count("{") - s.count("}")
    return names


def unbound_list():
    entries = {}
    for number, line in enumerate((REPO / "python" / "unbound-methods.txt").read_text()
                                  .splitlines(), 1):
        if not line.strip() or line.startswith("#"):
            continue
        name, _, why = line.partition(":")
        assert name not in entries, f"line {number}: {name} listed twice"
        entries[name.strip()] = why.strip()
    return entries


@pytest.mark.parametrize("cls, header", CLASSES)
def test_every_public_method_is_bound_or_listed(cls, header):
    methods = public_methods(header, cls)
    assert len(methods) > 40  # the parser found the class body
    bound = set(dir(getattr(plantarch, cls)))
    listed = {k.split(".", 1)[1]: v for k, v in unbound_list().items() if k.startswith(cls + ".")}
    missing = sorted(m for m in methods if m not in bound and m not in listed)
    assert missing == [], f"{cls}: neither bound nor listed in python/unbound-methods.txt"
    for name, why in listed.items():
        assert name in methods, f"{cls}.{name} is listed but is no public method of {header}"
        assert name not in bound, f"{cls}.{name} is listed but bound: drop the entry"
        if why.startswith("as "):
            other = why[3:].strip()
            assert other in bound, f"{cls}.{name}: Python has no {other}"
        else:
            assert why.startswith("not bound: ") and len(why) > 30, f"{cls}.{name}: {why!r}"


def test_the_walk_sees_a_known_method_and_a_private_one():
    methods = public_methods("include/plantarch/PlantArchitecture.h", "PlantArchitecture")
    assert {"advanceTime", "buildPlantInstanceFromLibrary", "getPlantHeight"} <= methods
    assert "impl_" not in methods


def header_comments():
    """The `///` comment of each declaration of the public headers, as the module's docstrings
    are generated from them (python/tools/make_docstrings.py)."""
    import importlib.util

    spec = importlib.util.spec_from_file_location(
        "make_docstrings", REPO / "python" / "tools" / "make_docstrings.py")
    assert spec is not None and spec.loader is not None
    tool = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(tool)
    comments = {}
    for header in sorted((REPO / "include" / "plantarch").glob("*.h")):
        for scope, name, comment in tool.declarations(header.read_text()):
            comments.setdefault((scope, name), []).append(comment)
    return comments


@pytest.mark.parametrize("cls, header", CLASSES)
def test_a_bound_method_s_help_is_its_header_comment(cls, header):
    """Where Python has a C++ method under its own name, its help carries the header's comment
    (one text for C++ and Python; a Python note may follow it)."""
    comments = header_comments()
    checked = 0
    for name in sorted(public_methods(header, cls)):
        method = getattr(getattr(plantarch, cls), name, None)
        if method is None or (cls, name) not in comments:
            continue
        doc = " ".join((method.__doc__ or "").split())
        for comment in comments[(cls, name)]:
            assert " ".join(comment.split()) in doc, f"{cls}.{name}: help lacks {comment[:60]!r}"
        checked += 1
    assert checked > (60 if cls == "PlantArchitecture" else 15)


def test_the_module_s_functions_carry_their_header_comment():
    comments = header_comments()
    for name in ("writePLY", "writeGLTF", "readPLY", "samplePoints", "render", "writeQSM"):
        doc = " ".join(getattr(plantarch, name).__doc__.split())
        for comment in comments[("", name)]:
            assert " ".join(comment.split()) in doc, f"{name}: help lacks {comment[:60]!r}"
