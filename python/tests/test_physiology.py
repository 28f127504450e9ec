"""The carbohydrate budget and nitrogen model from Python: records as numpy arrays."""

import math

import numpy as np
import pytest

import plantarch


def bean(age=15.0):
    ctx = plantarch.Context()
    arch = plantarch.PlantArchitecture(ctx)
    arch.loadPlantModelFromLibrary("bean")
    plant = arch.buildPlantInstanceFromLibrary(plantarch.vec3(0, 0, 0), age)
    return ctx, arch, plant


def test_a_season_of_clear_days_gives_records_whose_balance_closes():
    ctx, arch, plant = bean()
    arch.enableCarbohydrateModel(plant)
    arch.enableNitrogenModel(plant)
    arch.addPlantNitrogen(plant, 1.0)
    weather = []
    for day in range(1, 4):
        weather += plantarch.clearSkyDay(38.54, -121.74, f"2026-06-0{day}")
    options = plantarch.PhysiologyOptions()
    options.location = (38.54, -121.74)
    options.light.diffuseRays = 16
    options.lightEvery = 4
    records = plantarch.growPhysiology(arch, weather, options)
    assert list(records) == plantarch.physiologyColumns()
    assert isinstance(records["input"], np.ndarray)
    np.testing.assert_array_equal(records["age"], [16.0, 17.0, 18.0])
    assert (records["input"] > 0).all()
    assert (records["absorbed_par"] > 0).all()
    pools = records["sugar"] + records["starch"]
    change = np.diff(pools)
    fluxes = (records["input"] - records["maintenance"] - records["growth"]
              - records["growth_respiration"] - records["losses"])[1:]
    np.testing.assert_allclose(change, fluxes, rtol=1e-9, atol=1e-12)
    same = arch.getPhysiologyRecords(plant)
    np.testing.assert_array_equal(same["sugar"], records["sugar"])
    assert arch.hasCarbohydrateModel(plant) and arch.hasNitrogenModel(plant)


def test_measured_rates_feed_the_budget_and_bad_values_raise():
    ctx, arch, plant = bean(20.0)
    arch.enableCarbohydrateModel(plant)
    leaves = arch.getPlantObjectIDs(plant, plantarch.OrganKind.leaf)
    area = sum(ctx.objectArea(o) for o in leaves)
    arch.addLeafPhotosynthesis({o: 12.0 for o in leaves}, 10.0)
    arch.advanceTime(1.0, plant)
    records = arch.getPhysiologyRecords(plant)
    assert records["input"][0] == pytest.approx(12.0 * area * 10 * 3600e-6, rel=1e-12)
    with pytest.raises(plantarch.Error, match="hours must be from 0 to 24"):
        arch.addLeafPhotosynthesis({leaves[0]: 1.0}, -1.0)
    with pytest.raises(plantarch.Error, match="finite rate"):
        arch.addLeafPhotosynthesis({leaves[0]: math.nan}, 1.0)
    with pytest.raises(plantarch.Error, match="not a leaf of any plant"):
        arch.addLeafPhotosynthesis({10**6: 1.0}, 1.0)
    with pytest.raises(plantarch.Error, match="no nitrogen model"):
        arch.addPlantNitrogen(plant, 1.0)
    with pytest.raises(plantarch.Error, match="air temperature"):
        arch.setAirTemperature(math.inf)
    with pytest.raises(plantarch.Error, match="weather has no hours"):
        plantarch.growPhysiology(arch, [])


def test_parameters_are_in_the_plant_phenology():
    table = plantarch.PhenologyParameters()
    assert table.carbohydrates.enabled is False
    assert table.nitrogen.target_leaf_nitrogen == pytest.approx(1.5)
    assert table.leaf_physiology.vcmax25 == pytest.approx(100.0)
    table.carbohydrates.seed_reserve = 0.05
    assert table.carbohydrates.seed_reserve == pytest.approx(0.05)


def test_a_season_fertilises_at_plant_ages_and_checks_its_fields():
    ctx = plantarch.Context()
    arch = plantarch.PlantArchitecture(ctx)
    arch.loadPlantModelFromLibrary("bean")
    plants = arch.buildPlantCanopyFromLibrary(plantarch.vec3(0, 0, 0), plantarch.vec2(0.3, 0.3),
                                              (2, 1), 20.0)
    season = plantarch.PhysiologySeason()
    season.carbon = True
    season.nitrogen = True
    season.location = (38.54, -121.74)
    season.start = plantarch.UTCTime("2026-06-01")
    season.lightEvery = 6
    season.fertilise = [plantarch.Fertilisation(21, 0.5)]
    plantarch.checkPhysiologySeason(season)
    records = plantarch.growPhysiologySeason(arch, plants, season, 2)
    np.testing.assert_array_equal(records["age"], [21.0, 21.0, 22.0, 22.0])
    assert list(records["plant"][:2]) == list(plants)
    # The fertiliser came on the second day (the plants 21 days old at its start).
    assert (records["nitrogen_available"][2:] > records["nitrogen_available"][:2] + 0.3).all()
    assert arch.hasCarbohydrateModel(plants[0]) and arch.hasNitrogenModel(plants[1])
    bad = plantarch.PhysiologySeason()
    bad.location = (38.54, -121.74)
    bad.start = plantarch.UTCTime("2026-06-01")
    with pytest.raises(plantarch.Error, match="carbon or nitrogen"):
        plantarch.checkPhysiologySeason(bad)
    bad.carbon = True
    bad.fertilise = [plantarch.Fertilisation(3, 1.0)]
    with pytest.raises(plantarch.Error, match="needs the nitrogen model"):
        plantarch.growPhysiologySeason(arch, plants, bad, 1)
    bad.fertilise = []
    bad.lightEvery = 0
    with pytest.raises(plantarch.Error, match="1 to 24"):
        plantarch.checkPhysiologySeason(bad)
