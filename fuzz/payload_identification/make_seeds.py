#!/usr/bin/env python3
"""Writes the seeds of the payload-identification target: all-zero bytes (ordinary values),
all-0xff bytes (special values everywhere) and deterministic pseudo-random bytes of a few lengths,
each with a first byte for each service and model. FuzzedDataProvider reads integers and choices
from the end, values and strings from the front.
"""
import os
import random

here = os.path.join(os.path.dirname(os.path.abspath(__file__)), "seeds")
os.makedirs(here, exist_ok=True)
rng = random.Random(20261207)
for first in range(4):  # identify / trajectory × independent / coupled
    for flavour, body in (("zeros", bytes(2048)), ("ones", b"\xff" * 512)):
        with open(os.path.join(here, f"{flavour}_{first}"), "wb") as f:
            f.write(bytes([first]) + body)
    for length in (64, 1024, 8192):
        with open(os.path.join(here, f"random_{length}_{first}"), "wb") as f:
            f.write(bytes([first]) + bytes(rng.randrange(256) for _ in range(length)))
