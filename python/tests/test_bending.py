"""Shoots bending under load from Python: the mechanics parameters, bendPlant, pullNode,
displaceNode against the analytic cantilever, the bend kept in the plant state, and errors."""

import math

import pytest

import plantarch


def cantilever(n=40, radius=0.01, modulus=1e10, density=0.0):
    """A horizontal weightless (or heavy) shoot 1 m long along +x."""
    ctx = plantarch.Context()
    arch = plantarch.PlantArchitecture(ctx)
    shoot = plantarch.ShootParameters()
    shoot.phytomer_parameters.internode.pitch = 0
    arch.defineShootType("stem", shoot)
    arch.setGroundClearance(False)
    plant = arch.addPlantInstance(plantarch.vec3(0, 0, 0), 0)
    arch.addBaseStemShoot(plant, plantarch.ShootSpec(
        shoot_type_label="stem", current_node_number=n,
        base_rotation=plantarch.AxisRotation(90, 0, 0), internode_radius=radius,
        internode_length_max=1.0 / n))
    arch.removeShootLeaves(plant, 0)
    phenology = arch.plant(plant).phenology
    phenology.mechanics.elastic_modulus = modulus
    phenology.mechanics.stem_density = density
    arch.setPlantPhenologicalThresholds(plant, phenology)
    EI = modulus * math.pi / 4 * radius ** 4
    return ctx, arch, plant, EI


def test_mechanics_parameters_are_in_the_phenology():
    m = plantarch.PhenologyParameters().mechanics
    assert m.enabled is False
    assert m.elastic_modulus == pytest.approx(5e9)
    assert m.fruit_density == pytest.approx(900)


def test_weight_and_pull_match_the_cantilever():
    ctx, arch, plant, EI = cantilever(density=1000.0)
    plantarch.bendPlant(arch, plant)
    w = 1000 * 9.80665 * math.pi * 0.01 ** 2
    tip = plantarch.bentNodePositions(arch, plant, 0)[-1]
    assert -tip.z == pytest.approx(w / (8 * EI), rel=0.01)
    bend = arch.plant(plant).shoots[0].phytomers[-1].internode.bend
    assert bend is not None and bend.angle > 0

    ctx, arch, plant, EI = cantilever()
    P = 0.5
    r = plantarch.pullNode(arch, plant, 0, 39, plantarch.vec3(0, 0, -P))
    assert -r.displacement.z == pytest.approx(P / (3 * EI), rel=0.01)
    assert r.groundForce.z == pytest.approx(P, rel=1e-5)

    r = plantarch.displaceNode(arch, plant, 0, 39, plantarch.vec3(0, 0.002, 0))
    assert r.displacement.y == pytest.approx(0.002, rel=1e-3)
    assert r.force.y == pytest.approx(3 * EI * 0.002, rel=0.01)
    plantarch.straightenPlant(arch, plant)
    assert plantarch.bentNodePositions(arch, plant, 0)[-1].y == pytest.approx(0, abs=1e-6)


def test_bad_pulls_raise_one_line_errors():
    ctx, arch, plant, EI = cantilever(n=10)
    with pytest.raises(plantarch.Error, match="node"):
        plantarch.pullNode(arch, plant, 0, 10, plantarch.vec3(0, 0, -1))
    with pytest.raises(plantarch.Error, match="force"):
        plantarch.pullNode(arch, plant, 0, 3, plantarch.vec3(math.nan, 0, 0))
    phenology = arch.plant(plant).phenology
    with pytest.raises(plantarch.Error, match="elastic_modulus"):
        phenology.mechanics.elastic_modulus = -1  # checked as it is set
