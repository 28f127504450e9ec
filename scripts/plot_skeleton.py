#!/usr/bin/env python3
"""Draws a measured skeleton beside the plant plantarch rebuilds on it, to check a
reconstruction by eye: on the left the skeleton's points and segments (each axis in its own
colour, the root as a square), on the right the rebuilt plant seen from the same side. Needs
the plantarch module and matplotlib (Debian: python3-matplotlib).

    python3 scripts/plot_skeleton.py SKELETON --species NAME -o check.png [--unit cm]
        [--age DAYS] [--azimuth DEG] [--title TEXT]
"""

import argparse
import math
import os
import sys


def fail(message):
    sys.exit(f"plot_skeleton: {message}")


def axes_of(skeleton):
    """The skeleton's axes as lists of node indices: each starts at the node it grows from."""
    index = {n.id: i for i, n in enumerate(skeleton.nodes)}
    children = {i: [] for i in range(len(skeleton.nodes))}
    for i, n in enumerate(skeleton.nodes):
        if n.parent >= 0:
            children[index[n.parent]].append(i)
    axes, stack = [], [(i, None) for i, n in enumerate(skeleton.nodes) if n.parent < 0]
    while stack:
        start, first = stack.pop()
        axis = [start] if first is None else [start, first]
        node = axis[-1]
        while True:
            kids = children[node]
            nxt = next((k for k in kids if str(skeleton.nodes[k].link).endswith("continues")),
                       None)
            if nxt is None:
                nxt = next((k for k in kids if str(skeleton.nodes[k].link).endswith("auto")),
                           None)
            for k in kids:
                if k != nxt:
                    stack.append((node, k))
            if nxt is None:
                break
            axis.append(nxt)
            node = nxt
        axes.append(axis)
    return axes


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("skeleton", help="skeleton file: .csv node table, .json or .mtg")
    parser.add_argument("--species", required=True, help="species giving leaves and buds")
    parser.add_argument("-o", "--output", required=True, help="picture (.png, .svg, .pdf)")
    parser.add_argument("--unit", default="m", choices=["m", "cm", "mm"],
                        help="unit of the skeleton's coordinates")
    parser.add_argument("--age", type=float, default=0.0, help="the plant's age, days")
    parser.add_argument("--azimuth", type=float, default=-60.0,
                        help="side the plant is seen from, degrees")
    parser.add_argument("--title", default="", help="title over the two views")
    args = parser.parse_args()
    if not math.isfinite(args.azimuth) or not -360.0 <= args.azimuth <= 360.0:
        fail(f"--azimuth {args.azimuth}: out of range (valid: -360 to 360)")
    if os.path.splitext(args.output)[1].lower() not in (".png", ".svg", ".pdf"):
        fail(f"{args.output}: a picture is .png, .svg or .pdf")

    import plantarch
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        fail("needs matplotlib (Debian: apt-get install python3-matplotlib)")

    unit = {"m": 1.0, "cm": 0.01, "mm": 0.001}[args.unit]
    try:
        skeleton = plantarch.readSkeletonFile(args.skeleton)
        ctx = plantarch.Context()
        arch = plantarch.PlantArchitecture(ctx)
        arch.loadPlantModelFromLibrary(args.species)
        options = plantarch.ReconstructOptions()
        options.unit = unit
        options.age = args.age
        plants = plantarch.reconstructPlants(arch, skeleton, options)
    except plantarch.Error as e:
        fail(str(e))
    image = plantarch.render(ctx, width=900, height=900, azimuth=args.azimuth, elevation=15.0)

    fig = plt.figure(figsize=(10, 5), dpi=110)
    ax = fig.add_subplot(1, 2, 1, projection="3d")
    colours = plt.get_cmap("tab10")
    for k, axis in enumerate(axes_of(skeleton)):
        pts = [skeleton.nodes[i].position for i in axis]
        ax.plot([p.x * unit for p in pts], [p.y * unit for p in pts], [p.z * unit for p in pts],
                "-o", color=colours(k % 10), markersize=3, linewidth=1.5)
    for n in skeleton.nodes:
        if n.parent < 0:
            ax.plot([n.position.x * unit], [n.position.y * unit], [n.position.z * unit], "ks",
                    markersize=6)
    xs = [n.position.x * unit for n in skeleton.nodes]
    ys = [n.position.y * unit for n in skeleton.nodes]
    zs = [n.position.z * unit for n in skeleton.nodes]
    half = max(max(xs) - min(xs), max(ys) - min(ys), max(zs) - min(zs)) / 2 or 0.05
    for setter, values in ((ax.set_xlim, xs), (ax.set_ylim, ys), (ax.set_zlim, zs)):
        mid = (max(values) + min(values)) / 2
        setter(mid - half, mid + half)
    ax.view_init(elev=15.0, azim=args.azimuth)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")
    ax.set_title(f"skeleton: {len(skeleton.nodes)} nodes")
    right = fig.add_subplot(1, 2, 2)
    right.imshow(image)
    right.axis("off")
    shoots = sum(arch.getShootCount(p) for p in plants)
    right.set_title(f"rebuilt as {args.species}: {shoots} shoots")
    if args.title:
        fig.suptitle(args.title)
    fig.tight_layout()
    # Written beside the target, then renamed over it: never half a picture.
    folder = os.path.dirname(os.path.abspath(args.output))
    temporary = os.path.join(folder, f".{os.path.basename(args.output)}.{os.getpid()}.tmp")
    try:
        fig.savefig(temporary, format=os.path.splitext(args.output)[1][1:].lower())
        os.replace(temporary, args.output)
    except OSError as e:
        if os.path.exists(temporary):
            os.remove(temporary)
        fail(f"{args.output}: cannot write: {e.strerror}")


if __name__ == "__main__":
    main()
