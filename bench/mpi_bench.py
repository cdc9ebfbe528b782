#!/usr/bin/env python3
"""rayview render under mpirun against the single process (docs/scale-out.md, "Measured"):

  libmpi     what linking libmpi into rayview would cost every render: a small scene's wall time, plain and with
             libmpi preloaded (the reason rayview-mpi is a program of its own);
  one rank   `mpirun -n 1 rayview render` against `rayview render`, on a render of over a second (monkey at 49
             samples, 1.4 s at 2 threads);
  two ranks  2 ranks x 1 thread against 1 process x 2 threads, the same render;
  balance    the summary's mean/max busy time on a deliberately imbalanced frame (a small bright object,
             everything else background), 2 and 4 ranks;
  start-up   a 1M-triangle scene: load (rank 0's, with the broadcast and the check) plus BVH build, 1, 2, 4 ranks.

Each figure is the best of --repeat runs (the machine is shared). Prints a Markdown table.

    bench/mpi_bench.py --build build/release [--repeat 5] [--work build/mpi-bench]
"""
import argparse
import glob
import os
import re
import resource
import statistics
import subprocess
import sys
import time

TIME_LINE = re.compile(r"time\s+load ([\d.]+) ms[^,]*, BVH build ([\d.]+) ms, render ([\d.]+) ms")
BALANCE = re.compile(r"balance\s+([\d.]+)")


def cpu_seconds():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def run(command, env=None):
    """Wall ms, CPU ms of the whole process tree (mpirun and its ranks included), stdout."""
    start, cpu = time.monotonic(), cpu_seconds()
    done = subprocess.run(command, capture_output=True, text=True, env=env)
    wall = (time.monotonic() - start) * 1000.0
    if done.returncode != 0:
        sys.exit(f"failed: {' '.join(command)}\n{done.stderr}")
    return wall, (cpu_seconds() - cpu) * 1000.0, done.stdout


CPU = {}


