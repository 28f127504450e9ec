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
    text = text.replace("plantarch._plantarch.", "")
    text = re.sub(r"numpy\.ndarray\[[^\]]*\]", "numpy.ndarray", text)
    text = re.sub(r"\bfunction\b", "Callable[..., Any]", text)  # a Python callable
    return text


def clean_args(args):
    """Parameter annotations as callers may pass them: any sequence of numbers where a vec3 or
    vec2 is taken (the module converts it), any sequence where a list is taken."""
    args = re.sub(r"<[^<>]*>", "...", args)  # defaults printed as <object at 0x...>
    args = re.sub(r"= [^,()\[\]]*\.\.\.[^,()\[\]]*", "= ...", args)
    args = clean_type(args)
    args = re.sub(r"\bList\[", "Sequence[", args)
    args = re.sub(r"\bvec3\b", "Vec3Like", args)
    args = re.sub(r"\bvec2\b", "Vec2Like", args)
    args = args.replace("numpy.ndarray", "numpy.typing.ArrayLike")
    return args


def valid(stub):
    try:
        ast.parse(stub)
        return True
    except SyntaxError:
        return False


def signatures(name, doc, method):
    out = []
    overloaded = "Overloaded function." in (doc or "")
    for line in (doc or "").splitlines():
        m = SIGNATURE.match(line.strip())
        if not m or m.group(1) != name:
            continue
        if overloaded and m.group(2) == "*args, **kwargs":
            continue  # the dispatcher's own line above the numbered overloads
        args, ret = clean_args(m.group(2)), clean_type(m.group(3) or "None")
        text = f"def {name}({args}) -> {ret}: ..."
        if not valid(text):
            self_arg = "self, " if method else ""
            text = f"def {name}({self_arg}*args: Any, **kwargs: Any) -> Any: ..."
        out.append(text)
    if not out:
        out.append(f"def {name}({'self, ' if method else ''}*args: Any, **kwargs: Any) -> Any: ...")
    return out


def property_type(prop):
    """The type a property's getter returns, from its pybind11 signature ("(arg0: X) -> T")."""
    first = ((prop.fget and prop.fget.__doc__) or "").strip().splitlines()
    m = re.match(r"^\(.*\) -> (.+)$", first[0]) if first else None
    kind = clean_type(m.group(1)) if m else "Any"
    return kind if kind != "object" and valid(f"x: {kind}") else "Any"


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
    # An exception's attributes are set on each instance; its docstring names them.
    listed = re.search(r"Attributes: ([\w, ]+)\.", cls.__doc__ or "")
    if issubclass(cls, BaseException) and listed:
        for attr in listed.group(1).split(", "):
            lines.append(f"    {attr}: Any")
            body += 1
    for attr, value in sorted(vars(cls).items()):
        if attr.startswith("_") and attr not in (
            "__init__", "__eq__", "__iter__", "__len__", "__enter__", "__exit__"):
            continue
        if isinstance(value, property):
            kind = property_type(value)
            d = summary(value.__doc__)
            if value.fset is None:  # read only: a property, so editors refuse assignments
                lines.append("    @property")
                lines.append(f"    def {attr}(self) -> {kind}:" + (f'\n        """{d}"""' if d else " ..."))
            else:
                lines.append(f"    {attr}: {kind}")
                if d:
                    lines.append(f'    """{d}"""')
            body += 1
        elif isinstance(value, staticmethod):
            lines.append("    @staticmethod")
            emit_function(lines, attr, value.__func__, "    ", False)
            body += 1
        elif callable(value):
            emit_function(lines, attr, value, "    ", True)
            body += 1
        elif isinstance(value, cls):  # enum members
            lines.append(f"    {attr}: {name}")
            body += 1
    if hasattr(cls, "__members__"):  # an enum: its members by name, hashable
        lines.append("    __members__: Dict[str, Any]")
        lines.append("    def __hash__(self) -> int: ...")
        lines.append("    def __int__(self) -> int: ...")
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
        "import numpy.typing",
        "from plantarch import vec2, vec3",
        "",
        "# What a parameter taking a point or a pair accepts: the named tuple or any sequence.",
        "Vec3Like = Union[vec3, Tuple[float, float, float], Sequence[float]]",
        "Vec2Like = Union[vec2, Tuple[float, float], Sequence[float]]",
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
