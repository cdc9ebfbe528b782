#!/usr/bin/env python3
"""The viewer under load, meant for the sanitizer builds (docs/reliability.md). CTest label "viewer".

    stress_test.py CASE --rayview PATH --output DIR [--commands N] [--seed S]

Cases:
  soak     a deterministic (seeded) script of N automation commands (default 10000) in an 800x600 window:
           material, light and depth edits, orbits and dollies, resolutions from 16 to 700 pixels, failed loads
           checked by expect-error, reloads; it ends with wait-final and must exit 0. The resident memory
           (VmRSS, read from /proc while the viewer runs) after the warm-up and at the end must agree within
           RSS_TOLERANCE_MB.
  threads  edits while the other threads work: the file on disk is rewritten again and again (the file watch
           reloads it on the loader task while the script goes on editing and the mouse drags the camera),
           a measure-tradeoff, then a measurement cancelled by a reload and the exit right after. Built with
           -fsanitize=thread this is the viewer's race test: the progressive renderer, the loader task, the
           trade-off task and the UI thread.

Both fail on any sanitizer report on stderr (ASan, UBSan, LSan, TSan), whatever the exit code.
Like viewer_test.py, each case runs itself under `xvfb-run` (skipped, exit 77, when it is not installed).
"""

import argparse
import os
import random
import sys
import threading
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from viewer_harness import (Failure, Viewer, copy_scene, run_case, viewer_window, xdotool)  # noqa: E402

# Resident memory may grow this much between the end of the warm-up and the end of the soak. Under ASan the
# allocator keeps freed blocks in its quarantine (bounded by quarantine_size_mb, set small below) and
# grows its size-class caches, so a small drift is normal; a per-command leak of even 5 KB is not.
RSS_TOLERANCE_MB = 48
# The commands before the first memory sample: caches, fonts, the BVH and every resolution class warmed.
WARMUP_FRACTION = 0.2

SANITIZER_MARKERS = ("ERROR: AddressSanitizer", "ERROR: LeakSanitizer", "runtime error:",
                     "WARNING: ThreadSanitizer", "ERROR: ThreadSanitizer", "SUMMARY: UndefinedBehaviorSanitizer")

MATERIALS = ["floor", "red", "green", "mirror"]


def vm_rss_mb(pid):
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024.0
    raise Failure(f"no VmRSS for process {pid}")


def check_sanitizers(viewer):
    reports = [line for line in viewer.stderr if any(marker in line for marker in SANITIZER_MARKERS)]
    if reports:
        raise Failure("sanitizer report(s):\n  " + "\n  ".join(reports[:10]) + "\n" + viewer.output()[-20000:])


def soak_script(count, seed, scene, broken, work):
    """N commands, the same ones for the same seed. Two `print-state` lines mark where memory is sampled."""
    rng = random.Random(seed)

    def r(low, high, digits=2):
        return f"{rng.uniform(low, high):.{digits}f}"

    def rgb(low, high):
        return f"{r(low, high)} {r(low, high)} {r(low, high)}"

    makers = [
        (12, lambda: [f"set material {rng.choice(MATERIALS)} diffuse {rgb(0, 1)}"]),
        (4, lambda: [f"set material {rng.choice(MATERIALS)} specular {rgb(0, 1)}"]),
        (3, lambda: [f"set material {rng.choice(MATERIALS)} ambient {rgb(0, 1)}"]),
        (3, lambda: [f"set material {rng.choice(MATERIALS)} mirror {rgb(0, 0.9)}"]),
        (3, lambda: [f"set material {rng.choice(MATERIALS)} phong {r(1, 200)}"]),
        (6, lambda: [f"set light sun position {r(-5, 5)} {r(2, 8)} {r(-3, 6)}"]),
        (4, lambda: [f"set light sun intensity {rgb(1000, 9000)}"]),
        (3, lambda: [f"set light strip intensity {rgb(500, 3000)}"]),
        (3, lambda: [f"set light strip vertex1 {r(-4, -2)} {r(3.5, 4.5)} {r(-1.5, -0.5)}"]),
        (5, lambda: [f"set depth {rng.randint(0, 4)}"]),
        (2, lambda: [f"set light-samples {rng.choice([1, 2, 4])}"]),
        (2, lambda: [f"set tri-light {rng.choice(['area', 'directional'])}"]),
        (2, lambda: [f"set ray-start {rng.choice(['offset', 'exclude-hit'])}"]),
        (2, lambda: [f"set background {rgb(0, 255)}"]),
        (2, lambda: [f"set ambient {rgb(0, 60)}"]),
        (1, lambda: [f"set accel {rng.choice(['embree', 'reference'])}"]),
        # Display only: the shown image is mapped again, the render goes on.
        (1, lambda: [f"set exposure {r(-8, 8)}"]),
        (1, lambda: [f"set gamma {r(0.2, 5)}"]),
        (14, lambda: [f"camera orbit {r(-40, 40)} {r(-20, 20)}"]),
        (8, lambda: [f"camera dolly {r(-3, 3)}"]),
        (4, lambda: [f"camera pan {r(-0.2, 0.2)} {r(-0.2, 0.2)}"]),
        (1, lambda: ["camera frame"]),
        (1, lambda: ["camera reset"]),
        (6, lambda: [f"camera resolution {rng.randint(16, 700)} {rng.randint(16, 700)}"]),
        (3, lambda: [f"wait-frames {rng.randint(1, 4)}"]),
        (0.4, lambda: ["wait-final 300"]),
        # A failed load keeps the scene on screen; the scene is then opened again by name, since a reload
        # reloads the path asked for last (the broken one); a reload brings the file back, edits dropped.
        (1, lambda: [f"open {broken}", "expect-error broken.xml:", f"open {scene}"]),
        (1, lambda: ["reload", "expect-no-error"]),
    ]
    weights = [w for w, _ in makers]
    # The window at 800x600, the smallest the overlays case checks: every frame draws and renders a 400x600 image
    # area instead of the initial window's 880x800, a third of the pixels; the commands are the same seeded sequence
    # (the resize takes the place of its last one).
    lines = [f"# stress_test.py soak: {count} commands, seed {seed}", "resize 800 600", "wait-final 300"]
    warmup_mark = int(count * WARMUP_FRACTION)
    while len(lines) - 1 < count - 4:  # the first line is a comment
        if len(lines) >= warmup_mark and "print-state" not in lines:
            lines += ["wait-final 300", "print-state"]
            continue
        lines += rng.choices(makers, weights)[0][1]()
    # The end: every edit rendered, memory sampled while the viewer is idle, then exit 0.
    lines += ["wait-final 300", "print-state", "sleep 1", "quit"]
    return "\n".join(lines) + "\n"


