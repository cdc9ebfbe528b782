#!/usr/bin/env python3
"""rayview render under mpirun: the image is the single process's byte for byte, a bad scene fails once, a killed
rank ends the job cleanly (or, with mpirun --enable-recovery, the survivors finish the same image); turntables give
the single process's frames, dealt whole to ranks, and a killed one is finished by a rerun; a batch of scenes is
dealt by scene with the single process's images, its resume, a bad scene in it and a killed rank's scene."""
import argparse
import os
import shutil
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from image_files import same_file  # noqa: E402

SKIP = 77


# How many times a case that needs rank 0's message under plain mpirun runs before it fails (under_plain_mpirun).
MPIRUN_TRIES = 4


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--rayview", required=True)
    parser.add_argument("--shared", required=True)
    parser.add_argument("--source", required=True)
    parser.add_argument("--scratch", required=True)
    parser.add_argument("--max-ranks", type=int, default=4)
    # The sanitizers a build has ("" for none): there the killed-rank cases render fewer samples (below).
    parser.add_argument("--sanitizers", default="")
    args = parser.parse_args()
    if shutil.which("mpirun") is None:
        print("mpirun not found: skipped")
        return SKIP
    prepare(args.scratch)
    conformance = os.path.join(args.shared, "conformance", "ceng477")
    scenes = os.path.join(args.source, "scenes")
    t = Tester(args)
    # (scene, options, ranks, threads per rank): point lights, mirrors, area lights with samples, a texture (the
    # workers get it from rank 0), the default scene, every traversal back-end.
    cases = [
        (os.path.join(conformance, "bunny.xml"), [], 1, 2),
        (os.path.join(conformance, "monkey.xml"), ["--accel", "reference", "--depth", "3"], 2, 1),
        (os.path.join(scenes, "triangular_light.xml"), ["--light-samples", "4", "--samples", "2"], 3, 2),
        (os.path.join(scenes, "textured_2025.xml"), ["--accel", "embree"], args.max_ranks, 1),
        ("", ["--tri-light", "directional", "--accel", "packet"], 2, 2),
    ]
    # The course's scenes live in the shared folder beside the repository: without it, the cases that read them are
    # skipped, said once; rayview's own scenes still run every kind of check.
    have_shared = os.path.isdir(conformance)
    if not have_shared:
        print(f"skipped: the cases that read the course's scenes ({conformance} not found)")
        cases = [c for c in cases if not c[0].startswith(conformance)]
    for scene, options, ranks, threads in cases:
        t.identical(scene, options, min(ranks, args.max_ranks), threads)
    t.bad_scene()
    t.frames(os.path.join(scenes, "triangular_light.xml"), min(3, args.max_ranks), 4)
    t.frames(os.path.join(scenes, "triangular_light.xml"), min(2, args.max_ranks), 6)
    batch = [os.path.join(scenes, "triangular_light.xml"), os.path.join(scenes, "textured_2025.xml")]
    batch += ([os.path.join(conformance, "bunny.xml"), os.path.join(conformance, "scienceTree_512x512.xml")]
              if have_shared else [os.path.join(scenes, "default.xml")])
    t.batch(batch, min(2, args.max_ranks))  # 3 ranks: bad_scene_in_batch, killed_batch
    t.bad_scene_in_batch(batch)
    # A render long enough to kill a rank in: the course's monkey, or rayview's own scene with many samples.
    slow_scene = os.path.join(conformance, "monkey.xml") if have_shared else os.path.join(scenes, "triangular_light.xml")
    # Under a sanitizer every render is many times slower, so a quarter of the samples (at least one) still leaves
    # rank 1 rendering when it is killed, and the survivors finish the rest (most of these cases' time) sooner.
    samples = lambda n: str(max(1, n // 4) if args.sanitizers else n)
    t.killed_batch(slow_scene, samples(4))
    slow = [slow_scene, "--samples", samples(9) if have_shared else samples(36)]
    t.killed_rank(slow, recovery=False)
    t.killed_rank(slow, recovery=True)
    t.killed_turntable([slow_scene, "--samples", samples(4) if have_shared else samples(16)])
    print(f"{t.passed} passed, {len(t.failures)} failed")
    for failure in t.failures:
        print("FAIL:", failure)
    return 1 if t.failures else 0


def prepare(scratch):
    """An empty scratch folder, and mpirun allowed as root and past the cores."""
    shutil.rmtree(scratch, ignore_errors=True)
    os.makedirs(scratch)
    os.environ.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMPI_MCA_rmaps_base_oversubscribe="1")
    # Under ASan, OpenMPI's components keep allocations to the end and are unloaded before the leak check, so LSan
    # reports them from "<unknown module>", which no suppression can name: the rest of the suite checks the same
    # renderer code for leaks in one process; here ASan and UBSan check every access and operation.
    if os.environ.get("ASAN_OPTIONS") is not None:
        os.environ["ASAN_OPTIONS"] += ":detect_leaks=0"


class Tester:
    def __init__(self, args):
        self.args = args
        self.passed = 0
        self.failures = []
        self.count = 0

    def check(self, ok, what):
        if ok:
            self.passed += 1
        else:
            self.failures.append(what)

    def out(self, name):
        self.count += 1
        return os.path.join(self.args.scratch, f"{self.count:02d}_{name}.png")

    def mpirun(self, ranks, arguments, extra=()):
        return ["mpirun", *extra, "-n", str(ranks), self.args.rayview, "render", *arguments]

    def identical(self, scene, options, ranks, threads):
        name = os.path.basename(scene) or "default"
        single = self.out(name + "_single")
        scene_args = [scene] if scene else []
        subprocess.run([self.args.rayview, "render", *scene_args, "-o", single, "--quiet", *options], check=True)
        spread = self.out(f"{name}_{ranks}x{threads}")
        run = subprocess.run(self.mpirun(ranks, [*scene_args, "-o", spread, "--threads", str(threads), *options]),
                             capture_output=True, text=True, timeout=120)
        what = f"{name} {options} on {ranks} ranks x {threads} threads"
        self.check(run.returncode == 0, f"{what}: exit {run.returncode}: {run.stderr}")
        # One rank is a single process (nothing to share; MPI is not even started): its usual summary.
        summary = f"rank {ranks - 1}" in run.stdout and "balance" in run.stdout if ranks > 1 else "rays" in run.stdout
        self.check(summary, f"{what}: summary:\n{run.stdout}")
        same = os.path.exists(spread) and same_file(single, spread)
        self.check(same, f"{what}: the image differs from the single process's")

    def frames(self, scene, ranks, count):
        """A turntable under MPI: the single process's frames byte for byte, the first count - (ranks - 1) frames
        dealt whole to ranks and the last ones in tiles; a rerun renders only the missing one."""
        single = os.path.join(self.args.scratch, f"frames_single_{count}", "f_%d.png")
        spread = os.path.join(self.args.scratch, f"frames_mpi_{ranks}x{count}", "f_%d.png")
        options = ["--turntable", str(count), "--light-samples", "2"]
        what = f"turntable of {count} on {ranks} ranks"
        if not os.path.exists(single % (count - 1)):
            subprocess.run([self.args.rayview, "render", scene, *options, "-o", single, "--quiet"], check=True)
        run = subprocess.run(self.mpirun(ranks, [scene, *options, "-o", spread, "--threads", "1"]),
                             capture_output=True, text=True, timeout=120)
        self.check(run.returncode == 0 and f"{count} to render" in run.stdout
                   and f"frame {count} of {count} written" in run.stderr,
                   f"{what}: exit {run.returncode}: {run.stdout}{run.stderr}")
        # "rank 1     busy 72.7 ms, 3 whole frames, 7 tiles": whole frames add up to those dealt whole.
        rows = [line.split(",") for line in run.stdout.splitlines() if line.startswith("rank ")]
        whole = sum(int(row[1].split()[0]) for row in rows if len(row) == 3 and "whole frames" in row[1])
        self.check(len(rows) == ranks and whole == count - (ranks - 1),
                   f"{what}: {whole} frames rendered whole, not {count - (ranks - 1)}:\n{run.stdout}")
        same = lambda: all(os.path.exists(spread % k) and same_file(spread % k, single % k) for k in range(count))
        self.check(same(), f"{what}: frames differ from the single process's")
        os.remove(spread % 1)
        run = subprocess.run(self.mpirun(ranks, [scene, *options, "-o", spread]), capture_output=True, text=True,
                             timeout=120)
        self.check(run.returncode == 0 and f"{count - 1} complete already, 1 to render" in run.stdout and same(),
                   f"{what}, rerun: {run.stdout}{run.stderr}")

    def batch(self, scenes, ranks):
        """A batch of different scenes under MPI: dealt whole to ranks (the summary counts each scene once), the
        single process's images byte for byte; a rerun renders only the missing ones."""
        single = os.path.join(self.args.scratch, "batch_single") + "/"
        spread = os.path.join(self.args.scratch, f"batch_{ranks}") + "/"
        names = [os.path.splitext(os.path.basename(s))[0] + ".png" for s in scenes]
        what = f"batch of {len(scenes)} on {ranks} ranks"
        if not os.path.isdir(single):
            subprocess.run([self.args.rayview, "render", *scenes, "-o", single, "--quiet"], check=True)
        run = subprocess.run(self.mpirun(ranks, [*scenes, "-o", spread, "--threads", "1"]), capture_output=True,
                             text=True, timeout=120)
        self.check(run.returncode == 0 and f"frame {len(scenes)} of {len(scenes)} written" in run.stderr,
                   f"{what}: exit {run.returncode}: {run.stdout}{run.stderr}")
        # "rank 1     busy 72.7 ms, 2 scenes, 2 whole frames, 0 tiles"
        rows = [line.split(",") for line in run.stdout.splitlines() if line.startswith("rank ")]
        whole = sum(int(row[1].split()[0]) for row in rows if len(row) == 4 and "scene" in row[1])
        self.check(len(rows) == ranks and whole == len(scenes), f"{what}: {whole} scenes rendered whole:\n{run.stdout}")
        same = lambda: all(os.path.exists(spread + n) and same_file(spread + n, single + n) for n in names)
        self.check(same(), f"{what}: images differ from the single process's")
        for n in names[1:3]:
            os.remove(spread + n)
        run = subprocess.run(self.mpirun(ranks, [*scenes, "-o", spread]), capture_output=True, text=True, timeout=120)
        self.check(run.returncode == 0 and f"{len(scenes) - 2} complete already, 2 to render" in run.stdout and same(),
                   f"{what}, rerun: {run.stdout}{run.stderr}")

    def bad_scene_in_batch(self, scenes):
        """A batch whose third scene does not load: as the single process, the scenes before it written, the
        located message once, exit 2, nothing after it and no temporary file."""
        bad = os.path.join(self.args.scratch, "bad.xml")
        with open(bad, "w") as f:
            f.write("<scene>\n<camera>\n<position>0 0 oops</position>\n</camera>\n</scene>\n")
        listed = [*scenes[:2], bad, *scenes[2:]]
        single_dir = os.path.join(self.args.scratch, "bad_batch_single") + "/"
        spread_dir = os.path.join(self.args.scratch, "bad_batch") + "/"
        single = subprocess.run([self.args.rayview, "render", *listed, "-o", single_dir], capture_output=True, text=True)
        run = subprocess.run(self.mpirun(3, [*listed, "-o", spread_dir, "--threads", "1"]), capture_output=True,
                             text=True, timeout=60)
        message = single.stderr.strip().splitlines()[-1]
        self.check(run.returncode == 2 and single.returncode == 2, f"bad batch: exit {run.returncode}, not 2")
        self.check(run.stderr.count(message) == 1, f"bad batch: the located message once:\n{message}\nbut:\n{run.stderr}")
        listing = lambda d: sorted(os.listdir(d)) if os.path.isdir(d) else []
        self.check(listing(spread_dir) == listing(single_dir) == ["textured_2025.png", "triangular_light.png"],
                   f"bad batch: wrote {listing(spread_dir)}, the single process {listing(single_dir)}")

    def killed_batch(self, scene, samples):
        """Rank 1 killed in a batch under mpirun --enable-recovery: its scene goes to the others and every image is
        the single process's."""
        directory = os.path.join(self.args.scratch, "killed_batch")
        os.makedirs(directory)
        copies = []
        for k in range(4):
            copies.append(os.path.join(directory, f"m{k}.xml"))
            shutil.copy(scene, copies[-1])
        options = ["--samples", samples]
        single = os.path.join(directory, "single.png")
        subprocess.run([self.args.rayview, "render", scene, "-o", single, "--quiet", *options], check=True)
        out = os.path.join(directory, "out") + "/"
        ended = self.kill_rank_one(self.mpirun(3, [*copies, "-o", out, "--threads", "1", *options], ["--enable-recovery"]),
                                   "killed batch", 60)
        if ended is None:
            return
        job, stderr, _ = ended
        written = sorted(os.listdir(out)) if os.path.isdir(out) else []
        same = written == [f"m{k}.png" for k in range(4)] and all(same_file(out + n, single) for n in written)
        self.check(job.returncode == 0 and same and "rank 1 fell silent" in stderr,
                   f"killed batch: exit {job.returncode}, files {written}, same {same}:\n{stderr}")
        self.check(not any(rank_process(job.pid, r) for r in range(3)), "killed batch: a rank is still running")

    def under_plain_mpirun(self, name, attempt, said):
        """Whether to run a case that needs rank 0's message under plain mpirun again: OpenMPI 4.1 ends the other
        ranks with SIGTERM and SIGKILL a second later, but now and then (a bash rank that traps SIGTERM shows it
        too) with SIGKILL at once, and then no process can say anything. The message
        must come in one of MPIRUN_TRIES runs."""
        if said or attempt == MPIRUN_TRIES:
            return False
        print(f"{name}: no message from rank 0 (mpirun ended it with SIGKILL?): try {attempt + 1}")
        return True

    def killed_turntable(self, scene_args):
        """Rank 1 killed in a turntable under plain mpirun: the job ends, the frames written stay whole, and a rerun
        renders only the others."""
        directory = os.path.join(self.args.scratch, "killed_turntable")
        spread = os.path.join(directory, "f_%02d.png")
        frames = ["--turntable", "12"]
        for attempt in range(1, MPIRUN_TRIES + 1):
            shutil.rmtree(directory, ignore_errors=True)
            ended = self.kill_rank_one(self.mpirun(3, [*scene_args, *frames, "-o", spread, "--threads", "1"]),
                                       "killed turntable", 30)
            if ended is None:
                return
            if not self.under_plain_mpirun("killed turntable", attempt, "frames written" in ended[1]):
                break
        job, stderr, _ = ended
        written = sorted(os.listdir(directory)) if os.path.isdir(directory) else []
        self.check(job.returncode != 0 and "frames written" in stderr and len(written) < 12,
                   f"killed turntable: exit {job.returncode}, {len(written)} files:\n{stderr}")
        self.check(all(f.endswith(".png") for f in written), f"killed turntable: temporary files left: {written}")
        self.check(not any(rank_process(job.pid, r) for r in range(3)), "killed turntable: a rank is still running")
        run = subprocess.run(self.mpirun(2, [*scene_args, *frames, "-o", spread]), capture_output=True, text=True,
                             timeout=120)
        rest = f"{len(written)} complete already, {12 - len(written)} to render"
        self.check(run.returncode == 0 and rest in run.stdout and len(os.listdir(directory)) == 12,
                   f"killed turntable, rerun: {run.stdout}{run.stderr}")

    def bad_scene(self):
        bad = os.path.join(self.args.scratch, "bad.xml")
        with open(bad, "w") as f:
            f.write("<scene>\n<camera>\n<position>0 0 oops</position>\n</camera>\n</scene>\n")
        single = subprocess.run([self.args.rayview, "render", bad, "-o", self.out("bad_single")],
                                capture_output=True, text=True)
        output = self.out("bad")
        run = subprocess.run(self.mpirun(3, [bad, "-o", output]), capture_output=True, text=True, timeout=60)
        self.check(run.returncode == 2, f"bad scene: exit {run.returncode}, not 2")
        message = single.stderr.strip()
        self.check(message and run.stderr.count(message) == 1,
                   f"bad scene: the located message once, as a single process prints it:\n{message}\nbut:\n{run.stderr}")
        self.check(not os.path.exists(output), "bad scene: an image was written")

    def kill_rank_one(self, command, name, timeout):
        """Starts `command` (an mpirun), kills rank 1 with SIGKILL once it renders, and waits for the job to end.
        Returns (job, stderr, seconds from the kill to the end), or None with the failure recorded."""
        start = time.monotonic()
        job = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        victim = None
        while victim is None and job.poll() is None and time.monotonic() - start < 20:
            time.sleep(0.05)
            victim = rank_process(job.pid, 1, started_rendering=True)
        if victim is None:
            job.kill()
            self.check(False, f"{name}: rank 1 never started rendering")
            return None
        os.kill(victim, signal.SIGKILL)
        killed = time.monotonic()
        try:
            _, stderr = job.communicate(timeout=timeout)
        except subprocess.TimeoutExpired:
            job.kill()
            self.check(False, f"{name}: the job hangs after rank 1 was killed")
            return None
        return job, stderr, time.monotonic() - killed

    def killed_rank(self, scene_args, recovery):
        name = "recovered" if recovery else "killed"
        output = self.out(name)
        extra = ["--enable-recovery"] if recovery else []
        for attempt in range(1, MPIRUN_TRIES + 1):
            ended = self.kill_rank_one(self.mpirun(3, [*scene_args, "-o", output, "--threads", "1"], extra), name, 30)
            if ended is None:
                return
            if recovery or not self.under_plain_mpirun(name, attempt, "not finished" in ended[1]):
                break
        job, stderr, seconds = ended
        # Ending is bounded; finishing (recovery) takes the survivors' render time, which a sanitizer build stretches.
        if not recovery:
            self.check(seconds < 10, f"{name}: the job took {seconds:.1f} s to end")
        leftovers = [f for f in os.listdir(self.args.scratch) if f.startswith(os.path.basename(output)) and f != os.path.basename(output)]
        self.check(not leftovers, f"{name}: temporary files left: {leftovers}")
        self.check(not any(rank_process(job.pid, r) for r in range(3)), f"{name}: a rank is still running")
        if recovery:
            single = self.out("recovered_single")
            subprocess.run([self.args.rayview, "render", *scene_args, "-o", single, "--quiet"], check=True)
            same = os.path.exists(output) and same_file(output, single)
            self.check(job.returncode == 0 and same, f"{name}: exit {job.returncode}, same image {same}:\n{stderr}")
            self.check("rank 1 fell silent" in stderr, f"{name}: no message naming rank 1:\n{stderr}")
        else:
            self.check(job.returncode != 0, f"{name}: exit 0 after a rank was killed")
            self.check(not os.path.exists(output), f"{name}: an image was written")
            self.check("rank 1" in stderr and "not finished" in stderr,
                       f"{name}: no message naming rank 1 and what was not finished:\n{stderr}")


def rank_process(mpirun_pid, rank, started_rendering=False):
    """The pid of `rank` among mpirun's children (None if it is not running)."""
    try:
        children = open(f"/proc/{mpirun_pid}/task/{mpirun_pid}/children").read().split()
    except OSError:
        children = []
    for pid in children:
        try:
            environ = open(f"/proc/{pid}/environ", "rb").read().split(b"\0")
            if f"OMPI_COMM_WORLD_RANK={rank}".encode() not in environ:
                continue
            # Rendering: MPI's two threads, the tile thread and the pool's one.
            if started_rendering and len(os.listdir(f"/proc/{pid}/task")) < 5:
                continue
            return int(pid)
        except OSError:
            continue
    return None


if __name__ == "__main__":
    sys.exit(main())
