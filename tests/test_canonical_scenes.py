"""A run's canonical scene is made once between the driver and its planner
(tasks/canonical_scenes.py), whichever of the two asks first."""

from frictiondisk.tasks.canonical_scenes import CanonicalScenes


def counting():
    made = []

    def make():
        made.append(1)
        return {"n": len(made)}

    return made, make


def test_a_scene_made_for_the_job_is_the_one_keyed():
    made, make = counting()
    scenes = CanonicalScenes()
    sent = scenes.for_job("run", make)
    assert scenes.for_key("run", make) is sent
    assert len(made) == 1
    assert scenes.for_key("run", make) == {"n": 2}  # handed over once, then made again


def test_a_scene_the_driver_made_goes_with_the_job():
    made, make = counting()
    scenes = CanonicalScenes()
    keyed = {"driver": True}
    scenes.remember("run", keyed)
    assert scenes.for_job("run", make) is keyed
    assert not made


def test_a_forgotten_scene_is_made_again():
    made, make = counting()
    scenes = CanonicalScenes()
    scenes.remember("a", {"driver": True})
    scenes.for_job("b", make)
    scenes.forget("a")
    scenes.forget("b")
    assert scenes.for_job("a", make) == {"n": 2}
    assert scenes.for_key("b", make) == {"n": 3}
