"""Leaf angle distributions from Python (docs/measured-plants.md, "Leaf angle distributions"):
the parameters from the table, the histogram queries, the target's shares and G."""

import math

import pytest

import plantarch


def test_a_canopy_grown_with_a_distribution_has_its_histogram():
    arch = plantarch.PlantArchitecture(plantarch.Context())
    arch.loadPlantModelFromLibrary("bean")
    phenology = arch.getDefaultPhenology()
    assert phenology.leaf_angles.inclination == "none"
    phenology.leaf_angles.inclination = "erectophile"
    arch.setDefaultPhenology(phenology)
    plants = arch.buildPlantCanopyFromLibrary(plantarch.vec3(0, 0, 0), plantarch.vec2(0.4, 0.4),
                                              (2, 2), 30.0)
    h = plantarch.leafInclinationHistogram(arch, plants)
    assert len(h.fractions) == 9 and len(h.edges) == 10
    assert sum(h.fractions) == pytest.approx(1.0)
    assert h.leafArea > 0
    assert h.meanInclination == pytest.approx(plantarch.meanLeafInclination(arch, plants))
    # Erect leaves: most of the area above 45 degrees (curved blades spread it some).
    assert sum(h.fractions[5:]) > 0.6
    one = plantarch.leafInclinationHistogram(arch, plants[0], [0.0, 45.0, 90.0])
    assert len(one.fractions) == 2
    with pytest.raises(plantarch.Error, match="edges"):
        plantarch.leafInclinationHistogram(arch, plants[0], [0.0, 100.0])


def test_the_distributions_shares_and_projection():
    p = plantarch.PhenologyParameters().leaf_angles
    assert plantarch.leafInclinationFractions(p) == [0.0] * 9
    p.inclination = "spherical"
    shares = plantarch.leafInclinationFractions(p)
    expected = [math.cos(math.radians(10 * i)) - math.cos(math.radians(10 * i + 10))
                for i in range(9)]
    assert shares == pytest.approx(expected, abs=1e-9)
    assert plantarch.leafProjection(p, 30.0) == pytest.approx(0.5, abs=1e-4)
    assert plantarch.leafInclinationDensity(p, 90.0) == pytest.approx(math.pi / 180, rel=1e-9)
    p.histogram = {"30": 1.0, "90": 1.0}
    p.inclination = "histogram"
    assert plantarch.leafInclinationFractions(p, [0.0, 30.0, 90.0]) == pytest.approx([0.5, 0.5])
    with pytest.raises(plantarch.Error, match="ellipsoidal_x"):
        p.ellipsoidal_x = 20.0
