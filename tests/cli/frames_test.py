#!/usr/bin/env python3
"""rayview render of several frames without MPI: a turntable (frame 0 is the plain render, the others turn), a batch
of scenes into a directory (each the plain render), a rerun that renders only the missing or broken frames,
--overwrite, and outputs that cannot name the frames."""
import argparse
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from image_files import same_content, same_file  # noqa: E402


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--rayview", required=True)
    parser.add_argument("--source", required=True)
    parser.add_argument("--scratch", required=True)
    args = parser.parse_args()
    shutil.rmtree(args.scratch, ignore_errors=True)
    os.makedirs(args.scratch)
    failures = []

    def check(ok, what):
        if not ok:
            failures.append(what)

    def render(*arguments):
        return subprocess.run([args.rayview, "render", *arguments, "--threads", "2"], capture_output=True, text=True,
                              timeout=120)

    def read(path):
        with open(path, "rb") as f:
            return f.read()

    scene = os.path.join(args.source, "scenes", "triangular_light.xml")
    textured = os.path.join(args.source, "scenes", "textured_2025.xml")
    plain = os.path.join(args.scratch, "plain.png")
    render(scene, "-o", plain, "--quiet")
    frames = os.path.join(args.scratch, "spin", "spin_%02d.png")
    names = [frames % k for k in range(4)]
    run = render(scene, "--turntable", "4", "-o", frames)
    check(run.returncode == 0 and all(os.path.exists(n) for n in names), f"turntable: {run.returncode} {run.stderr}")
    check("4 to render" in run.stdout and "frame 4 of 4 written" in run.stderr and "0 remaining" in run.stderr,
          f"turntable progress: {run.stdout} {run.stderr}")
    first = [read(n) for n in names]
    check(same_content(first[0], read(plain)), "turntable: frame 0 is not the scene's own view")
    check(len(set(first)) == 4, "turntable: frames repeat: the camera does not turn")

    # A rerun renders only what is missing or broken, and the same pixels again.
    os.remove(names[1])
    with open(names[2], "wb") as f:
        f.write(b"\x89PNG broken")
    before = os.stat(names[0]).st_mtime_ns
    run = render(scene, "--turntable", "4", "-o", frames)
    check(run.returncode == 0 and "2 complete already, 2 to render" in run.stdout, f"rerun: {run.stdout} {run.stderr}")
    check(all(same_content(read(n), f) for n, f in zip(names, first)), "rerun: frames differ from the first run")
    check(os.stat(names[0]).st_mtime_ns == before, "rerun: a complete frame was written again")
    run = render(scene, "--turntable", "4", "-o", frames, "--overwrite")
    check("0 complete already, 4 to render" in run.stdout, f"--overwrite: {run.stdout}")

    # A batch: each scene's file in the directory, the plain render's pixels.
    batch = os.path.join(args.scratch, "batch") + "/"
    run = render(scene, textured, "-o", batch)
    plain_textured = os.path.join(args.scratch, "textured.png")
    render(textured, "-o", plain_textured, "--quiet")
    check(run.returncode == 0, f"batch: {run.returncode} {run.stderr}")
    check(os.path.exists(batch + "triangular_light.png") and same_file(batch + "triangular_light.png", plain),
          "batch: triangular_light.png is not the plain render")
    check(os.path.exists(batch + "textured_2025.png") and same_file(batch + "textured_2025.png", plain_textured),
          "batch: textured_2025.png is not the plain render")

    # Outputs that cannot name the frames, and a bad scene in a batch: exit 2, nothing written.
    for arguments, what in (([scene, "--turntable", "3", "-o", os.path.join(args.scratch, "none", "spin.png")], "no %d"),
                            ([scene, textured, "-o", os.path.join(args.scratch, "none", "one.png")], "not a directory")):
        run = render(*arguments)
        check(run.returncode == 2 and "error" in run.stderr, f"{what}: {run.returncode} {run.stderr}")
        check(not os.path.exists(os.path.join(args.scratch, "none")), f"{what}: something was written")
    bad = os.path.join(args.scratch, "bad.xml")
    with open(bad, "w") as f:
        f.write("<scene>\n<camera>\n<position>0 0 oops</position>\n</camera>\n</scene>\n")
    run = render(bad, scene, "-o", os.path.join(args.scratch, "badbatch") + "/")
    check(run.returncode == 2 and "bad.xml:3" in run.stderr, f"bad scene in a batch: {run.returncode} {run.stderr}")

    for failure in failures:
        print("FAIL:", failure)
    print(f"{len(failures)} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
