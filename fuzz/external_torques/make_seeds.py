#!/usr/bin/env python3
"""Writes the seeds of the external-torque target: each scene (the first bytes pick the whole Panda
or its arm) with all-zero bytes (accepted default-like settings, then samples at ordinary values),
all-0xff bytes (special values everywhere) and deterministic pseudo-random bytes of a few lengths.
FuzzedDataProvider reads integers and choices from the end, values and strings from the front.
"""
import os
import random

here = os.path.join(os.path.dirname(os.path.abspath(__file__)), "seeds")
os.makedirs(here, exist_ok=True)
rng = random.Random(20261207)
for flavour, body in (("zeros", bytes(512)), ("ones", b"\xff" * 512)):
    with open(os.path.join(here, flavour), "wb") as f:
        f.write(body)
for length in (64, 256, 1024, 4096):
    for k in range(2):
        with open(os.path.join(here, f"random_{length}_{k}"), "wb") as f:
            f.write(bytes(rng.randrange(256) for _ in range(length)))
