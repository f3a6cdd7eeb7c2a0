#!/usr/bin/env python3
"""Compare two runs of family.py (two builds of the library, or two settings) scene by scene.

usage: family_compare.py BEFORE/family.json AFTER/family.json [--preset P] [--show N]

For each preset both runs measured (or only --preset): the mean RMSE before and after, how many scenes got better
and worse by more than the reference's resolution (family.REFERENCE_RESOLUTION), how many are worse than their
1-spp input before and after, and the N scenes that changed most each way. Both runs must have measured the same
seeds against the same references (family.py --references shared): a scene whose input RMSE differs between the
two runs is reported and the comparison stops, since its numbers are not comparable.
"""
import argparse
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from family import REFERENCE_RESOLUTION  # noqa: E402


def load(path):
    return {s["seed"]: s for s in json.loads(Path(path).read_text())}


def compare(before, after, preset, show):
    seeds = sorted(set(before) & set(after))
    if not seeds:
        sys.exit("the two runs share no seed")
    if len(seeds) < max(len(before), len(after)):
        print(f"comparing the {len(seeds)} seeds both runs measured ({len(before)} and {len(after)} in each)")
    pairs = [(seed, before[seed]["results"][preset], after[seed]["results"][preset]) for seed in seeds]
    moved = [seed for seed, b, a in pairs if abs(b["noisy"] - a["noisy"]) > 1e-6]
    if moved:
        sys.exit(f"{preset}: the input differs on seeds {moved}: not the same scenes or references")
    n = len(pairs)

    def mean(k):
        return sum(r[k]["denoised"] for r in pairs) / n

    def worse_than_input(k):
        return sum(r[k]["denoised"] > r[k]["noisy"] + REFERENCE_RESOLUTION for r in pairs)

    delta = sorted(((a["denoised"] - b["denoised"], seed, b, a) for seed, b, a in pairs), key=lambda t: t[0])
    better = [t for t in delta if t[0] < -REFERENCE_RESOLUTION]
    worse = [t for t in delta if t[0] > REFERENCE_RESOLUTION]
    print(f"{preset} ({n} scenes): mean RMSE {mean(1):.5f} -> {mean(2):.5f}; {len(better)} better, {len(worse)} worse "
          f"(by more than {REFERENCE_RESOLUTION}); worse than the input {worse_than_input(1)} -> {worse_than_input(2)}")
    for label, rows in (("better", better[:show]), ("worse", worse[::-1][:show])):
        for _, seed, b, a in rows:
            print(f"  {label} {seed}: {b['denoised']:.4f} -> {a['denoised']:.4f} (input {b['noisy']:.4f})")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("before")
    ap.add_argument("after")
    ap.add_argument("--preset")
    ap.add_argument("--show", type=int, default=5)
    a = ap.parse_args()
    before, after = load(a.before), load(a.after)
    measured = [next(iter(runs.values()))["results"] for runs in (before, after)]
    presets = [a.preset] if a.preset else [p for p in measured[0] if p in measured[1]]
    if not presets:
        sys.exit("no preset measured by both runs")
    for preset in presets:
        compare(before, after, preset, a.show)


if __name__ == "__main__":
    main()
