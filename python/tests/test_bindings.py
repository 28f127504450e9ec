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
