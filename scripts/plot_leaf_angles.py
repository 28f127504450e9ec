"""Draws docs/images/leaf-angle-histograms.png: the leaf inclination histograms of bean canopies
grown with three leaf angle distributions, beside each distribution's expected shares.

Usage: PYTHONPATH=build/python python3 scripts/plot_leaf_angles.py [OUT.png]
"""

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import plantarch  # noqa: E402

FAMILIES = [
    ("planophile", {}),
    ("spherical", {}),
    ("erectophile", {}),
    ("ellipsoidal", {"ellipsoidal_x": 3.0}),
]


def canopy_histogram(family, settings):
    arch = plantarch.PlantArchitecture(plantarch.Context())
    arch.setSeed(1)
    arch.loadPlantModelFromLibrary("bean")
    phenology = arch.getDefaultPhenology()
    angles = phenology.leaf_angles
    angles.inclination = family
    for name, value in settings.items():
        setattr(angles, name, value)
    phenology.leaf_angles = angles
    arch.setDefaultPhenology(phenology)
    plants = arch.buildPlantCanopyFromLibrary((0, 0, 0), (0.4, 0.4), (4, 4), 40.0)
    measured = plantarch.leafInclinationHistogram(arch, plants)
    expected = plantarch.leafInclinationFractions(angles)
    return measured, expected


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "docs/images/leaf-angle-histograms.png"
    fig, axes = plt.subplots(1, len(FAMILIES), figsize=(12, 3.2), sharey=True)
    for ax, (family, settings) in zip(axes, FAMILIES):
        measured, expected = canopy_histogram(family, settings)
        centres = [0.5 * (a + b) for a, b in zip(measured.edges, measured.edges[1:])]
        ax.bar(centres, measured.fractions, width=9, color="#6a9f4e",
               label="bean canopy (triangles)")
        ax.plot(centres, expected, "o-", color="#333333", label="target distribution")
        title = family + "".join(f", x = {v:g}" for v in settings.values())
        ax.set_title(f"{title}\nmean {measured.meanInclination:.1f} degrees", fontsize=10)
        ax.set_xlabel("leaf inclination (degrees)")
        ax.set_xticks(range(0, 91, 30))
    axes[0].set_ylabel("share of leaf area")
    axes[0].legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print("wrote", out)


if __name__ == "__main__":
    main()
