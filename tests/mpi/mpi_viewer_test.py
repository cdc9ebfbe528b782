#!/usr/bin/env python3
"""The viewer under mpirun: `mpirun -n N rayview SCENE` opens the window on rank 0, the other ranks trace its
passes, edits reach them, the final pass is `rayview render`'s image byte for byte, and quitting ends every rank.
A worker killed: under --enable-recovery the window goes on and says so; under plain mpirun the edits are kept.
Needs xvfb-run and mpirun (exit 77, skipped, without them)."""
import argparse
import glob
import os
import pathlib
import re
import shutil
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mpi_test  # noqa: E402  (the render test's preparation, beside this file)

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from image_files import same_file  # noqa: E402

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
    # The viewer's recovery files of unsaved edits go to the scratch folder, never the user's ~/.local/state.
    os.environ["XDG_STATE_HOME"] = os.path.join(args.scratch, "state")
    failures = []
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
    failures += killed_worker_plain(args, textured)
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
                and same_file(shown, reference)):
            failures.append(f"{name}: the {stage} final pass is not `rayview render`'s image ({shown}, {reference})")
    return failures


def killed_worker(args, scene):
    """Under mpirun --enable-recovery, a worker killed while the window is idle: the next edit's first pass is not held
    up waiting for it (it once took over 3 s), the render goes on with the other ranks and its final pass is still
    `rayview render`'s image; the stats then count the dead rank out (`lost_ranks=1`), the quit summary says it was
    lost instead of listing it as working, and quitting ends every rank."""
    out = os.path.join(args.scratch, "killed.png")
    script = os.path.join(args.scratch, "killed.txt")
    with open(script, "w") as f:
        f.write(f"view image\nwait-final\nprint-state\nsleep 4\nset samples 12\nwait-final\nprint-state\n"
                f"save-frame {out}\nsleep 3.5\nset samples 1\nwait-final\nprint-state\nquit\n")
    marker = f"rayview-killed-{os.getpid()}"
    env = dict(os.environ, RAYVIEW_TEST_JOB=marker, XDG_STATE_HOME=os.path.join(args.scratch, "state"))
    job, text = kill_rank_one(["xvfb-run", "-a", "mpirun", "--enable-recovery", "-n", "3", args.rayview, "--threads",
                               "1", "--script", script, scene], env, marker, "killed worker", 180)
    if job is None:
        return [text]
    states = [line for line in text.splitlines() if line.startswith("state ")]
    failures = []
    if job.returncode != 0 or len(states) != 3:
        return [f"killed worker: exit {job.returncode}, or not the script's three states:\n{text}"]
    first_pass = float(re.search(r" first_pass_ms=([0-9.]+)", states[1]).group(1))
    if first_pass > 1500:  # waiting for the dead rank took kLostAfter, 3 s
        failures.append(f"killed worker: the first pass after the loss took {first_pass} ms:\n{text}")
    if " lost_ranks=1 " not in states[2] or "lost rank 1: fell silent" not in text:
        failures.append(f"killed worker: the stats should count rank 1 out:\n{text}")
    summary = re.search(r"tiles traced: rank 0 \d+ [^,]*, rank 1 lost: [^,]*, rank 2 \d+", text)
    if not summary or "PMIX" in summary.group(0):
        failures.append(f"killed worker: the summary should say rank 1 was lost, not list it as working:\n{text}")
    reference = os.path.join(args.scratch, "killed_render.png")
    subprocess.run([args.rayview, "render", scene, "--samples", "12", "-o", reference, "--quiet"], check=False)
    if not (os.path.exists(out) and same_file(out, reference)):
        failures.append(f"killed worker: the final pass is not `rayview render`'s image ({out})")
    if job_rank(marker, 2) is not None:
        failures.append("killed worker: rank 2 still runs after the window closed")
    return failures


def killed_worker_plain(args, scene):
    """Under plain mpirun (the README's command), a worker killed after an edit: OpenMPI 4.1 ends the whole job
    (only mpirun's own --enable-recovery, or OMPI_MCA_orte_enable_recovery=1 in its environment, lets it go on), so
    the window says why it closes and that the edits are kept, their recovery file holds them, and the next start
    restores them."""
    state = os.path.join(args.scratch, "plain_state")
    script = os.path.join(args.scratch, "plain.txt")
    with open(script, "w") as f:
        f.write("view image\nwait-final\nset material floor diffuse 0.25 0.5 0.75\nwait-final\nprint-state\nsleep 60\n")
    marker = f"rayview-plain-{os.getpid()}"
    env = dict(os.environ, RAYVIEW_TEST_JOB=marker, XDG_STATE_HOME=state)
    # Now and then mpirun ends the window with SIGKILL at once (mpi_test.Tester.under_plain_mpirun): a run without the
    # window's message is tried again when its recovery file holds the edit (written at most 1 s after it, SIGKILL or
    # not); the message must come in one of mpi_test.MPIRUN_TRIES runs.
    for attempt in range(1, mpi_test.MPIRUN_TRIES + 1):
        shutil.rmtree(state, ignore_errors=True)
        job, text = kill_rank_one(["xvfb-run", "-a", "mpirun", "-n", "3", args.rayview, "--threads", "1", "--script",
                                   script, scene], env, marker, "plain mpirun", 60, pause=1.5)
        if job is None:
            return [text]
        kept = re.search(r"your unsaved edits are kept in (\S+\.recovery\.xml)", text)
        if "mpirun is ending the job" in text and kept and os.path.exists(kept.group(1)):
            break
        files = glob.glob(os.path.join(state, "rayview", "*.recovery.xml"))
        if attempt == mpi_test.MPIRUN_TRIES or not files or "0.25 0.5 0.75" not in pathlib.Path(files[0]).read_text():
            return [f"plain mpirun: the window should say why it closes and where the edits are:\n{text}"]
        print(f"plain mpirun: no message from the window (ended by SIGKILL?), edits kept: try {attempt + 1}")
    restore = os.path.join(args.scratch, "plain_restore.txt")
    restored = os.path.join(args.scratch, "plain_restored.xml")
    with open(restore, "w") as f:
        f.write(f"wait-final\nrecovery restore\nwait-final\nsave-scene {restored}\nquit\n")
    run = subprocess.run(["xvfb-run", "-a", args.rayview, "--threads", "1", "--script", restore, scene],
                         capture_output=True, text=True, timeout=120, env=dict(os.environ, XDG_STATE_HOME=state))
    if run.returncode != 0 or "recovery offered" not in run.stdout:
        return [f"plain mpirun: the next start should offer the edits:\n{run.stdout}\n{run.stderr}"]
    if not os.path.exists(restored) or "0.25 0.5 0.75" not in open(restored).read():
        return [f"plain mpirun: the restored scene {restored} lacks the edit"]
    return []


def kill_rank_one(command, env, marker, name, timeout, pause=0.0):
    """Starts `command` (the viewer under mpirun), reads its output up to the script's first state (the workers hold
    the geometry and trace), kills rank 1 with SIGKILL `pause` seconds later and waits for the job to end.
    Returns (job, all its output), or (None, the failure)."""
    job = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env)
    seen = []
    for line in job.stdout:
        seen.append(line)
        if line.startswith("state "):
            break
    time.sleep(pause)
    victim = job_rank(marker, 1)
    if victim is None:
        job.kill()
        return None, f"{name}: rank 1 not found:\n{''.join(seen)}"
    os.kill(victim, signal.SIGKILL)
    try:
        rest, _ = job.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        job.kill()
        return None, f"{name}: the job did not end within {timeout} s of the kill"
    return job, "".join(seen) + rest


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
