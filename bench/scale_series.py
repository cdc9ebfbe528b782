#!/usr/bin/env python3
"""Scale series (how time and memory grow with the scene): load, build and render time and peak memory of
`rayview render` on generated sphere, heightfield and random-soup scenes of 1e3..1e7 triangles at 1920x1080.

Writes the scenes (once) to --work, runs `rayview render SCENE -o out.png --threads T` for each, reads the
summary's times and its peak resident memory (bench/peak_rss: ru_maxrss from a small parent) and, from the
summary's memory line, the stage that reached it, prints a Markdown table,
with each scene's peak over the fixed cost of any render at that resolution per triangle (a 2-triangle scene's
peak after the stage that set the scene's: the libraries and the image, and in the write stb's filtered copy),
writes RESULTS.csv and the log-log plot, and with --breakdown runs `scale_series breakdown` on the scenes
of at least 1e5 triangles. The 1e7 scenes take minutes and ~2 GB of XML each: scripts only, never CI.

    bench/scale_series.py --build build/release [--work build/scale] [--sizes 1e3,1e4,1e5,1e6,1e7]
                          [--kinds sphere,heightfield,soup] [--threads 2] [--breakdown] [--plot docs/images/scale.png]
"""
import argparse
import os
import re
import subprocess
import sys

TIME_LINE = re.compile(r"time\s+load ([\d.]+) ms, BVH build ([\d.]+) ms, render ([\d.]+) ms")
# The summary's own memory line: the peak as it stood after each stage.
MEMORY_LINE = re.compile(r"peak after load ([\d.]+), BVH build ([\d.]+), render ([\d.]+), write ([\d.]+) MiB")
STAGES = ("load", "build", "render", "write")


def stage_peaks(stdout):
    """The peak after each stage in bytes, from the summary's memory line (None without one)."""
    m = MEMORY_LINE.search(stdout)
    return [float(v) * 2**20 for v in m.groups()] if m else None


def peak_stage(peaks):
    """The index of the first stage after which the process's peak stood within 1 % of its final value (None without
    the memory line): a stage that adds only its last few hundred KiB does not count as setting the peak."""
    if not peaks:
        return None
    return next(i for i, peak in enumerate(peaks) if peak >= 0.99 * peaks[-1])


def measure(peak_rss, rayview, scene, threads, out_png):
    # bench/peak_rss runs the render and reports its peak resident memory: a child forked from this Python
    # process would carry the interpreter's ~10 MB as its peak (Linux keeps ru_maxrss across exec).
    result = subprocess.run([peak_rss, rayview, "render", scene, "-o", out_png, "--threads", str(threads)],
                            capture_output=True, text=True)
    peak = re.search(r"peak_rss_kb (\d+)", result.stderr)
    times = TIME_LINE.search(result.stdout)
    if result.returncode != 0 or not times or not peak:
        raise RuntimeError(f"{scene}: rayview failed: {result.stderr.strip()[-300:]}")
    return (float(times.group(1)), float(times.group(2)), float(times.group(3)), int(peak.group(1)) * 1024,
            stage_peaks(result.stdout))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default="build/release")
    parser.add_argument("--work", default="build/scale")
    parser.add_argument("--sizes", default="1e3,1e4,1e5,1e6,1e7")
    parser.add_argument("--kinds", default="sphere,heightfield,soup")
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--breakdown", action="store_true")
    parser.add_argument("--plot", default=None, help="PNG to write (default: WORK/scale.png)")
    args = parser.parse_args()

    rayview = os.path.join(args.build, "app", "rayview")
    tool = os.path.join(args.build, "bench", "scale_series")
    peak_rss = os.path.join(args.build, "bench", "peak_rss")
    os.makedirs(args.work, exist_ok=True)
    sizes = [int(float(s)) for s in args.sizes.split(",")]
    kinds = args.kinds.split(",")
    csv_path = os.path.join(args.work, "results.csv")
    rows = []
    # The fixed cost: what a render at 1920x1080 holds with (almost) no geometry, stage by stage. A scene's peak over
    # it is taken at the stage that set the scene's peak (the write holds stb's filtered copy of the image, the
    # render does not), from the two summaries' memory lines.
    fixed_scene = os.path.join(args.work, "fixed_2.xml")
    if not os.path.exists(fixed_scene):
        subprocess.run([tool, "write", "heightfield", "2", fixed_scene], check=True, stdout=subprocess.DEVNULL)
    fixed = measure(peak_rss, rayview, fixed_scene, args.threads, os.path.join(args.work, "out.png"))[4]
    if fixed:
        print("fixed cost: a 2-triangle scene at 1920x1080 peaks at " +
              ", ".join(f"{p / 2**20:.1f} MiB after the {s}" for s, p in zip(STAGES, fixed)) + "\n")
    print("| scene | triangles | XML MB | load ms | build ms | render ms | peak RSS MB | B/triangle | peak in | "
          "B/triangle over the fixed cost there |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---|---:|")
    for kind in kinds:
        for n in sizes:
            scene = os.path.join(args.work, f"{kind}_{n}.xml")
            if not os.path.exists(scene):
                subprocess.run([tool, "write", kind, str(n), scene], check=True, stdout=subprocess.DEVNULL)
            load, build, render, peak, peaks = measure(peak_rss, rayview, scene, args.threads,
                                                       os.path.join(args.work, "out.png"))
            stage = peak_stage(peaks)
            triangles = n
            xml_mb = os.path.getsize(scene) / 1e6
            rows.append((kind, triangles, load, build, render, peak))
            over = f"{(peaks[-1] - fixed[stage]) / triangles:.0f}" if fixed and stage is not None else "?"
            print(f"| {kind} | {triangles:.0e} | {xml_mb:.1f} | {load:.0f} | {build:.0f} | {render:.0f} | "
                  f"{peak / 1e6:.0f} | {peak / triangles:.0f} | {STAGES[stage] if stage is not None else '?'} | "
                  f"{over} |")
            sys.stdout.flush()
            with open(csv_path, "w") as f:
                f.write("kind,triangles,load_ms,build_ms,render_ms,peak_bytes\n")
                for r in rows:
                    f.write(",".join(str(v) for v in r) + "\n")
    plot = args.plot or os.path.join(args.work, "scale.png")
    subprocess.run([tool, "plot", csv_path, plot], check=True)
    if args.breakdown:
        for kind in kinds:
            for n in sizes:
                if n < 100000:
                    continue
                print()
                sys.stdout.flush()
                subprocess.run([tool, "breakdown", os.path.join(args.work, f"{kind}_{n}.xml"), str(args.threads)],
                               check=True)


if __name__ == "__main__":
    main()
