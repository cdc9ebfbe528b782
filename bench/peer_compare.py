#!/usr/bin/env python3
"""Whole-process wall time of `rayview render` against another renderer of the same scene format (a peer), run
by run alternating (rayview, peer, rayview, ...) so that a change of machine load hits both alike: the median of
RUNS runs each, and the ratio peer/rayview per scene. Prints a Markdown table and the machine's load averages.

    bench/peer_compare.py [--runs 5] [--threads 2] --peer-cmd TEMPLATE [--peer-cwd DIR] RAYVIEW [SCENE...]

TEMPLATE is the peer's command line, split like a shell's but run without one; {scene} is the scene's absolute
path, {out} an image path in a fresh directory, {threads} the thread count, {name} the scene's name (bunny).
The peer runs in that fresh directory, one per run, so that a peer writing a fixed file name (output.ppm) never
finds the last run's image; --peer-cwd runs it in DIR instead. The peer's output is discarded; it must exit 0.
A peer that writes its image to stdout: wrap it, --peer-cmd 'sh -c "peer {scene} > {out}"'.

Default scenes: the seven of bench_scenes.py. The fastest peer found (the only one of the eight public ones with a
BVH) is mertugr/mesh-trace at 7b1bc40; built with its own Makefile (g++ -O2, threads as its third argument):

    git clone https://github.com/mertugr/mesh-trace /tmp/peers/mesh-trace
    git -C /tmp/peers/mesh-trace checkout 7b1bc40
    make -C /tmp/peers/mesh-trace -j 2
    bench/peer_compare.py --runs 7 --peer-cmd '/tmp/peers/mesh-trace/raytracer {scene} {out} {threads}' \
        build/release/app/rayview"""
import argparse
import os
import shlex
import statistics
import subprocess
import tempfile
import time

from bench_scenes import SEVEN, name


def wall_ms(cmd, cwd):
    start = time.perf_counter()
    subprocess.run(cmd, cwd=cwd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return (time.perf_counter() - start) * 1000.0


def rayview_ms(rayview, scene, threads):
    with tempfile.TemporaryDirectory() as d:
        cmd = [rayview, "render", os.path.abspath(scene), "-o", f"{d}/image.png", "--threads", str(threads), "--quiet"]
        return wall_ms(cmd, d)


def peer_ms(template, scene, threads, cwd):
    with tempfile.TemporaryDirectory() as d:
        fields = {"scene": os.path.abspath(scene), "out": f"{d}/image.png", "threads": threads, "name": name(scene)}
        return wall_ms([arg.format(**fields) for arg in shlex.split(template)], cwd or d)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--runs", type=int, default=5)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--peer-cmd", required=True)
    p.add_argument("--peer-cwd")
    p.add_argument("rayview")
    p.add_argument("scenes", nargs="*")
    a = p.parse_args()
    rayview = os.path.abspath(a.rayview)
    load = "%.2f %.2f %.2f" % os.getloadavg()
    ratios = []
    print("| scene | rayview ms | peer ms | peer / rayview |\n|---|---:|---:|---:|")
    for scene in a.scenes or SEVEN:
        ours, theirs = [], []
        for _ in range(a.runs):
            ours.append(rayview_ms(rayview, scene, a.threads))
            theirs.append(peer_ms(a.peer_cmd, scene, a.threads, a.peer_cwd))
        o, t = statistics.median(ours), statistics.median(theirs)
        ratios.append(t / o)
        print(f"| {name(scene)} | {o:.1f} | {t:.1f} | {t / o:.2f} |", flush=True)
    print(f"\nmedian peer/rayview {statistics.median(ratios):.2f}, lowest {min(ratios):.2f}, highest {max(ratios):.2f}")
    print(f"load averages (1, 5, 15 min) before {load}, after %.2f %.2f %.2f" % os.getloadavg())


if __name__ == "__main__":
    main()
