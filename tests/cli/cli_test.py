#!/usr/bin/env python3
"""The `rayview` command line as a user meets it: exit codes, output files written whole, the summary.

Usage: cli_test.py --rayview PATH --shared DIR --scratch DIR
Each check prints one line; the script exits 1 on the first failure.
"""
import argparse
import os
import shutil
import subprocess
import sys


def run(args, rayview):
    result = subprocess.run([rayview] + args, capture_output=True, text=True, timeout=300)
    print(f"  $ rayview {' '.join(args)} -> exit {result.returncode}")
    return result


def check(condition, message):
    if not condition:
        print(f"FAILED: {message}")
        sys.exit(1)
    print(f"  ok: {message}")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--rayview", required=True)
    parser.add_argument("--shared", required=True)
    parser.add_argument("--scratch", required=True)
    a = parser.parse_args()
    shutil.rmtree(a.scratch, ignore_errors=True)
    os.makedirs(a.scratch)
    scene = os.path.join(a.shared, "conformance", "ceng477", "bunny.xml")
    skeleton = os.path.join(a.shared, "handout", "skeleton_2024.xml")
    out_png = os.path.join(a.scratch, "bunny.png")

    r = run(["--version"], a.rayview)
    check(r.returncode == 0 and r.stdout.startswith("rayview "), "--version prints the version")
    r = run(["--help"], a.rayview)
    check(r.returncode == 0 and "--light-samples" in r.stdout and "exit status" in r.stdout, "--help lists the options")

    r = run(["render", scene], a.rayview)
    check(r.returncode == 2 and "-o" in r.stderr, "render without -o is a usage error (exit 2)")
    r = run(["render", scene, "-o", out_png, "--threads", "zero"], a.rayview)
    check(r.returncode == 2 and "--threads" in r.stderr and not os.path.exists(out_png),
          "a bad option value exits 2 and writes nothing")
    r = run(["render", scene, "-o", out_png, "--frobnicate"], a.rayview)
    check(r.returncode == 2 and "unknown option" in r.stderr, "an unknown option exits 2")

    r = run(["render", scene, "-o", out_png, "--threads", "2"], a.rayview)
    check(r.returncode == 0, "a good scene renders (exit 0)")
    for word in ("load", "BVH build", "render", "camera", "shadow", "reflection", "Mrays/s", "wrote"):
        check(word in r.stdout, f"the summary mentions '{word}'")
    with open(out_png, "rb") as f:
        png = f.read()
    check(png.startswith(b"\x89PNG"), "the output is a PNG")
    check(not [n for n in os.listdir(a.scratch) if ".tmp-" in n], "no temporary file is left behind")

    r = run(["render", scene, "-o", os.path.join(a.scratch, "one.png"), "--threads", "1", "--quiet"], a.rayview)
    check(r.returncode == 0 and r.stdout == "", "--quiet prints nothing on success")
    with open(os.path.join(a.scratch, "one.png"), "rb") as f:
        check(f.read() == png, "1 and 2 threads write the same bytes")

    r = run(["render", skeleton, "-o", out_png], a.rayview)
    check(r.returncode == 2 and "skeleton_2024.xml:2: error:" in r.stderr, "a bad scene exits 2 with file:line")
    with open(out_png, "rb") as f:
        check(f.read() == png, "a failed render leaves the existing output untouched")

    r = run(["render", os.path.join(a.scratch, "missing.xml"), "-o", out_png], a.rayview)
    check(r.returncode == 2 and "missing.xml" in r.stderr, "a missing scene exits 2 naming it")

    r = run(["render", scene, "-o", os.path.join(a.scratch, "no", "such", "dir", "x.png")], a.rayview)
    check(r.returncode == 1 and "cannot write" in r.stderr, "an unwritable output exits 1")

    r = run(["render", scene, "-o", os.path.join(a.scratch, "x.jpg")], a.rayview)
    check(r.returncode == 2, "an unsupported output extension exits 2")

    out_ppm = os.path.join(a.scratch, "bunny.ppm")
    r = run(["render", scene, "-o", out_ppm, "--quiet"], a.rayview)
    with open(out_ppm, "rb") as f:
        ppm = f.read()
    check(r.returncode == 0 and ppm.startswith(b"P6\n512 512\n255\n") and len(ppm) == 15 + 512 * 512 * 3,
          "PPM output is binary P6 with the whole image")

    r = run(["render", "-o", os.path.join(a.scratch, "default.png"), "--quiet"], a.rayview)
    check(r.returncode == 0 and os.path.getsize(os.path.join(a.scratch, "default.png")) > 1000,
          "without a scene, the embedded default renders")
    default_png = os.path.join(a.scratch, "default.png")
    r = run(["render", "-o", default_png], a.rayview)
    check("1 point light," in r.stdout and "1 triangular light," in r.stdout and "(1 sample)" in r.stdout,
          "the summary says '1 point light', not '1 point lights'")

    # Each command's own help; a misspelt command is named as such.
    r = run(["render", "--help"], a.rayview)
    check(r.returncode == 0 and r.stdout.startswith("usage: rayview render") and "-o " in r.stdout
          and "--script" not in r.stdout and "--out" not in r.stdout and "bench tradeoff" not in r.stdout,
          "render --help prints render's usage and only its options")
    r = run(["compare", "--help"], a.rayview)
    check(r.returncode == 0 and r.stdout.startswith("usage: rayview compare") and "--min-within1" in r.stdout
          and "--threads" not in r.stdout, "compare --help prints compare's usage and options")
    r = run(["rendr", scene], a.rayview)
    check(r.returncode == 2 and "unknown command 'rendr' (did you mean 'render'?)" in r.stderr,
          "a misspelt command is an unknown command with a suggestion")

    # compare: identical, different with and without a threshold, a difference map, bad inputs.
    r = run(["compare", out_png, os.path.join(a.scratch, "one.png")], a.rayview)
    check(r.returncode == 0 and r.stdout.strip() == "exact=100.000% within1=100.000% maxdiff=0 psnr=inf",
          "compare of identical images: 100% exact, exit 0")
    shallow = os.path.join(a.scratch, "shallow.png")
    run(["render", "-o", shallow, "--depth", "0", "--quiet"], a.rayview)
    diff = os.path.join(a.scratch, "diff.png")
    r = run(["compare", shallow, default_png, "--diff", diff], a.rayview)
    fields = dict(f.split("=") for f in r.stdout.split())
    check(r.returncode == 1 and set(fields) == {"exact", "within1", "maxdiff", "psnr"} and int(fields["maxdiff"]) > 1
          and float(fields["within1"].rstrip("%")) < 100.0, "compare of different images: the figures, exit 1")
    with open(diff, "rb") as f:
        check(f.read().startswith(b"\x89PNG"), "--diff writes a PNG")
    r = run(["compare", shallow, default_png, "--min-within1", "1"], a.rayview)
    check(r.returncode == 0, "compare within a lower --min-within1 exits 0")
    r = run(["compare", out_png, default_png], a.rayview)
    check(r.returncode == 2 and "different sizes" in r.stderr, "images of different sizes are an error (exit 2)")
    r = run(["compare", out_png, os.path.join(a.scratch, "missing.png")], a.rayview)
    check(r.returncode == 2 and "missing.png" in r.stderr, "an unreadable image exits 2 naming it")
    r = run(["compare", out_png], a.rayview)
    check(r.returncode == 2, "compare with one image is a usage error (exit 2)")
    print("cli: all checks passed")


if __name__ == "__main__":
    main()
