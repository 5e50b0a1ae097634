#!/usr/bin/env python3
"""Replays one log through two builds of ugv-terrain and compares their maps byte for byte.

    compare_replay.py OLD_UGV_TERRAIN NEW_UGV_TERRAIN LOG [--config TOML]

terrain_map_t may have gained fields at its end (max_z, min_z after count, age_s after
min_z): every field the old message has (pose, geometry, mean_z, variance_z, count, ...) must
have the same bytes in the new one; the new arrays are only checked for being NaN exactly where
the mean is, min <= mean <= max and age >= 0. Exit 0 when every map matches. Needs nothing but
Python 3.
"""
import argparse
import math
import struct
import subprocess
import sys
import tempfile
from pathlib import Path

SYNC = 0xEDA1DA01
# Bytes before the arrays: fingerprint, utime, seq, pose_t (385), 8 four-byte fields, mode,
# statistics; ncells is the last four of them.
ARRAYS_AT = 8 + 16 + 385 + 32 + 2 + 4


def events(path, channel):
    """(timestamp, data) of each event on channel, in file order (the LCM log format)."""
    with open(path, "rb") as f:
        while True:
            head = f.read(28)
            if len(head) < 28:
                return
            sync, _num, stamp, clen, dlen = struct.unpack(">IqqII", head)
            if sync != SYNC:
                raise ValueError(f"{path}: lost sync")
            name = f.read(clen).decode()
            data = f.read(dlen)
            if name == channel:
                yield stamp, data


def replay(binary, log, out, config):
    args = [binary, "--replay", log, "--out", out]
    if config:
        args[1:1] = ["--config", config]
    subprocess.run(args, check=True, stdout=subprocess.DEVNULL)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("old")
    p.add_argument("new")
    p.add_argument("log")
    p.add_argument("--config")
    a = p.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        old_out, new_out = str(Path(tmp) / "old.lcm"), str(Path(tmp) / "new.lcm")
        replay(a.old, a.log, old_out, a.config)
        replay(a.new, a.log, new_out, a.config)
        old = list(events(old_out, "TERRAIN_MAP"))
        new = list(events(new_out, "TERRAIN_MAP"))
    bad = 0
    known = 0
    tall = 0  # cells whose highest sample is more than 0.1 m above their mean
    if len(old) != len(new):
        print(f"maps: {len(old)} old, {len(new)} new")
        bad += 1
    for k, ((t_old, d_old), (t_new, d_new)) in enumerate(zip(old, new)):
        body = d_old[8:]  # after the 8-byte fingerprint
        if t_old != t_new or d_new[8:8 + len(body)] != body:
            first = next((i for i, (x, y) in enumerate(zip(body, d_new[8:])) if x != y), None)
            print(f"map {k}: differs (first differing byte {first} of {len(body)})")
            bad += 1
            continue
        # The new message's arrays: mean_z, variance_z, count, max_z, min_z, age_s.
        (ncells,) = struct.unpack(">i", d_new[ARRAYS_AT - 4:ARRAYS_AT])
        layer = [struct.unpack(f">{ncells}f", d_new[ARRAYS_AT + 4 * ncells * i:ARRAYS_AT + 4 * ncells * (i + 1)])
                 for i in range(6)]
        for m, hi, lo, age in zip(layer[0], layer[3], layer[4], layer[5]):
            if any(math.isnan(m) != math.isnan(v) for v in (hi, lo, age)) or age < 0:
                bad += 1
            elif not math.isnan(m):
                known += 1
                tall += hi > m + 0.1
                if not lo - 1e-4 <= m <= hi + 1e-4:
                    bad += 1
    print(f"{len(new)} maps, {known} known cells: mean, variance, count and every older field "
          f"{'identical' if bad == 0 else 'NOT identical'}; max/min/age NaN exactly where the mean is, "
          f"min <= mean <= max, age >= 0 ({tall} cells with max more than 0.1 m above the mean)")
    return 0 if bad == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
