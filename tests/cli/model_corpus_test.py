#!/usr/bin/env python3
"""scripts/model-corpus as the lead runs it: extract a corpus from git mirrors, render it, read the summary.

Usage: model_corpus_test.py --rayview PATH --source DIR --scratch DIR
Makes its own mirror (a git repository holding an OBJ with its MTL in a sub-folder, a broken OBJ and a
reference PNG) and its own corpus list; each check prints one line; exits 1 on the first failure,
77 (skipped) without git or ImageMagick.
"""
import argparse
import os
import shutil
import subprocess
import sys


def check(condition, message):
    if not condition:
        print(f"FAILED: {message}")
        sys.exit(1)
    print(f"  ok: {message}")


def git(repo, *args):
    return subprocess.run(["git", "-C", repo, *args], check=True, capture_output=True, text=True).stdout


def make_mirror(mirrors):
    """mirrors/tester+models/repo: a committed tetrahedron whose MTL sits beside it one folder up."""
    repo = os.path.join(mirrors, "tester+models", "repo")
    os.makedirs(os.path.join(repo, "models", "mtl"))
    with open(os.path.join(repo, "models", "tet.obj"), "w") as f:
        f.write("mtllib mtl/tet.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nusemtl red\n"
                "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")
    with open(os.path.join(repo, "models", "mtl", "tet.mtl"), "w") as f:
        f.write("newmtl red\nKd 0.8 0.1 0.1\n")
    with open(os.path.join(repo, "models", "broken.obj"), "w") as f:
        f.write("v 0 0 0\nf 1 2 3\n")
    subprocess.run(["convert", "-size", "64x48", "xc:red", os.path.join(repo, "models", "ref.png")], check=True)
    git(repo, "init", "-q")
    git(repo, "add", ".")
    git(repo, "-c", "user.name=t", "-c", "user.email=t@t", "commit", "-qm", "models")
    return git(repo, "rev-parse", "HEAD").strip()


def write_tsv(path, commit):
    rows = [["name", "format", "kinds", "repository", "commit", "path(s)", "reference"],
            ["tet", "obj", "mtl-in-subfolder", "tester/models", commit, "models/tet.obj,models/mtl/tet.mtl",
             "models/ref.png"],
            ["broken", "obj", "bad-index", "tester/models", commit, "models/broken.obj", "-"]]
    with open(path, "w") as f:
        f.write("".join("\t".join(r) + "\n" for r in rows))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--rayview", required=True)
    parser.add_argument("--source", required=True)
    parser.add_argument("--scratch", required=True)
    a = parser.parse_args()
    if not (shutil.which("git") and shutil.which("montage") and shutil.which("convert")):
        print("skipped: git and ImageMagick are needed")
        return 77
    shutil.rmtree(a.scratch, ignore_errors=True)
    s = lambda *name: os.path.join(a.scratch, *name)
    commit = make_mirror(s("mirrors"))
    write_tsv(s("corpus.tsv"), commit)
    script = [sys.executable, os.path.join(a.source, "scripts", "model-corpus"), "--tsv", s("corpus.tsv")]

    ex = subprocess.run(script + ["--extract", s("corpus"), "--mirrors", s("mirrors")], capture_output=True, text=True)
    check(ex.returncode == 0, f"--extract succeeds ({ex.stderr.strip()})")
    check(os.path.exists(s("corpus", "tet", "tet.obj")) and os.path.exists(s("corpus", "tet", "mtl", "tet.mtl")),
          "a model's files keep their layout below their common folder")
    check(os.path.exists(s("corpus", "_references", "tet.png")), "the reference lands in _references/, not beside the model")

    run = subprocess.run(script + [s("corpus"), s("out"), "--rayview", a.rayview, "--threads", "1"],
                         capture_output=True, text=True, timeout=600)
    check(run.returncode == 1, "a corpus with a refused model exits 1")
    with open(s("out", "summary.tsv")) as f:
        rows = {r[0]: r for r in (line.rstrip("\n").split("\t") for line in f)}
    tet, broken = rows["tet"], rows["broken"]
    check(tet[2] == "0" and broken[2] == "2", "the summary records each model's exit code")
    check(int(tet[7]) > 1000, "the tetrahedron covers model pixels")
    check(0 <= float(tet[4]) <= 100 and 0 < float(tet[6]) < 255, "clipped % and mean brightness are in range")
    check("broken.obj" in broken[9], "the first stderr line names the refused file")
    for name in ["contact-sheet.png", "summary.md", "gallery-rayview.png", "gallery-compare.png"]:
        check(os.path.getsize(s("out", name)) > 0, f"{name} is written")
    red = lambda name: float(subprocess.run(
        ["convert", s("out", name), "-fill", "black", "+opaque", "#FF0000", "-format", "%[fx:mean]", "info:"],
        capture_output=True, text=True).stdout)
    check(red("gallery-compare.png") > 0.01, "the comparison shows the (pure red) reference beside the render")
    check(red("gallery-rayview.png") == 0, "the gallery for the repository holds rayview's render only")
    print("model_corpus_test: all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
