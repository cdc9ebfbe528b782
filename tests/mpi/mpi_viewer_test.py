#!/usr/bin/env python3
"""The viewer under mpirun: `mpirun -n N rayview SCENE` opens the window on rank 0, the other ranks trace its
passes, edits reach them, the final pass is `rayview render`'s image byte for byte, and quitting ends every rank.
Needs xvfb-run and mpirun (exit 77, skipped, without them)."""
import argparse
import os
import re
import shutil
import signal
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mpi_test  # noqa: E402  (the render test's preparation, beside this file)

SKIP = 77


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--rayview", required=True)
    parser.add_argument("--shared", required=True)
    parser.add_argument("--source", required=True)
    parser.add_argument("--scratch", required=True)
    args = parser.parse_args()
    for tool in ("mpirun", "xvfb-run"):
        if shutil.which(tool) is None:
            print(f"{tool} not found: skipped")
            return SKIP
    mpi_test.prepare(args.scratch)
    failures = []
    # A clone without the shared folder has none of the course's scenes these cases render: skip, as the others do.
    if not os.path.isdir(os.path.join(args.shared, "conformance", "ceng477")):
        print(f"{args.shared}/conformance/ceng477 not found (the course's scenes): skipped")
        return SKIP
    bunny = os.path.join(args.shared, "conformance", "ceng477", "bunny.xml")
    textured = os.path.join(args.source, "scenes", "textured_2025.xml")
    scenes = [(bunny, "bunny", ["set material 1 diffuse 0.9 0.2 0.1", "set light 1 position 0 5 5",
                                "camera orbit 20 10"], [])]
    if not os.path.exists(bunny):
        print(f"{bunny} missing: only the textured scene runs")
        scenes = []
    # The texture, vertex normals and an area light with several samples reach the workers too.
    # (Render settings are not saved with the scene: the reference render is given them as options.)
    scenes.append((textured, "textured", ["set samples 2", "set light-samples 3", "camera orbit -15 5"],
                   ["--samples", "2", "--light-samples", "3"]))
    for scene, name, edits, options in scenes:
        failures += edited_render_matches(args, scene, name, edits, options)
    failures += killed_worker(args, textured)
    for failure in failures:
        print("FAIL:", failure)
    print(f"{len(failures)} failed")
    return 1 if failures else 0


def edited_render_matches(args, scene, name, edits, options):
    """Saves the first final pass and one after the edits, with the scene as edited; each must be that scene's
    `rayview render` image byte for byte."""
    out = lambda f: os.path.join(args.scratch, f"{name}_{f}")
    script = out("script.txt")
    with open(script, "w") as f:
        f.write("view image\nwait-final\n")
        f.write(f"save-frame {out('first.png')}\nsave-scene {out('first.xml')}\n")
        f.write("\n".join(edits) + "\nwait-final\n")
        f.write(f"save-frame {out('edited.png')}\nsave-scene {out('edited.xml')}\nquit\n")
    command = ["xvfb-run", "-a", "mpirun", "-n", "3", args.rayview, "--threads", "1", "--script", script, scene]
    try:
        run = subprocess.run(command, capture_output=True, text=True, timeout=180)
    except subprocess.TimeoutExpired:
        return [f"{name}: the job did not end within 180 s of the script's quit"]
    failures = []
    if run.returncode != 0:
        failures.append(f"{name}: exit {run.returncode}:\n{run.stdout}\n{run.stderr}")
    if "rendering on 3 ranks" not in run.stdout:
        failures.append(f"{name}: the window does not say it renders on 3 ranks:\n{run.stdout}")
    traced = re.search(r"tiles traced: rank 0 (\d+) [^,]*, rank 1 (\d+) [^,]*, rank 2 (\d+)", run.stdout)
    if not traced or int(traced.group(2)) == 0 or int(traced.group(3)) == 0:
        failures.append(f"{name}: the other ranks traced no tiles:\n{run.stdout}")
    for stage, settings in (("first", []), ("edited", options)):
        reference = out(f"{stage}_render.png")
        subprocess.run([args.rayview, "render", out(f"{stage}.xml"), "-o", reference, "--quiet", *settings],
                       check=False)
        shown = out(f"{stage}.png")
        if not (os.path.exists(shown) and os.path.exists(reference)
                and open(shown, "rb").read() == open(reference, "rb").read()):
            failures.append(f"{name}: the {stage} final pass is not `rayview render`'s image ({shown}, {reference})")
    return failures


def killed_worker(args, scene):
    """Under mpirun --enable-recovery, a worker killed while the passes render: the window goes on with the other
    ranks, the final pass is still `rayview render`'s image, and quitting ends every rank."""
    out = os.path.join(args.scratch, "killed.png")
    script = os.path.join(args.scratch, "killed.txt")
    with open(script, "w") as f:
        f.write(f"view image\nwait-final\nset samples 40\nwait-final\nsave-frame {out}\nquit\n")
    marker = f"rayview-killed-{os.getpid()}"
    env = dict(os.environ, RAYVIEW_TEST_JOB=marker)
    job = subprocess.Popen(["xvfb-run", "-a", "mpirun", "--enable-recovery", "-n", "3", args.rayview, "--threads", "1",
                            "--script", script, scene], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                           env=env)
    seen = []
    for line in job.stdout:  # the first final pass: the workers hold the geometry and trace
        seen.append(line)
        if "final pass generation 2" in line:
            break
    victim = job_rank(marker, 1)
    if victim is None:
        job.kill()
        return [f"killed worker: rank 1 not found:\n{''.join(seen)}"]
    os.kill(victim, signal.SIGKILL)
    try:
        rest, _ = job.communicate(timeout=180)
    except subprocess.TimeoutExpired:
        job.kill()
        return ["killed worker: the job did not end within 180 s"]
    text = "".join(seen) + rest
    failures = []
    if job.returncode != 0 or "rank 1 fell silent" not in text:
        failures.append(f"killed worker: exit {job.returncode}, or no word of rank 1:\n{text}")
    reference = os.path.join(args.scratch, "killed_render.png")
    subprocess.run([args.rayview, "render", scene, "--samples", "40", "-o", reference, "--quiet"], check=False)
    if not (os.path.exists(out) and open(out, "rb").read() == open(reference, "rb").read()):
        failures.append(f"killed worker: the final pass is not `rayview render`'s image ({out})")
    if job_rank(marker, 2) is not None:
        failures.append("killed worker: rank 2 still runs after the window closed")
    return failures


def job_rank(marker, rank):
    """The pid of `rank` of the job whose environment holds `marker`, or None."""
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            environ = open(f"/proc/{pid}/environ", "rb").read().split(b"\0")
        except OSError:
            continue
        if f"RAYVIEW_TEST_JOB={marker}".encode() in environ and f"OMPI_COMM_WORLD_RANK={rank}".encode() in environ:
            return int(pid)
    return None


if __name__ == "__main__":
    sys.exit(main())
