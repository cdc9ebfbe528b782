#!/usr/bin/env python3
"""Load, BVH build and render time of every conformance and peer scene at 1 and 2 threads.

Runs `rayview render` on each scene and prints a Markdown table (docs/PERFORMANCE.md, "How to measure").
Each cell is the median of --repeat runs. Usage:
    bench/scene_timings.py --rayview build/release/app/rayview [--shared ../shared] [--repeat 3]
"""
import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile

TIME_LINE = re.compile(r"time\s+load ([\d.]+) ms, BVH build ([\d.]+) ms, render ([\d.]+) ms")
RAYS_LINE = re.compile(r"rays .* ([\d.]+) Mrays/s")


def scenes(shared):
    conformance = os.path.join(shared, "conformance", "ceng477")
    for name in sorted(os.listdir(conformance)):
        if name.endswith(".xml") and not name.endswith(".ceng477.xml"):
            yield "conformance", name[:-4], os.path.join(conformance, name)
    peers = os.path.join(shared, "peer-scenes")
    for root, _, files in sorted(os.walk(peers)):
        for name in sorted(files):
            if name.endswith(".xml"):
                path = os.path.join(root, name)
                yield "peer", os.path.relpath(path, peers), path


def measure(rayview, scene, threads, repeat, out):
    samples = []
    for _ in range(repeat):
        result = subprocess.run([rayview, "render", scene, "-o", out, "--threads", str(threads)],
                                capture_output=True, text=True)
        if result.returncode != 0:
            return None, result.stderr.strip().splitlines()[-1] if result.stderr.strip() else "failed"
        m = TIME_LINE.search(result.stdout)
        r = RAYS_LINE.search(result.stdout)
        samples.append((float(m.group(1)), float(m.group(2)), float(m.group(3)), float(r.group(1))))
    return tuple(statistics.median(s[i] for s in samples) for i in range(4)), None


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--rayview", default="build/release/app/rayview")
    parser.add_argument("--shared", default=os.path.join(os.path.dirname(__file__), "..", "..", "shared"))
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()

    print("| set | scene | load ms | build ms | render ms, 1 thread | render ms, 2 threads | speed-up | Mrays/s, 2 threads |")
    print("|---|---|---:|---:|---:|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out.png")
        for kind, name, path in scenes(args.shared):
            one, error = measure(args.rayview, path, 1, args.repeat, out)
            if one is None:
                print(f"| {kind} | {name} | refused: {error.split('error: ', 1)[-1][:70]} | | | | | |")
                sys.stdout.flush()
                continue
            two, _ = measure(args.rayview, path, 2, args.repeat, out)
            print(f"| {kind} | {name} | {one[0]:.1f} | {one[1]:.1f} | {one[2]:.1f} | {two[2]:.1f} | "
                  f"{one[2] / two[2]:.2f} | {two[3]:.1f} |")
            sys.stdout.flush()


if __name__ == "__main__":
    main()
