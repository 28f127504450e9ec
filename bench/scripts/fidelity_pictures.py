#!/usr/bin/python3
"""Side-by-side pictures of the reference system's plants and plantarch's: for each species and
age, the reference's driver grows the plant (seed 1) and lists every primitive it drew; those
become an OBJ scene (coloured by organ), and `plantarch compare --against` draws it above
plantarch's plant of the same species, age and seed, in the same framing and at the same scale.

Usage: fidelity_pictures.py --plantarch build/plantarch
                            --reference REF_BUILD/reference_driver --out DIR
                            [--species bean,maize] [--ages 35] [--seed 1] [--panel-size 400]

Without --ages, each species is drawn at one tabled age besides its usual one: seven tenths
of its usual age, or a tree's or vine's first season. Trellises are left out (the reference
draws none). The reference draws its leaves as textured
rectangles whose transparent corners an OBJ cannot carry: they are drawn whole here, so its
leaves look square-ended. Not part of CI (bench/reference/build.sh builds the reference).
"""

import argparse
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import fidelity  # noqa: E402  (the tabled ages)

COLOURS = {"leaf": (0.27, 0.47, 0.2), "shoot": (0.45, 0.36, 0.26), "petiole": (0.42, 0.56, 0.27),
           "flower": (0.95, 0.93, 0.85), "fruit": (0.78, 0.24, 0.16),
           "peduncle": (0.42, 0.56, 0.27)}


def dump_to_obj(dump, obj):
    """The driver's primitive list (label, object ID, vertices) as an OBJ with one material per
    organ label; quads are split in two triangles."""
    mtl = obj[:-4] + ".mtl"
    with open(mtl, "w") as m:
        for name, (r, g, b) in list(COLOURS.items()) + [("other", (0.6, 0.6, 0.6))]:
            m.write(f"newmtl {name}\nKd {r} {g} {b}\n")
    faces = {}
    vertices = []
    with open(dump) as f:
        for line in f:
            cells = line.split()
            if len(cells) < 11:
                continue
            label = cells[0] if cells[0] in COLOURS else "other"
            xyz = [float(c) for c in cells[2:]]
            first = len(vertices) + 1
            points = [xyz[i:i + 3] for i in range(0, len(xyz) - 2, 3)]
            vertices.extend(points)
            for k in range(1, len(points) - 1):
                faces.setdefault(label, []).append((first, first + k, first + k + 1))
    with open(obj, "w") as o:
        o.write(f"mtllib {os.path.basename(mtl)}\n")
        for v in vertices:
            o.write(f"v {v[0]:.6f} {v[1]:.6f} {v[2]:.6f}\n")
        for label, fs in faces.items():
            o.write(f"g {label}\nusemtl {label}\n")
            for a, b, c in fs:
                o.write(f"f {a} {b} {c}\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--plantarch", required=True)
    parser.add_argument("--reference", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--species", help="comma-separated (default: every species)")
    parser.add_argument("--ages", help="comma-separated days (default: the middle tabled age)")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--panel-size", type=int, default=400)
    args = parser.parse_args()
    pictures = fidelity.picture_ages(os.path.join(HERE, "..", "..", "tests", "data",
                                                  "reference_stats.tsv"))
    species = args.species.split(",") if args.species else sorted(pictures)
    os.makedirs(args.out, exist_ok=True)
    driver = os.path.abspath(args.reference)
    with tempfile.TemporaryDirectory() as scratch:
        for s in species:
            tabled = fidelity.default_ages(pictures[s])
            ages = ([float(a) for a in args.ages.split(",")] if args.ages
                    else [tabled[0] if pictures[s] >= 250 else tabled[1]])
            for age in ages:
                dump = os.path.join(scratch, "dump.txt")
                run = subprocess.run([driver, "xml-write", s, f"{age:g}",
                                      os.path.join(scratch, "plant.xml"), str(args.seed), dump],
                                     cwd=os.path.dirname(driver), capture_output=True, text=True)
                if run.returncode != 0:
                    sys.exit(f"fidelity_pictures: reference {s} {age:g}: {run.stderr[-300:]}")
                obj = os.path.join(scratch, f"reference_{s}_{age:g}d.obj")
                dump_to_obj(dump, obj)
                png = os.path.join(args.out, f"{s}_{age:g}d.png")
                run = subprocess.run([args.plantarch, "--seed", str(args.seed), "compare", s,
                                      "--age", f"{age:g}", "--no-trellis", "--against", obj,
                                      "--panel-size",
                                      str(args.panel_size), "-o", png],
                                     capture_output=True, text=True)
                if run.returncode != 0:
                    sys.exit(f"fidelity_pictures: plantarch {s} {age:g}: {run.stderr[-300:]}")
                print(png)


if __name__ == "__main__":
    main()
