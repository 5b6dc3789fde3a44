#!/usr/bin/env python3
"""Writes the seed inputs of fuzz_scene_reduction into seeds/ (run once; the seeds are committed).
Each seed spells out, in the byte format sd_fuzz::Reader reads (fuzz_common.hpp) and the order
fuzz_scene_reduction.cpp reads it: robot, base, payloads, scene (joints to keep / root and tips,
locked positions), coupling of mimic joints, and the seed of the states."""
import pathlib
import struct

ROBOTS = ["double_pendulum", "panda", "ur5", "solo12", "talos", "mobile_manipulator"]
GENERATED = len(ROBOTS)
SPECIAL = {0.0: 0, 1.0: 1, -1.0: 2, 0.5: 3, 1e-300: 4, 1e300: 5, -1e300: 6, "nan": 7, "inf": 8, "-inf": 9,
           "max": 10, "denorm": 11, 1e6: 12, -1e6: 13, "pi": 14, 1e-9: 15}


def number(x):
    if x in SPECIAL:
        return bytes([SPECIAL[x]])
    if isinstance(x, float) and abs(x) < 32.0 and round(x * 1000) == x * 1000:
        return bytes([100]) + struct.pack("<h", int(round(x * 1000)))
    return bytes([150]) + struct.pack("<d", x)


def name(index):  # index into the model's joint or frame names
    return bytes([index % 224, index // 224])


def unknown(text):
    return bytes([250, len(text)]) + text.encode()


def payload(frame, mass, com, diagonal):
    out = number(mass) + b"".join(number(c) for c in com) + bytes([1])
    return out + b"".join(number(d) for d in diagonal) + frame


def seed(robot, floating, payloads=(), mode=0, locked=(), kept=(), root=None, tips=(), coupled=0, generated=b""):
    out = bytes([robot, floating]) + generated + bytes([len(payloads)]) + b"".join(payloads) + bytes([mode])
    if mode:
        out += bytes([len(locked)]) + b"".join(n + number(x) for n, x in locked)
        if mode == 1:
            out += bytes([len(kept)]) + b"".join(kept)
        else:
            out += root + bytes([len(tips)]) + b"".join(tips)
        out += struct.pack("<H", 7)
    return out + bytes([coupled]) + struct.pack("<HH", 1, 2)


def generated_robot(links):
    """links: (mass index, type index, parent, axis index, mimic) per link after the first;
    mimic = None or (master position among the movable joints so far, multiplier + 2)."""
    out = bytes([len(links)])
    movable = 0
    for mass, kind, parent, axis, mimic in links:
        out += bytes([mass, kind, parent, axis])
        if kind != 3:
            if movable:  # the mimic choice is read only when there is a joint to mimic
                out += bytes([1]) if mimic is None else bytes([0, mimic[0], mimic[1]])
            movable += 1
    return out


seeds = {}
for r, robot in enumerate(ROBOTS):
    for floating in (0, 1):
        base = f"{robot}_{'floating' if floating else 'fixed'}"
        seeds[base] = seed(r, floating)
        seeds[base + "_coupled"] = seed(r, floating, coupled=1)
        seeds[base + "_keep_first_three"] = seed(r, floating, mode=1, kept=[name(k) for k in range(3)],
                                                 locked=[(name(5), 0.25), (name(6), -1.5)])
        seeds[base + "_root_tip"] = seed(r, floating, mode=2, root=name(0), tips=[name(7), name(11)], coupled=1)
        seeds[base + "_payload"] = seed(r, floating, payloads=[payload(name(3), 2.0, (0.0, 0.0, 0.1),
                                                                       (0.004, 0.004, 0.002))])
seeds["panda_lock_nan"] = seed(1, 0, mode=1, kept=[name(0)], locked=[(name(2), "nan")])
seeds["panda_lock_inf"] = seed(1, 0, mode=1, kept=[name(0)], locked=[(name(2), "inf")])
seeds["panda_lock_huge"] = seed(1, 0, mode=1, kept=[name(0)], locked=[(name(2), 1e300)])
seeds["panda_keep_unknown"] = seed(1, 0, mode=1, kept=[name(0), unknown("no_such_joint")])
seeds["panda_lock_unknown"] = seed(1, 0, mode=1, kept=[name(0)], locked=[(unknown("ghost"), 0.5)])
seeds["panda_keep_and_lock"] = seed(1, 0, mode=1, kept=[name(1)], locked=[(name(1), 0.5)])
seeds["talos_unknown_tip"] = seed(4, 1, mode=2, root=name(3), tips=[unknown("no_such_link")])
seeds["talos_no_tips"] = seed(4, 1, mode=2, root=name(3), tips=[])
seeds["talos_lock_root_joint"] = seed(4, 1, mode=1, kept=[name(4)], locked=[(name(0), 1.0)])
seeds["panda_payload_unknown_frame"] = seed(1, 0, payloads=[payload(unknown("ghost_frame"), 1.0, (0, 0, 0), (1, 1, 1))])
seeds["panda_payload_nan_mass"] = seed(1, 0, payloads=[payload(name(4), "nan", (0, 0, 0), (1, 1, 1))])
seeds["panda_payload_huge_mass"] = seed(1, 0, payloads=[payload(name(4), 1e300, (0, 0, 0), (1, 1, 1))])
seeds["panda_payload_max_mass"] = seed(1, 0, payloads=[payload(name(4), "max", (0, 0, 0), (1, 1, 1))])
seeds["panda_payload_triangle"] = seed(1, 0, payloads=[payload(name(4), 1.0, (0, 0, 0), (1, 1, 3))])
seeds["panda_payload_inf_com"] = seed(1, 0, payloads=[payload(name(4), 1.0, ("inf", 0, 0), (1, 1, 1))])
seeds["mobile_coupled_keep_fingers"] = seed(5, 0, mode=1, kept=[name(k) for k in range(18, 22)], coupled=1)
chain = generated_robot([(2, 0, 0, 2, None), (2, 0, 1, 1, (0, 0)), (0, 2, 2, 4, (1, 4)), (1, 3, 1, 0, None)])
seeds["generated_mimic_chain"] = seed(GENERATED, 0, generated=chain, coupled=1)
seeds["generated_mimic_chain_reduced"] = seed(GENERATED, 1, generated=chain, mode=1, kept=[name(0), name(1)], coupled=1)
massless = generated_robot([(2, 0, 0, 2, None), (0, 2, 1, 5, None)])
seeds["generated_massless_leaf"] = seed(GENERATED, 0, generated=massless)

out = pathlib.Path(__file__).resolve().parent / "seeds"
out.mkdir(exist_ok=True)
for key, data in seeds.items():
    (out / key).write_bytes(data)
print(f"{len(seeds)} seeds in {out}")
