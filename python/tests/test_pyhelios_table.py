"""Keeps the table "The C++ class" of docs/pyhelios.md honest. The table maps every public
method of the reference system's C++ PlantArchitecture to plantarch's C++ and Python
equivalents; this test checks that it has one row per reference method, in alphabetical
order; that every plantarch C++ name it gives is declared in include/plantarch/*.h and every
plantarch Python name is an attribute of plantarch.PlantArchitecture or of the plantarch
module (cells marked not offered or **missing** name nothing); and that the counts of the C++
class under "Counts" are those of the rows."""

import pathlib
import re

import plantarch

REPO = pathlib.Path(__file__).resolve().parents[2]
DOC = REPO / "docs" / "pyhelios.md"
STATUSES = ("same name", "differently named or placed", "not offered", "missing")
COLUMNS = ("plantarch C++", "plantarch Python")
COUNTS_HEADER = "| | plantarch C++ | plantarch Python |"


def section(title):
    """The text of the page's section `## title`, up to the next `## ` heading."""
    match = re.search(r"^## " + re.escape(title) + r"\n(.*?)(?=^## |\Z)", DOC.read_text(),
                      re.S | re.M)
    assert match, f"docs/pyhelios.md has no section '## {title}'"
    return match.group(1)


def cells(line):
    return [cell.strip() for cell in line.strip().strip("|").split("|")]


def rows():
    """The rows of the table of "The C++ class": (reference name, C++ cell, Python cell)."""
    text = section("The C++ class")
    header = "| Reference C++ method | plantarch C++ | plantarch Python | Notes |"
    assert header in text, "the table's header changed"
    found = []
    for line in text.splitlines():
        if not line.startswith("| `"):
            continue
        row = cells(line)
        assert len(row) == 4, f"not four cells: {line}"
        name = re.match(r"`(\w+)\(", row[0])
        assert name, f"the first cell names no method: {line}"
        found.append((name.group(1), row[1], row[2]))
    return found


def code_spans(cell):
    return re.findall(r"`([^`]*)`", cell)


def skipped(cell):
    return cell.startswith("not offered") or cell.startswith("**missing**")


def status(reference, cell, prefix):
    """How a plantarch cell answers the reference method: one of STATUSES. "same name" is a
    cell whose first code span calls the method of the same name (`prefix` + name + "(")."""
    if cell.startswith("not offered"):
        return "not offered"
    if cell.startswith("**missing**"):
        return "missing"
    spans = code_spans(cell)
    assert spans, f"{reference}: a cell names no plantarch call: {cell}"
    if spans[0].startswith(prefix + reference + "("):
        return "same name"
    return "differently named or placed"


def header_functions():
    """Names declared as functions or methods in include/plantarch/*.h: a name written after
    a type (`unsigned name(`, `std::vector<T> name(`, `const T& name(`), comments left out."""
    names = set()
    for header in sorted((REPO / "include" / "plantarch").glob("*.h")):
        text = re.sub(r"//[^\n]*", "", header.read_text())
        names.update(re.findall(r"[\w>&*]\s+[&*]?(\w+)\s*\(", text))
    return names


def test_the_table_has_one_row_per_reference_method_in_alphabetical_order():
    names = [name for name, _, _ in rows()]
    assert len(names) > 100  # the parser found the table
    duplicates = sorted({name for name in names if names.count(name) > 1})
    assert duplicates == [], "reference methods listed twice"
    assert names == sorted(names, key=str.lower), "rows not in alphabetical order"


def test_every_cpp_name_is_declared_in_the_headers():
    declared = header_functions()
    assert {"advanceTime", "writeQSM", "getPlantObjectIDs"} <= declared  # the regex works
    unknown = []
    for reference, cpp, _ in rows():
        if skipped(cpp):
            continue
        for span in code_spans(cpp):
            used = set(re.findall(r"PlantArchitecture::(\w+)", span))
            used.update(re.findall(r"(\w+)\(", span))
            unknown += [f"{reference}: {name}" for name in sorted(used - declared)]
    assert unknown == [], "C++ names not declared in include/plantarch/*.h"


def module_attribute(path):
    """Whether `path` ("OrganKind.leaf") names an attribute of the plantarch module."""
    value = plantarch
    for part in path.split("."):
        if not hasattr(value, part):
            return False
        value = getattr(value, part)
    return True


def test_every_python_name_exists():
    unknown = []
    for reference, _, python in rows():
        if skipped(python):
            continue
        for span in code_spans(python):
            # Bare calls; a qualified one (plantarch.GrowthRecorder.clear()) is checked whole
            # below.
            for name in re.findall(r"(?<![\w.])(\w+)\(", span):
                if not (hasattr(plantarch.PlantArchitecture, name) or hasattr(plantarch, name)):
                    unknown.append(f"{reference}: {name}")
            # Dotted names written out in full: plantarch.writeQSM, plantarch.OrganKind.leaf.
            for path in re.findall(r"\bplantarch\.(\w+(?:\.\w+)*)", span):
                if not module_attribute(path):
                    unknown.append(f"{reference}: plantarch.{path}")
    assert unknown == [], "Python names neither on plantarch.PlantArchitecture nor plantarch"


def test_the_counts_of_the_cpp_class_are_those_of_the_rows():
    table = rows()
    expected = {}
    for column, prefix, index in (("plantarch C++", "PlantArchitecture::", 1),
                                  ("plantarch Python", "", 2)):
        counts = {s: 0 for s in STATUSES}
        for row in table:
            counts[status(row[0], row[index], prefix)] += 1
        counts["reference methods"] = len(table)
        expected[column] = counts

    lines = section("Counts").splitlines()
    assert COUNTS_HEADER in lines, "no counts table of the C++ class under Counts"
    start = lines.index(COUNTS_HEADER)
    written = {column: {} for column in COLUMNS}
    for line in lines[start + 2:]:
        if not line.startswith("|"):
            break
        label, cpp, python = cells(line)
        written["plantarch C++"][label] = int(cpp)
        written["plantarch Python"][label] = int(python)
    assert written == expected
