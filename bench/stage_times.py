#!/usr/bin/env python3
"""Stage times of whole `rayview render` processes: exec to main ("start"), load, build, thread pool, render,
PNG (encode and write), exit; with glibc's defaults and with the launcher's malloc settings, alternating
(docs/PERFORMANCE.md, "Page faults and start-up").

The times come from timestamps inside the process, which only a build with bench/stage_stamps.patch prints, so
this script builds one in a worktree of HEAD (build/stages) first:

    bench/stage_times.py [--runs 9] [--threads 2] [--variant NAME=TUNABLES]... [SCENE...]
                                                       (default: the seven scenes of issue 8)

--variant adds a row per scene run with GLIBC_TUNABLES=TUNABLES (e.g. the launcher's without top_pad).

Each process gets the parent's CLOCK_MONOTONIC start in STAGE_T0_NS; medians of --runs per stage.
"""
import argparse
import collections
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
STAGES = ["main", "loaded", "built", "pool", "rendered", "written"]
COLUMNS = ["start", "load", "build", "pool", "render", "PNG", "exit", "whole"]


def stamped_build():
    tree = os.path.join(ROOT, "build", "stages")
    if not os.path.isdir(tree):
        subprocess.run(["git", "-C", ROOT, "worktree", "add", "-f", "--detach", tree, "HEAD"], check=True,
                       stdout=subprocess.DEVNULL)
        subprocess.run(["git", "-C", tree, "apply", os.path.join(ROOT, "bench", "stage_stamps.patch")], check=True)
        subprocess.run(["cmake", "--preset", "release", "-DRAYVIEW_BUILD_TESTS=OFF", "-DRAYVIEW_BUILD_BENCH=OFF",
                        "-DRAYVIEW_BUILD_VIEWER=OFF", f"-DRAYVIEW_SHARED_DIR={SHARED}"], cwd=tree, check=True,
                       stdout=subprocess.DEVNULL)
    subprocess.run(["cmake", "--build", "--preset", "release", "--target", "rayview"], cwd=tree, check=True,
                   stdout=subprocess.DEVNULL)
    return os.path.join(tree, "build", "release", "app")


def run(cli, scene, threads, out, tunables):
    env = dict(os.environ)
    env.pop("GLIBC_TUNABLES", None)
    if tunables:
        env["GLIBC_TUNABLES"] = tunables
    t0 = time.monotonic_ns()
    env["STAGE_T0_NS"] = str(t0)
    p = subprocess.run([cli, "render", scene, "-o", out, "--threads", str(threads), "--quiet"], env=env,
                       capture_output=True, text=True, check=True)
    whole = (time.monotonic_ns() - t0) / 1e6
    at = {}
    for line in p.stderr.splitlines():
        if line.startswith("STAMP "):
            _, stage, ms = line.split()
            at[stage] = float(ms)
    marks = [0.0] + [at[s] for s in STAGES] + [whole]
    return [b - a for a, b in zip(marks, marks[1:])] + [whole]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--runs", type=int, default=9)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--variant", action="append", default=[], metavar="NAME=TUNABLES")
    p.add_argument("scenes", nargs="*")
    a = p.parse_args()
    app = stamped_build()
    version = subprocess.run([os.path.join(app, "rayview"), "--version"], capture_output=True, text=True).stdout
    tunables = version.split("GLIBC_TUNABLES=")[-1].strip() if "GLIBC_TUNABLES=" in version else ""
    cli = os.path.join(app, "rayview-cli")
    print("| scene | settings | " + " | ".join(COLUMNS) + " |\n|---|---|" + "---:|" * len(COLUMNS))
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "image.png")
        for scene in a.scenes or SEVEN:
            variants = [("glibc defaults", ""), ("launcher's", tunables)] + [tuple(v.split("=", 1)) for v in a.variant]
            times = {name: collections.defaultdict(list) for name, _ in variants}
            for _ in range(a.runs):
                for name, value in variants:
                    for column, ms in zip(COLUMNS, run(cli, scene, a.threads, out, value)):
                        times[name][column].append(ms)
            for name, by in times.items():
                cells = " | ".join(f"{statistics.median(by[c]):.1f}" for c in COLUMNS)
                print(f"| {os.path.splitext(os.path.basename(scene))[0]} | {name} | {cells} |", flush=True)


if __name__ == "__main__":
    main()
