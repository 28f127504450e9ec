"""plantarch: builds and grows 3D plants (crops, weeds, vines, orchard trees) from a
phytomer-based parameter model.

    import plantarch
    context = plantarch.Context()
    arch = plantarch.PlantArchitecture(context)
    arch.loadPlantModelFromLibrary("bean")
    plant = arch.buildPlantInstanceFromLibrary(plantarch.vec3(0, 0, 0), age=30)
    mesh = arch.getMeshArrays(plant)          # numpy views: vertices, triangles, labels

Names follow the model specification (and plantarch's C++ API). Errors are plantarch.Error
(a ValueError) with one line naming the parameter, value and valid range. See docs/python.md.
"""

from typing import NamedTuple


class vec3(NamedTuple):
    """A point or direction, metres (z up). Any sequence of three numbers is accepted too."""

    x: float
    y: float
    z: float


class vec2(NamedTuple):
    """A pair of numbers (spacings, extents). Any sequence of two numbers is accepted too."""

    x: float
    y: float


def make_int2(x: int, y: int):
    """A pair of whole numbers (plant counts), as the specification writes it."""
    return (int(x), int(y))


from ._plantarch import *  # noqa: E402,F401,F403
from ._plantarch import (  # noqa: E402
    Context,
    PlantArchitecture,
    Error,
    render as _render,
    encodePNG,
    __version__,
)
from ._plantarch import ORGAN_LABELS  # noqa: E402,F401
from . import _plantarch  # noqa: E402

make_vec3 = vec3
make_vec2 = vec2


def render(scene, width=640, height=480, mode="shaded", **options):
    if isinstance(scene, Plant):
        return scene.render(width=width, height=height, mode=mode, **options)
    if isinstance(scene, PlantArchitecture):
        scene = scene.getContext()
    return _render(scene, width=width, height=height, mode=mode, **options)


class Plant:
    """One plant of a PlantArchitecture, as a value a notebook can show (_repr_png_).

    It holds the PlantArchitecture and the plant's ID: once the plant is deleted, its methods
    raise plantarch.Error (its repr says so).
    """

    def __init__(self, architecture, plantID):
        architecture.getPlantAge(plantID)  # plantarch.Error when there is no such plant
        self.architecture = architecture
        self.plantID = int(plantID)

    def statistics(self):
        """Height, leaf area, leaf count, shoots and triangles, as a dict."""
        a, p = self.architecture, self.plantID
        summary = a.summarizePlant(p)  # counts triangles without copying the mesh
        return {
            "plantID": p,
            "age": a.getPlantAge(p),
            "height": summary.height,
            "leaf_area": summary.leafArea,
            "leaf_count": summary.leaves,
            "shoots": a.getShootCount(p),
            "triangles": summary.triangles,
        }

    to_dict = statistics

    def shoot_tree(self):
        """The shoots as a list of dicts (id, type, parent, parent_node, rank, nodes, children)."""
        state = self.architecture.plant(self.plantID)
        return [
            {
                "id": s.id,
                "type": s.shoot_type_label,
                "parent": s.parent_shoot_ID,
                "parent_node": s.parent_node_index,
                "rank": s.rank,
                "nodes": len(s.phytomers),
                "children": list(s.children),
            }
            for s in state.shoots
            if not s.removed
        ]

    def render(self, width=480, height=480, mode="shaded", **options):
        """This plant alone, rendered as an image array."""
        context = Context()
        scratch = PlantArchitecture(context)
        scratch.readPlantStructureXMLString(
            self.architecture.getPlantStructureXML([self.plantID])
        )
        return _render(context, width=width, height=height, mode=mode, **options)

    def _repr_png_(self):
        return encodePNG(self.render())

    def __repr__(self):
        try:
            s = self.statistics()
        except Error:
            return f"<plantarch.Plant {self.plantID}: no longer in its PlantArchitecture>"
        return (
            f"<plantarch.Plant {s['plantID']}: {s['age']:g} days, {s['height']:.3f} m tall, "
            f"{s['leaf_count']} leaves, {s['shoots']} shoots, {s['triangles']} triangles>"
        )


render.__doc__ = "The scene may also be a PlantArchitecture or a Plant.\n\n" + (_render.__doc__ or "")


def _context_png(self):
    return encodePNG(_render(self, width=480, height=480))


def _architecture_png(self):
    return encodePNG(_render(self.getContext(), width=480, height=480))


Context._repr_png_ = _context_png
PlantArchitecture._repr_png_ = _architecture_png
PlantArchitecture.getPlant = lambda self, plantID: Plant(self, plantID)
PlantArchitecture.getPlant.__doc__ = "The plant as a plantarch.Plant (statistics, shoot tree, picture)."


def _nearest_attribute(cls):
    """__getattr__ for a class of the module: a mistyped name raises AttributeError naming the
    nearest attribute the class has: one that differs only in case and underscores (breakTime:
    break_time), else one that ends with the name (length: internode_length), else the closest
    spelling."""

    def __getattr__(self, name):
        import difflib

        names = [n for n in dir(cls) if not n.startswith("_")]
        def fold(n):
            return n.replace("_", "").lower()

        near = [n for n in names if fold(n) == fold(name)]
        near = near or [n for n in names if fold(n).endswith(fold(name)) and "_" in n]
        near = near or difflib.get_close_matches(name, names, 1)
        hint = f"; did you mean {near[0]!r}?" if near else ""
        # obj without name: the hint above is the only one Python shows
        raise AttributeError(f"{cls.__name__!r} object has no attribute {name!r}{hint}", obj=self)

    return __getattr__


for _cls in vars(_plantarch).values():
    if isinstance(_cls, type) and not issubclass(_cls, BaseException) and not hasattr(_cls, "__members__"):
        _cls.__getattr__ = _nearest_attribute(_cls)
