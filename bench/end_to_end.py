#!/usr/bin/env python3
"""Whole-process wall time of `rayview render` (load, build, render, writing the PNG) for two builds side by
side in one run: the median of RUNS runs at 2 threads, old and new alternating so that a change of machine
load hits both alike. Prints a Markdown table with the ratio old/new.

    bench/end_to_end.py [--runs 5] [--threads 2] [--stage load|build|render|write] OLD_RAYVIEW NEW_RAYVIEW [SCENE...]

--stage compares one stage instead, as each process's summary reports it ("time  load X ms, BVH build Y ms,
render Z ms, write W ms"), from the same alternating runs.

Default scenes: the seven of bench_scenes.py. docs/PERFORMANCE.md records runs against 7f2ad53."""
import argparse
import re
import statistics
import subprocess
import tempfile
import time

from bench_scenes import SEVEN, name

TIME_LINE = re.compile(r"time\s+load ([\d.]+) ms, BVH build ([\d.]+) ms, render ([\d.]+) ms, write ([\d.]+) ms")
STAGES = {"load": 1, "build": 2, "render": 3, "write": 4}


def measure(rayview, scene, out, threads, stage):
    start = time.perf_counter()
    p = subprocess.run([rayview, "render", scene, "-o", out, "--threads", str(threads)] + ([] if stage else ["--quiet"]),
                       check=True, capture_output=True, text=True)
    wall = (time.perf_counter() - start) * 1000.0
    return float(TIME_LINE.search(p.stdout).group(STAGES[stage])) if stage else wall


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--runs", type=int, default=5)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--stage", choices=sorted(STAGES))
    p.add_argument("old")
    p.add_argument("new")
    p.add_argument("scenes", nargs="*")
    a = p.parse_args()
    what = f"{a.stage} ms" if a.stage else "ms"
    ratios = []
    print(f"| scene | old {what} | new {what} | old / new |\n|---|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as d:
        out = f"{d}/image.png"
        for scene in a.scenes or SEVEN:
            old, new = [], []
            for _ in range(a.runs):
                old.append(measure(a.old, scene, out, a.threads, a.stage))
                new.append(measure(a.new, scene, out, a.threads, a.stage))
            o, n = statistics.median(old), statistics.median(new)
            ratios.append(o / n)
            print(f"| {name(scene)} | {o:.1f} | {n:.1f} | {o / n:.2f} |", flush=True)
    print(f"\nmedian old/new {statistics.median(ratios):.2f}, lowest {min(ratios):.2f}")


if __name__ == "__main__":
    main()
