#!/usr/bin/env python3
"""Writes the seeds of the service-handler target: one input per service and scene.

The first byte selects the scene, (byte >> 3) % 4 (0: the whole Panda, 1: its arm as a reduced
scene, 2: coupled mimic joints, 3: a floating Solo12 on its four feet), and the call, byte % 6 (0: inverse dynamics, 1: forward dynamics,
2: mass matrix, 3: wrench transform, 4: a trajectory's inverse dynamics, 5: a joint_states message). FuzzedDataProvider reads the rest:
integers and choices from the end, values and strings from the front. Each seed comes in three
flavours: all zero bytes (empty arrays, first names), all 0xff bytes (largest lengths and the
unknown-name and special-value branches), and deterministic pseudo-random bytes.
"""
import os
import random

here = os.path.join(os.path.dirname(os.path.abspath(__file__)), "seeds")
os.makedirs(here, exist_ok=True)
services = ["inverse_dynamics", "forward_dynamics", "mass_matrix", "transform_wrench", "inverse_dynamics_trajectory",
            "joint_states"]
scenes = ["panda", "panda_arm", "panda_coupled", "solo12_floating"]
rng = random.Random(20261122)
for scene in range(len(scenes)):
    for service in range(6):
        selector = next(s for s in range(256) if (s >> 3) % len(scenes) == scene and s % 6 == service)
        for flavour, body in (("zeros", bytes(256)), ("ones", b"\xff" * 256),
                              ("random", bytes(rng.randrange(256) for _ in range(512)))):
            name = f"{scenes[scene]}_{services[service]}_{flavour}"
            with open(os.path.join(here, name), "wb") as f:
                f.write(bytes([selector]) + body)
