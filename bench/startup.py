#!/usr/bin/env python3
"""Start-up cost of `rayview render` on small scenes, where it is most of the time: process start to first ray,
less load and build.

For each scene, runs `rayview render SCENE -o out.ppm --threads T` --repeat times and takes medians of:
wall time of the whole process (fork to exit, measured here), the load / build / render times it prints,
and the remainder = wall - (load + build + render), which is everything else: exec, dynamic linking and
relocation, static initialisers, thread pool and tracer set-up, writing the (PPM, so no deflate) file, exit.
`rayview --version` is measured the same way: exec + linking + exit, with no scene at all. The dynamic
loader's own share comes from LD_DEBUG=statistics (cycles), minor page faults from getrusage (wait4).

    bench/startup.py --rayview build/release/app/rayview [--repeat 21] [--threads 2] [--probes DIR] SCENE.xml...

--probes DIR adds rows for the empty programs bench/CMakeLists.txt builds into DIR (build/release/bench):
library_load_probe_plain (C and C++ runtimes), _tbb (and libtbb), _embree (and libembree3, which loads libtbb);
the differences between their rows are what loading those libraries costs a process before `main`.
"""
import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

TIME_LINE = re.compile(r"time\s+load ([\d.]+) ms, BVH build ([\d.]+) ms, render ([\d.]+) ms")


def run(command, env=None):
    start = time.perf_counter()
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env)
    _, status, usage = os.wait4(process.pid, 0)
    wall = (time.perf_counter() - start) * 1000.0
    out = process.stdout.read().decode()
    err = process.stderr.read().decode()
    process.returncode = os.waitstatus_to_exitcode(status)
    if process.returncode != 0:
        raise RuntimeError(f"{command}: {err[-300:]}")
    return wall, out, err, usage.ru_minflt, (usage.ru_utime + usage.ru_stime) * 1000.0


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--rayview", default="build/release/app/rayview")
    parser.add_argument("--repeat", type=int, default=21)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--probes", help="directory holding the library_load_probe_* programs")
    parser.add_argument("scenes", nargs="*")
    args = parser.parse_args()

    env = dict(os.environ, LD_DEBUG="statistics")
    _, _, err, _, _ = run([args.rayview, "--version"], env)
    cycles = re.search(r"total startup time in dynamic loader: (\d+) cycles", err)
    relocation = re.search(r"time needed for relocation: (\d+) cycles", err)
    relocs = re.search(r"number of relative relocations: (\d+)", err)
    print(f"dynamic loader (LD_DEBUG=statistics, one run): {int(cycles.group(1)) / 1e6:.1f} M cycles in total, "
          f"{int(relocation.group(1)) / 1e6:.1f} M of them relocating; {relocs.group(1)} relative relocations")
    print()
    print("| command | wall ms | load ms | build ms | render ms | remainder ms | CPU ms (user+sys, all threads) "
          "| minor page faults |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    commands = [("/bin/true (the harness's own fork/exec/wait)", ["/bin/true"])]
    if args.probes:
        for kind, what in (("plain", "C and C++ runtimes"), ("tbb", "+ libtbb"), ("embree", "+ libembree3, libtbb")):
            commands.append((f"empty program, {what}", [os.path.join(args.probes, f"library_load_probe_{kind}")]))
    commands.append(("rayview --version", [args.rayview, "--version"]))
    for name, command in commands:
        walls, faults, cpus = [], [], []
        for _ in range(args.repeat):
            wall, _, _, minflt, cpu = run(command)
            walls.append(wall)
            faults.append(minflt)
            cpus.append(cpu)
        print(f"| {name} | {statistics.median(walls):.1f} | | | | {statistics.median(walls):.1f} | "
              f"{statistics.median(cpus):.1f} | {statistics.median(faults):.0f} |")
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out.ppm")
        for scene in args.scenes:
            rows = []
            for _ in range(args.repeat):
                wall, stdout, _, minflt, cpu = run([args.rayview, "render", scene, "-o", out, "--threads",
                                                    str(args.threads)])
                m = TIME_LINE.search(stdout)
                load, build, render = (float(m.group(i)) for i in (1, 2, 3))
                rows.append((wall, load, build, render, wall - load - build - render, cpu, minflt))
            med = [statistics.median(r[i] for r in rows) for i in range(7)]
            print(f"| render {os.path.basename(scene)} | {med[0]:.1f} | {med[1]:.1f} | {med[2]:.1f} | {med[3]:.1f} | "
                  f"{med[4]:.1f} | {med[5]:.1f} | {med[6]:.0f} |")
            sys.stdout.flush()


if __name__ == "__main__":
    main()
