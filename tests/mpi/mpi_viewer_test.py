#!/usr/bin/env python3
"""The viewer under mpirun: `mpirun -n N rayview SCENE` opens the window on rank 0, the other ranks trace its
passes, edits reach them, the final pass is `rayview render`'s image byte for byte, and quitting ends every rank.
Needs xvfb-run and mpirun (exit 77, skipped, without them)."""
import argparse
import os
import re
import shutil
import subprocess
import sys

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
    shutil.rmtree(args.scratch, ignore_errors=True)
    os.makedirs(args.scratch)
    os.environ.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMPI_MCA_rmaps_base_oversubscribe="1")
    if os.environ.get("ASAN_OPTIONS") is not None:  # see mpi_test.py: OpenMPI's leaks cannot be suppressed by name
        os.environ["ASAN_OPTIONS"] += ":detect_leaks=0"
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


if __name__ == "__main__":
    sys.exit(main())
