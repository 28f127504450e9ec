"""A reader for the subset of USD's text format (.usda) plantarch writes: prims with
metadata, attributes with values or time samples, arrays, tuples, dictionaries, paths (<...>),
assets (@...@) and attribute metadata. It returns plain Python data so the tests can check
structure, counts and labels."""

import re

TOKEN = re.compile(r'"(?:[^"\\]|\\.)*"|<[^>\s]*>|@[^@]*@|[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?|'
                   r'[A-Za-z_][\w:.]*|\[\]|[()\[\]{}=,]')


class Prim:
    def __init__(self, kind, name):
        self.kind, self.name, self.specifier = kind, name, "def"
        self.metadata, self.attributes, self.children = {}, {}, []

    def child(self, name):
        return next(c for c in self.children if c.name == name)


class Reader:
    def __init__(self, text):
        assert text.startswith("#usda 1.0\n"), "not a usda file"
        self.tokens = TOKEN.findall(text[len("#usda 1.0"):])
        self.i = 0

    def peek(self):
        return self.tokens[self.i] if self.i < len(self.tokens) else None

    def take(self, expected=None):
        t = self.tokens[self.i]
        self.i += 1
        if expected is not None and t != expected:
            raise ValueError(f"expected {expected!r}, found {t!r} at token {self.i}")
        return t

    def value(self):
        t = self.take()
        if t in ("(", "["):
            close = ")" if t == "(" else "]"
            items = []
            while self.peek() != close:
                items.append(self.value())
                if self.peek() == ",":
                    self.take()
            self.take(close)
            return tuple(items) if t == "(" else items
        if t == "{":
            return self.dictionary()
        if t.startswith('"'):
            return t[1:-1].encode().decode("unicode_escape")
        try:
            return int(t)
        except ValueError:
            try:
                return float(t)
            except ValueError:
                return t

    def dictionary(self):
        d = {}
        while self.peek() != "}":
            self.take()  # the value's type
            if self.peek() == "[]":
                self.take()
            name = self.take()
            self.take("=")
            d[name] = self.value()
        self.take("}")
        return d

    def time_samples(self):
        """{ time: value, ... } as a dict from time code to value."""
        samples = {}
        self.take("{")
        while self.peek() != "}":
            time = float(self.take())
            samples[time] = self.value()
            if self.peek() == ",":
                self.take()
        self.take("}")
        return samples

    def metadata(self):
        m = {}
        self.take("(")
        while self.peek() != ")":
            key = self.take()
            if key in ("prepend", "append"):
                key = self.take()
            self.take("=")
            m[key] = self.value()
        self.take(")")
        return m

    def prim(self):
        specifier = self.take()
        if specifier not in ("def", "class", "over"):
            raise ValueError(f"expected a prim, found {specifier!r} at token {self.i}")
        kind = self.take()
        p = Prim(kind, self.value())
        p.specifier = specifier
        if self.peek() == "(":
            p.metadata = self.metadata()
        self.take("{")
        while self.peek() != "}":
            if self.peek() in ("def", "class", "over"):
                p.children.append(self.prim())
                continue
            if self.peek() in ("uniform", "custom"):
                self.take()
            kind = self.take()
            if self.peek() == "[]":
                kind += self.take()
            name = self.take()
            attr = {"type": kind, "value": None, "metadata": {}}
            if self.peek() == "=":
                self.take()
                attr["value"] = self.time_samples() if name.endswith(".timeSamples") \
                    else self.value()
            if self.peek() == "(":
                attr["metadata"] = self.metadata()
            p.attributes[name] = attr
        self.take("}")
        return p

    def stage(self):
        layer = self.metadata() if self.peek() == "(" else {}
        prims = []
        while self.peek() is not None:
            prims.append(self.prim())
        return layer, prims


def read(path):
    with open(path) as f:
        return Reader(f.read()).stage()