def best(repeat, command, env=None):
    """(best wall ms, best render ms, best load+build ms, balances) over `repeat` runs; the best CPU ms in CPU."""
    walls, renders, startups, balances, cpus = [], [], [], [], []
    for _ in range(repeat):
        wall, cpu, out = run(command, env)
        walls.append(wall)
        cpus.append(cpu)
        CPU[tuple(command)] = min(cpus)
        m = TIME_LINE.search(out)
        if m:
            renders.append(float(m.group(3)))
            startups.append(float(m.group(1)) + float(m.group(2)))
        b = BALANCE.search(out)
        if b:
            balances.append(float(b.group(1)))
    return min(walls), min(renders or [0]), min(startups or [0]), balances


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default="build/release")
    parser.add_argument("--work", default="build/mpi-bench")
    parser.add_argument("--shared", default=os.path.join(os.path.dirname(__file__), "..", "..", "shared"))
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--skip-large", action="store_true", help="no 1M-triangle start-up")
    args = parser.parse_args()
    os.makedirs(args.work, exist_ok=True)
    os.environ.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
                      OMPI_MCA_rmaps_base_oversubscribe="1")
    rayview = os.path.join(args.build, "app", "rayview")
    source = os.path.join(os.path.dirname(__file__), "..")
    monkey = os.path.join(args.shared, "conformance", "ceng477", "monkey.xml")
    bunny = os.path.join(args.shared, "conformance", "ceng477", "bunny.xml")
    out = os.path.join(args.work, "out.png")
    mpirun = lambda n: ["mpirun", "--bind-to", "none", "-n", str(n)]
    rows = []

    launch = best(args.repeat, mpirun(1) + ["true"])
    launch_cpu = CPU[tuple(mpirun(1) + ["true"])]
    rows.append(("mpirun's own launch (`mpirun -n 1 true`): wall, CPU", "", f"{launch[0]:.0f} ms", f"CPU {launch_cpu:.0f} ms"))

    small = [rayview, "render", os.path.join(source, "scenes", "triangular_light.xml"), "-o", out, "--threads", "2"]
    libmpi = sorted(glob.glob("/usr/lib/*/libmpi.so.40") + glob.glob("/usr/lib/*/openmpi/lib/libmpi.so.40"))
    plain = best(args.repeat * 3, small)[0]
    plain_cpu = CPU[tuple(small)]
    if libmpi:
        env = dict(os.environ, LD_PRELOAD=libmpi[0])
        loaded = best(args.repeat * 3, small, env)[0]
        loaded_cpu = CPU[tuple(small)]
        rows.append(("libmpi loaded into a small render: wall", f"{plain:.1f} ms", f"{loaded:.1f} ms",
                     f"{loaded / plain:.3f}x"))
        rows.append(("libmpi loaded into a small render: CPU", f"{plain_cpu:.1f} ms", f"{loaded_cpu:.1f} ms",
                     f"{loaded_cpu / plain_cpu:.3f}x"))

    heavy = [monkey, "-o", out, "--samples", "49"]
    single2 = best(args.repeat, [rayview, "render", *heavy, "--threads", "2"])
    one_rank = best(args.repeat, mpirun(1) + [rayview, "render", *heavy, "--threads", "2"])
    rows.append(("1 rank x 2 threads vs no MPI, render", f"{single2[1]:.0f} ms", f"{one_rank[1]:.0f} ms",
                 f"{one_rank[1] / single2[1]:.3f}x"))
    rows.append(("1 rank x 2 threads vs no MPI, wall", f"{single2[0]:.0f} ms", f"{one_rank[0]:.0f} ms",
                 f"{one_rank[0] / single2[0]:.3f}x"))
    cpu_single = CPU[tuple([rayview, "render", *heavy, "--threads", "2"])]
    cpu_one = CPU[tuple(mpirun(1) + [rayview, "render", *heavy, "--threads", "2"])]
    rows.append(("1 rank x 2 threads vs no MPI, CPU time less mpirun's launch", f"{cpu_single:.0f} ms",
                 f"{cpu_one - launch_cpu:.0f} ms", f"{(cpu_one - launch_cpu) / cpu_single:.3f}x"))
    rows.append(("1 rank x 2 threads vs no MPI, CPU time with mpirun's launch", f"{cpu_single:.0f} ms",
                 f"{cpu_one:.0f} ms", f"{cpu_one / cpu_single:.3f}x"))
    two_ranks = best(args.repeat, mpirun(2) + [rayview, "render", *heavy, "--threads", "1"])
    rows.append(("2 ranks x 1 thread vs 1 process x 2 threads, render", f"{single2[1]:.0f} ms",
                 f"{two_ranks[1]:.0f} ms", f"{single2[1] / two_ranks[1] * 100:.1f} %"))
    rows.append(("2 ranks x 1 thread vs 1 process x 2 threads, wall", f"{single2[0]:.0f} ms",
                 f"{two_ranks[0]:.0f} ms", f"{single2[0] / two_ranks[0] * 100:.1f} %"))
    # OpenMPI's default transport (UCX) costs a multi-rank job ~0.2 s more to start here than its on-node one: a
    # choice for whoever runs mpirun (on a cluster UCX is the right one), measured so the fixed cost is visible.
    on_node = ["--mca", "pml", "ob1", "--mca", "btl", "self,vader"]
    two_on_node = best(args.repeat, ["mpirun", "--bind-to", "none", *on_node, "-n", "2", rayview, "render", *heavy, "--threads", "1"])
    rows.append(("2 ranks x 1 thread vs 1 process x 2 threads, wall, `--mca pml ob1 --mca btl self,vader`",
                 f"{single2[0]:.0f} ms", f"{two_on_node[0]:.0f} ms", f"{single2[0] / two_on_node[0] * 100:.1f} %"))
    init_only = os.path.join(args.build, "bench", "mpi_init_only")
    if os.path.exists(init_only):
        rows.append(("MPI_Init + MPI_Finalize alone, 2 ranks: wall (default; on-node transport)", "",
                     f"{best(args.repeat, mpirun(2) + [init_only])[0]:.0f} ms",
                     f"{best(args.repeat, ['mpirun', '--bind-to', 'none', *on_node, '-n', '2', init_only])[0]:.0f} ms"))
    cpu_two = CPU[tuple(mpirun(2) + [rayview, "render", *heavy, "--threads", "1"])]
    rows.append(("2 ranks x 1 thread vs 1 process x 2 threads, CPU time less mpirun's launch", f"{cpu_single:.0f} ms",
                 f"{cpu_two - launch_cpu:.0f} ms", f"{cpu_single / (cpu_two - launch_cpu) * 100:.1f} %"))

    imbalanced = [bunny, "-o", out, "--samples", "36", "--threads", "1"]
    for n in (2, 4):
        balances = best(args.repeat, mpirun(n) + [rayview, "render", *imbalanced])[3]
        rows.append((f"balance, bunny (object in the middle) on {n} ranks", "", f"median {statistics.median(balances):.3f}",
                     f"min {min(balances):.3f}"))

    if not args.skip_large:
        large = os.path.join(args.work, "heightfield_1e6.xml")
        if not os.path.exists(large):
            subprocess.run([os.path.join(args.build, "bench", "scale_series"), "write", "heightfield", "1000000", large],
                           check=True, stdout=subprocess.DEVNULL)
        lean = [large, "-o", out, "--threads", "1"]
        first = best(args.repeat, mpirun(1) + [rayview, "render", *lean])[2]
        for n in (2, 4):
            startup = best(args.repeat, mpirun(n) + [rayview, "render", *lean])[2]
            rows.append((f"1M triangles: load+build on {n} ranks vs 1 rank", f"{first:.0f} ms", f"{startup:.0f} ms",
                         f"{startup / first:.2f}x"))

    print("| measure | baseline | MPI | ratio |\n|---|---|---|---|")
    for row in rows:
        print("| " + " | ".join(row) + " |")


if __name__ == "__main__":
    main()
