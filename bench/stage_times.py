#!/usr/bin/env python3
"""Stage times of whole `rayview render` processes, alternating between settings rows (docs/PERFORMANCE.md,
"How to measure").

    bench/stage_times.py [--build build/release] [--runs 9] [--threads 2] [--variant NAME=ENV]... [--spread]
                         [SCENE...]
                                                       (default: the seven of bench_scenes.py)

Runs `rayview render` once per settings row: the first with the environment as it is, each --variant with one
more environment variable (e.g. --variant "mimalloc=LD_PRELOAD=libmimalloc.so.2" to try an allocator without
building one in). The stages are what the summary prints: start-up (main() to the first ray, less load and build:
the thread pool, the tracer's set-up),
load, build, render, write (encoding and writing the PNG); "Mrays/s" is the summary's rays traced per second of
render; "rest" is the whole process less those (its exit
and the summary's printing); "faults" counts the process's page faults (minor and major; ~13 us each on
this project's machines, bench/page_fault_bench). Medians of --runs per stage; --spread adds the quartiles.
"""
import argparse
import collections
import os
import re
import resource
import statistics
import subprocess
import tempfile
import time

from bench_scenes import ROOT, SEVEN, name

SUMMARY = re.compile(r"time\s+load ([\d.]+) ms, BVH build ([\d.]+) ms, render ([\d.]+) ms, write ([\d.]+) ms\n"
                     r"start-up\s+([\d.]+) ms: main\(\)")
RATE = re.compile(r"total \d+, ([\d.]+) Mrays/s")
COLUMNS = ["start-up", "load", "build", "render", "write", "rest", "whole", "faults", "Mrays/s"]


def run(cli, scene, threads, out, variable):
    env = dict(os.environ)
    if variable:
        key, value = variable.split("=", 1)
        env[key] = value
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.monotonic_ns()
    p = subprocess.run([cli, "render", scene, "-o", out, "--threads", str(threads)], env=env, capture_output=True,
                       text=True, check=True)
    whole = (time.monotonic_ns() - t0) / 1e6
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    faults = (after.ru_minflt - before.ru_minflt) + (after.ru_majflt - before.ru_majflt)
    load, build, render, write, startup = (float(v) for v in SUMMARY.search(p.stdout).groups())
    rate = float(RATE.search(p.stdout).group(1))  # the summary's rays (camera, shadow, reflection) over render
    return [startup, load, build, render, write, whole - (startup + load + build + render + write), whole, faults,
            rate]


def cell(values, form, spread):
    text = form.format(statistics.median(values))
    if spread and len(values) >= 2:
        q1, _, q3 = statistics.quantiles(values, n=4)
        text += f" ({form.format(q1)}-{form.format(q3)})"
    return text


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--build", default=os.path.join(ROOT, "build", "release"))
    p.add_argument("--runs", type=int, default=9)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--variant", action="append", default=[], metavar="NAME=VARIABLE=VALUE")
    p.add_argument("--spread", action="store_true", help="each cell also gives the quartiles: median (q1-q3)")
    p.add_argument("scenes", nargs="*")
    a = p.parse_args()
    app = os.path.join(a.build, "app")
    cli = os.path.join(app, "rayview")
    variants = [("as built", "")] + [tuple(v.split("=", 1)) for v in a.variant]
    print("| scene | settings | " + " | ".join(COLUMNS) + " |\n|---|---|" + "---:|" * len(COLUMNS))
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "image.png")
        for scene in a.scenes or SEVEN:
            times = {n: collections.defaultdict(list) for n, _ in variants}
            for _ in range(a.runs):
                for n, value in variants:
                    for column, ms in zip(COLUMNS, run(cli, scene, a.threads, out, value)):
                        times[n][column].append(ms)
            for n, by in times.items():
                cells = " | ".join(cell(by[c], "{:.0f}" if c == "faults" else "{:.2f}" if c == "Mrays/s" else "{:.1f}", a.spread) for c in COLUMNS)
                print(f"| {name(scene)} | {n} | {cells} |", flush=True)


if __name__ == "__main__":
    main()
