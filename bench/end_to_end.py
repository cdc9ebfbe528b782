#!/usr/bin/env python3
"""Whole-process wall time of `rayview render` (load, build, render, writing the PNG) for two builds side by
side in one run: the median of RUNS runs at 2 threads, old and new alternating so that a change of machine
load hits both alike. Prints a Markdown table with the ratio old/new.

    bench/end_to_end.py OLD_RAYVIEW NEW_RAYVIEW [--runs 5] [SCENE...]

Default scenes: the seven of issue 8 (bunny, car, killeroo_2020, dragon_lowres, monkey of the conformance set;
grid_large and mirror_scene of the peer scenes). docs/PERFORMANCE.md records a run against 7f2ad53."""
import argparse
import os
import statistics
import subprocess
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHARED = os.environ.get("RAYVIEW_SHARED_DIR", os.path.join(ROOT, "..", "shared"))
CONFORMANCE = os.path.join(SHARED, "conformance", "ceng477")
PEER = os.path.join(SHARED, "peer-scenes", "mertugr__mesh-trace", "scenes")
SEVEN = [os.path.join(CONFORMANCE, n + ".xml") for n in ("bunny", "car", "killeroo_2020", "dragon_lowres", "monkey")] + \
        [os.path.join(PEER, n + ".xml") for n in ("grid_large", "mirror_scene")]


def wall(rayview, scene, out):
    start = time.perf_counter()
    subprocess.run([rayview, "render", scene, "-o", out, "--threads", "2", "--quiet"], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return (time.perf_counter() - start) * 1000.0


def main():
    p = argparse.ArgumentParser()
    p.add_argument("old")
    p.add_argument("new")
    p.add_argument("--runs", type=int, default=5)
    p.add_argument("scenes", nargs="*")
    a = p.parse_args()
    ratios = []
    print("| scene | old ms | new ms | old / new |\n|---|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "image.png")
        for scene in a.scenes or SEVEN:
            old, new = [], []
            for _ in range(a.runs):
                old.append(wall(a.old, scene, out))
                new.append(wall(a.new, scene, out))
            o, n = statistics.median(old), statistics.median(new)
            ratios.append(o / n)
            print(f"| {os.path.splitext(os.path.basename(scene))[0]} | {o:.0f} | {n:.0f} | {o / n:.2f} |", flush=True)
    print(f"\nmedian old/new {statistics.median(ratios):.2f}, lowest {min(ratios):.2f}")


if __name__ == "__main__":
    main()