def case_soak(args, work):
    scene = copy_scene(work)
    broken = os.path.join(work, "broken.xml")
    with open(scene) as f:
        text = f.read()
    with open(broken, "w") as f:
        f.write(text[: len(text) // 2])  # truncated: a located error, never a partial scene
    script = os.path.join(work, "soak.rvs")
    with open(script, "w") as f:
        f.write(soak_script(args.commands, args.seed, scene, broken, work))
    commands = sum(1 for line in open(script) if line.strip() and not line.startswith("#"))

    # A small ASan quarantine, so that freed memory held back by ASan does not hide or fake a trend.
    os.environ["ASAN_OPTIONS"] = ":".join(filter(None, [os.environ.get("ASAN_OPTIONS"), "quarantine_size_mb=16"]))
    started = time.monotonic()
    viewer = Viewer(args.rayview, [scene, "--threads", "2", "--script", script], work)
    samples = []  # (seconds, MB) every half second: the curve, for the log
    marks = []

    def sample():
        while viewer.process.poll() is None:
            try:
                samples.append((time.monotonic() - started, vm_rss_mb(viewer.process.pid)))
            except (OSError, Failure):
                return
            time.sleep(0.5)

    threading.Thread(target=sample, daemon=True).start()
    try:
        for _ in range(2):
            viewer.wait_for("state ", timeout=args.timeout)
            marks.append(vm_rss_mb(viewer.process.pid))
            print(f"  resident memory at mark {len(marks)}: {marks[-1]:.1f} MB")
        code = viewer.finish(timeout=60)
    finally:
        viewer.kill()
    elapsed = time.monotonic() - started
    check_sanitizers(viewer)
    if code != 0:
        raise Failure(f"the soak script failed ({code})\n" + viewer.output()[-20000:])
    peak = max(mb for _, mb in samples) if samples else 0.0
    growth = marks[1] - marks[0]
    print(f"  soak: {commands} commands in {elapsed:.0f} s, seed {args.seed}; resident memory after warm-up "
          f"{marks[0]:.1f} MB, at the end {marks[1]:.1f} MB ({growth:+.1f} MB), peak {peak:.1f} MB; "
          f"{sum(1 for l in viewer.stdout if l.startswith('final pass'))} final passes, "
          f"{sum(1 for l in viewer.stdout if l.startswith('loaded'))} loads")
    if growth > RSS_TOLERANCE_MB:
        raise Failure(f"resident memory grew by {growth:.1f} MB during the soak (allowed {RSS_TOLERANCE_MB} MB)")


def case_threads(args, work):
    scene = copy_scene(work)
    with open(scene) as f:
        original = f.read()
    # Two valid versions of the file, told apart by the floor's colour, so each rewrite is a real change.
    versions = [original, original.replace("<diffuse>0.7 0.7 0.7</diffuse>", "<diffuse>0.6 0.7 0.8</diffuse>", 1)]
    if versions[0] == versions[1]:
        raise Failure("the test scene's floor material changed; update stress_test.py")

    rng = random.Random(args.seed)

    def edits(n):
        return "\n".join(rng.choice([
            f"set material red diffuse {rng.random():.2f} {rng.random():.2f} {rng.random():.2f}",
            f"camera orbit {rng.uniform(-20, 20):.1f} {rng.uniform(-10, 10):.1f}",
            f"set depth {rng.randint(0, 4)}",
            f"camera resolution {rng.randint(16, 320)} {rng.randint(16, 240)}",
            f"set light sun position {rng.uniform(-4, 4):.1f} 5 4",
            "wait-frames 2",
        ]) for _ in range(n))

    # Run 1. Phases, told to this test by `print-state` lines: (a) edits while the file is rewritten (the
    # file watch reloads it on the loader task, twice a second) and the mouse drags the camera; (b) a
    # measurement, left alone (any edit or load cancels it, which fails the script); (c) edits and
    # rewrites again; (d) quiet, to the final pass.
    script = os.path.join(work, "threads.rvs")
    with open(script, "w") as f:
        f.write(f"wait-final 600\n{edits(80)}\nprint-state\nsleep 2\nmeasure-tradeoff 0.1 900\n{edits(80)}\n"
                "reload\nprint-state\nwait-final 600\nquit\n")
    viewer = Viewer(args.rayview, [scene, "--threads", "2", "--script", script], work)
    busy = threading.Event()  # set: rewrite the file and drag
    stop = threading.Event()
    counts = {"rewrites": 0, "drags": 0}

    def rewrite_file():
        # Written whole and renamed, as editors do.
        while not stop.is_set():
            if busy.wait(0.1) and not stop.is_set():
                temporary = scene + ".tmp"
                with open(temporary, "w") as f:
                    f.write(versions[counts["rewrites"] % 2])
                os.replace(temporary, scene)
                counts["rewrites"] += 1
                stop.wait(0.6)

    def drag_camera():
        # Real mouse drags over the image: navigation on the UI thread while the other threads run.
        try:
            window = viewer_window(viewer)
        except Failure:
            return
        while not stop.is_set():
            if busy.wait(0.1) and not stop.is_set():
                try:
                    xdotool("mousemove", "--window", window, 800, 380, "mousedown", 1,
                            "mousemove", "--window", window, 860, 400, "mouseup", 1)
                    counts["drags"] += 1
                except Failure:
                    return
                stop.wait(0.4)

    helpers = [threading.Thread(target=rewrite_file, daemon=True), threading.Thread(target=drag_camera, daemon=True)]
    try:
        viewer.wait_for("final pass generation", timeout=args.timeout)
        busy.set()
        for t in helpers:
            t.start()
        viewer.wait_for("state ", timeout=args.timeout)      # (b): quiet until the measurement is over
        busy.clear()
        viewer.wait_for("tradeoff ", timeout=args.timeout)   # (c)
        busy.set()
        viewer.wait_for("state ", timeout=args.timeout)      # (d)
        busy.clear()
        code = viewer.finish(timeout=args.timeout)
    finally:
        stop.set()
        viewer.kill()
    check_sanitizers(viewer)
    if code != 0:
        raise Failure(f"the threads script failed ({code})\n" + viewer.output()[-20000:])
    loads = [l for l in viewer.stdout if l.startswith("loaded ")]
    print(f"  run 1: 160 edits, {counts['rewrites']} rewrites of the file, {len(loads)} loads, {counts['drags']} drags, "
          f"one measurement")
    if len(loads) < 3:
        raise Failure(f"only {len(loads)} loads: the file watch should have reloaded the rewritten file\n" +
                      viewer.output())

    # Run 2: a load cancels a running measurement (the file changes under it), then the viewer exits while
    # the trade-off and loader threads wind down. The script fails with "cancelled" (exit 1), unless the
    # measurement was already over (exit 0).
    script = os.path.join(work, "cancel.rvs")
    with open(script, "w") as f:
        f.write("wait-final 600\nprint-state\nmeasure-tradeoff 0.5 900\nquit\n")
    viewer = Viewer(args.rayview, [scene, "--threads", "2", "--script", script], work)
    try:
        viewer.wait_for("state ", timeout=args.timeout)
        time.sleep(1.0)
        with open(scene, "w") as f:
            f.write(versions[0] if counts["rewrites"] % 2 else versions[1])
        code = viewer.finish(timeout=args.timeout)
    finally:
        viewer.kill()
    check_sanitizers(viewer)
    cancelled = any("measure-tradeoff: cancelled" in line for line in viewer.stderr)
    if not (code == 1 and cancelled) and code != 0:
        raise Failure(f"run 2 should end cancelled (1) or measured (0), not {code}\n" + viewer.output())
    print(f"  run 2: the measurement was {'cancelled by the reload' if cancelled else 'over before the reload'}")


CASES = {"soak": case_soak, "threads": case_threads}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("case", choices=sorted(CASES))
    parser.add_argument("--rayview", required=True)
    parser.add_argument("--output", required=True)
    parser.add_argument("--commands", type=int, default=10000)
    parser.add_argument("--seed", type=int, default=9)
    parser.add_argument("--timeout", type=float, default=1200.0, help="seconds for the whole run")
    args = parser.parse_args()
    args.rayview = os.path.abspath(args.rayview)

    return run_case(__file__, CASES, args)


if __name__ == "__main__":
    sys.exit(main())
