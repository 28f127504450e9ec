"""Writes type stubs (_plantarch.pyi) for the built plantarch module, from the signatures and
docstrings pybind11 gives every function, method and property.

Usage: make_stubs.py BUILD_PYTHON_DIR   (the folder holding plantarch/_plantarch*.so)
"""

import ast
import inspect
import os
import re
import sys

SIGNATURE = re.compile(r"^(?:\d+\. )?(\w+)\((.*)\)(?: -> (.+))?$")
KNOWN = {"Any", "None", "int", "float", "bool", "str", "bytes", "object"}


def clean_type(text):
    text = text.replace("plantarch._plantarch.", "").replace("numpy.ndarray", "numpy.ndarray")
    text = re.sub(r"numpy\.ndarray\[[^\]]*\]", "numpy.ndarray", text)
    text = text.replace("Callable[[", "Callable[[")
    return text


def clean_args(args):
    args = re.sub(r"<[^<>]*>", "...", args)  # defaults printed as <object at 0x...>
    args = re.sub(r"= [^,()\[\]]*\.\.\.[^,()\[\]]*", "= ...", args)
    return clean_type(args)


def valid(stub):
    try:
        ast.parse(stub)
        return True
    except SyntaxError:
        return False


def signatures(name, doc, method):
    out = []
    for line in (doc or "").splitlines():
        m = SIGNATURE.match(line.strip())
        if not m or m.group(1) != name:
            continue
        args, ret = clean_args(m.group(2)), clean_type(m.group(3) or "None")
        text = f"def {name}({args}) -> {ret}: ..."
        if not valid(text):
            self_arg = "self, " if method else ""
            text = f"def {name}({self_arg}*args: Any, **kwargs: Any) -> Any: ..."
        out.append(text)
    if not out:
        out.append(f"def {name}({'self, ' if method else ''}*args: Any, **kwargs: Any) -> Any: ...")
    return out


def summary(doc):
    lines = [l for l in (doc or "").splitlines() if l.strip() and not SIGNATURE.match(l.strip())]
    return lines[0].strip().replace('"""', "'") if lines else ""


def emit_function(lines, name, obj, indent, method):
    sigs = signatures(name, obj.__doc__, method)
    doc = summary(obj.__doc__)
    for sig in sigs:
        if len(sigs) > 1:
            lines.append(indent + "@overload")
        lines.append(indent + sig[:-4] + (f'\n{indent}    """{doc}"""' if doc else " ..."))


def emit_class(lines, name, cls):
    bases = [b.__name__ for b in cls.__bases__ if b.__name__ not in ("object", "pybind11_object")]
    lines.append(f"class {name}({', '.join(bases)}):" if bases else f"class {name}:")
    doc = summary(cls.__doc__)
    if doc:
        lines.append(f'    """{doc}"""')
    body = 0
    for attr, value in sorted(vars(cls).items()):
        if attr.startswith("_") and attr not in (
            "__init__", "__eq__", "__iter__", "__len__", "__enter__", "__exit__"):
            continue
        if isinstance(value, property):
            lines.append(f"    {attr}: Any")
            d = summary(value.__doc__)
            if d:
                lines.append(f'    """{d}"""')
            body += 1
        elif callable(value):
            emit_function(lines, attr, value, "    ", True)
            body += 1
        elif isinstance(value, cls):  # enum members
            lines.append(f"    {attr}: {name}")
            body += 1
    if not body:
        lines.append("    ...")
    lines.append("")


def main():
    sys.path.insert(0, sys.argv[1])
    import plantarch._plantarch as module

    lines = [
        "# Type stubs of plantarch._plantarch, generated from the built module by",
        "# python/tools/make_stubs.py. Do not edit.",
        "from typing import (Any, Callable, Dict, Iterator, List, Optional, Sequence, Tuple,",
        "                    Union, overload)",
        "import numpy",
        "from plantarch import vec2, vec3",
        "",
    ]
    names = sorted(vars(module).items(), key=lambda kv: (not inspect.isclass(kv[1]), kv[0]))
    for name, obj in names:
        if name.startswith("_"):
            continue
        if inspect.isclass(obj):
            emit_class(lines, name, obj)
        elif callable(obj):
            emit_function(lines, name, obj, "", False)
        else:
            lines.append(f"{name}: Any")
    text = "\n".join(lines) + "\n"
    ast.parse(text)  # a stub that does not parse is a build error
    target = os.path.join(sys.argv[1], "plantarch", "_plantarch.pyi")
    with open(target + ".tmp", "w") as f:
        f.write(text)
    os.replace(target + ".tmp", target)


if __name__ == "__main__":
    main()
