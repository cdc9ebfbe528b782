#!/usr/bin/env python3
"""Every command x every input kind x every option of opening a scene, as docs/inputs-and-options.md tables them.

The table in that doc is read here: each of its cells must have a check below and each check a cell. Under mpirun
(when mpirun is found) every run is also compared with one process's: the same exit code, the same files (images by
their pixels: tests/support/image_files.py), the same first message.

Usage: open_matrix_test.py --rayview PATH --source DIR --scratch DIR
"""
import argparse
import atexit
import base64
import json
import os
import re
import shutil
import struct
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from image_files import same_content, same_files  # noqa: E402

HANDOUT = """<scene>
  <maxraytracedepth>1</maxraytracedepth>
  <background>10 20 30</background>
  <camera><position>0 0 3</position><gaze>0 0 -1</gaze><up>0 1 0</up>
    <nearplane>-1 1 -0.75 0.75</nearplane><neardistance>1</neardistance><imageresolution>32 24</imageresolution></camera>
  <lights><ambientlight>20 20 20</ambientlight>
    <pointlight id="1"><position>1 1 3</position><intensity>900 900 900</intensity></pointlight></lights>
  <materials><material id="1"><ambient>1 1 1</ambient><diffuse>0.6 0.4 0.2</diffuse><specular>0.3 0.3 0.3</specular>
    <phongexponent>8</phongexponent><{mirror}>0.2 0.2 0.2</{mirror}></material></materials>
  <vertexdata>-1 -1 0  1 -1 0  0 1 0  -1 -1 -1</vertexdata>
  <objects><mesh id="1"><materialid>1</materialid><faces>1 2 3  1 3 4</faces></mesh></objects>
</scene>
"""

CAMERA = """<Camera id="{k}"><Position>{x} 0 3</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up>
<NearPlane>-1 1 -0.75 0.75</NearPlane><NearDistance>1</NearDistance><ImageResolution>{w} {h}</ImageResolution>
<ImageName>view{k}.png</ImageName></Camera>"""

CENG477 = """<Scene>
<BackgroundColor>5 5 5</BackgroundColor>
<MaxRecursionDepth>1</MaxRecursionDepth>
<Cameras>{cameras}</Cameras>
<Lights><AmbientLight>20 20 20</AmbientLight><PointLight id="1"><Position>0 1 3</Position>
<Intensity>900 900 900</Intensity></PointLight></Lights>
<Materials><Material id="1"><AmbientReflectance>1 1 1</AmbientReflectance><DiffuseReflectance>0.5 0.2 0.2</DiffuseReflectance>
<SpecularReflectance>0.2 0.2 0.2</SpecularReflectance><PhongExponent>10</PhongExponent></Material></Materials>
<VertexData>-1 -1 0
1 -1 0
0 1 0
</VertexData>
<Objects><Mesh id="1"><Material>1</Material><Faces>1 2 3</Faces></Mesh></Objects>
</Scene>
"""


def write_lit_gltf(path):
    """A glTF triangle with a point light of its own (KHR_lights_punctual) above it, bright enough to light it."""
    data = base64.b64encode(struct.pack("<9f", -1, -1, 0, 1, -1, 0, 0, 1, 0)).decode()
    gltf = {"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_lights_punctual"],
            "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": 10, "color": [1, 0.5, 0.2]}]}},
            "scene": 0, "scenes": [{"nodes": [0, 1]}],
            "nodes": [{"mesh": 0}, {"extensions": {"KHR_lights_punctual": {"light": 0}}, "translation": [0, 3, 3]}],
            "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
            "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [-1, -1, 0],
                           "max": [1, 1, 0]}],
            "bufferViews": [{"buffer": 0, "byteLength": 36}],
            "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64," + data}]}
    with open(path, "w") as f:
        json.dump(gltf, f)


def write_ply(path):
    """A binary PLY tetrahedron, taller along y than along z, so the up axis shows."""
    vertices = [(0, 0, 0), (1, 0, 0), (0, 2, 0), (0, 0, 0.5)]
    faces = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]
    header = ("ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
              "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n")
    with open(path, "wb") as f:
        f.write(header.encode())
        for v in vertices:
            f.write(struct.pack("<3f", *v))
        for face in faces:
            f.write(struct.pack("<B3i", 3, *face))


class Run:
    def __init__(self, code, stderr, files, out):
        self.code, self.stderr, self.files, self.out = code, stderr, files, out

    def first_message(self):
        lines = [l for l in self.stderr.splitlines() if "error" in l]
        return lines[0] if lines else ""


class Rows:
    """How each row of the table runs: arguments for one input and options; the files it wrote."""

    def __init__(self, args, inputs):
        self.args, self.inputs, self.count = args, inputs, 0
        libexec = os.path.join(os.path.dirname(args.rayview), "libexec")
        # A build without MPI or without the viewer has no row to check there.
        self.mpirun = shutil.which("mpirun") and os.path.exists(os.path.join(libexec, "rayview-mpi"))
        self.viewer = shutil.which("Xvfb") and os.path.exists(os.path.join(libexec, "rayview-viewer"))
        self.xvfb, self.display = None, None

    def shared_display(self):
        """One virtual display for the viewer's row, started at its first cell: an X server per cell (xvfb-run)
        took about a second of each of its 16 runs. -displayfd picks a free display number and tells it when ready."""
        if self.display is None:
            ready, tell = os.pipe()
            self.xvfb = subprocess.Popen(["Xvfb", "-displayfd", str(tell), "-screen", "0", "800x600x24", "-nolisten",
                                          "tcp"], pass_fds=(tell,), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            os.close(tell)
            atexit.register(self.close)  # also when a cell raises
            number = b""
            while not number.endswith(b"\n"):
                chunk = os.read(ready, 16)
                if not chunk:
                    raise RuntimeError(f"Xvfb exited ({self.xvfb.wait()}) before it named its display")
                number += chunk
            os.close(ready)
            self.display = ":" + number.decode().strip()
        return self.display

    def close(self):
        if self.xvfb is not None:
            self.xvfb.terminate()
            self.xvfb.wait()
            self.xvfb = None

    def fresh(self):
        self.count += 1
        out = os.path.join(self.args.scratch, f"run{self.count:04d}")
        os.makedirs(out)
        return out

    def execute(self, command, out, timeout=300, env=None):
        result = subprocess.run(command, capture_output=True, text=True, timeout=timeout, cwd=out, env=env)
        files = {}
        for root, _, names in os.walk(out):
            for name in names:
                if name.endswith(".rvs"):
                    continue
                with open(os.path.join(root, name), "rb") as f:
                    files[os.path.relpath(os.path.join(root, name), out)] = f.read()
        return Run(result.returncode, result.stderr, files, out)

    def render_args(self, shape, kind, options, out):
        source = self.inputs[kind]
        if shape == "image":
            return ["render", source, "-o", os.path.join(out, "image.png"), *options]
        if shape == "turntable":
            return ["render", source, "--turntable", "2", "-o", os.path.join(out, "t_%d.png"), *options]
        # A batch: two copies of the input under other names, or (a CENG477 file) its cameras.
        if kind == "CENG477 XML":
            return ["render", source, "-o", out + "/", *options]
        return ["render", self.inputs[kind + " copy"], source, "-o", out + "/", *options]

    def run(self, row, kind, options):
        out = self.fresh()
        rv = self.args.rayview
        mpi = row.startswith("`mpirun ")
        plain = row.replace("mpirun ", "")
        shape = {"`render`": "image", "`render --turntable N`": "turntable", "`render A B -o DIR/`": "batch"}.get(plain)
        if shape:
            arguments = self.render_args(shape, kind, options, out)
            if mpi:
                return self.execute(["mpirun", "-n", "2", rv, *arguments, "--threads", "1"], out, env=mpi_env())
            return self.execute([rv, *arguments, "--threads", "1"], out)
        source = self.inputs[kind]
        if row == "`bench tradeoff`":
            # Small: the cell checks what is measured, not how well. The scenes' 32x24 at a tenth; a model's
            # default 1280x720 at a fortieth (32x18), where each render is quick enough to be timed in turn: at
            # 128x72 a sanitizer build's renders are timed alone and repeated, with pauses, whenever the other
            # tests hold the cores (50 s a cell under ASan, against 3 s).
            scale = "0.025" if kind in ("model", "lit model") and "--resolution" not in options else "0.1"
            run = self.execute([rv, "bench", "tradeoff", source, "--out", out, "--quiet", "--threads", "1",
                                "--scale", scale, *options], out)
            # Times differ from run to run: keep what was rendered (knob, setting, rays).
            csv = run.files.get("tradeoff.csv", b"").decode().splitlines()
            kept = [",".join(l.split(",")[1:3] + l.split(",")[-1:]) for l in csv[1:]]
            run.files = {"rays": "\n".join(kept).encode()} if csv else {}
            return run
        if row == "`import`":
            return self.execute([rv, "import", source, "-o", os.path.join(out, "scene.xml"), *options], out)
        if row == "`export`":
            return self.execute([rv, "export", source, "-o", os.path.join(out, "model.obj"), *options], out)
        if row == "viewer":
            script = os.path.join(out, "save.rvs")
            with open(script, "w") as f:
                f.write(f"expect-no-error\nwait-final 60\nsave-frame {os.path.join(out, 'shown.png')}\nquit\n")
            # Under ASan the viewer alone gets the sanitizer runtime and Mesa's driver preloaded, as the window tests
            # give it (tests/viewer/viewer_harness.py, viewer_environment): Xvfb and xvfb-run never do.
            preload = os.environ.get("RAYVIEW_VIEWER_PRELOAD")
            viewer = ["env", "LD_PRELOAD=" + preload, rv] if preload else [rv]
            return self.execute([*viewer, source, "--script", script, "--threads", "1", *options], out, timeout=120,
                                env=dict(os.environ, DISPLAY=self.shared_display()))
        raise AssertionError(f"no runner for the row {row}")


def mpi_env():
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_rmaps_base_oversubscribe="1")
    if "ASAN_OPTIONS" in env:
        env["ASAN_OPTIONS"] += ":detect_leaks=0"
    return env


def cell_checks(rows, row):
    """Each column's check for `row`: a list of (what, ok) and the runs it made, for the mpirun comparison."""
    runs = []

    def run(kind, *options):
        r = rows.run(row, kind, list(options))
        runs.append((kind, options, r))
        return r

    # A refusal: exit 2 from the command line; the viewer shows the error and its script stops on it.
    def refused(r, text):
        return (r.code != 0 if row == "viewer" else r.code == 2) and not r.files and text in r.stderr

    renders = row.replace("mpirun ", "") in ("`render`", "`render --turntable N`", "`render A B -o DIR/`")
    export = row == "`export`"

    def opens(kind):
        r = run(kind)
        return r.code == 0 and len(r.files) > 0, f"exit {r.code}: {r.stderr[-400:]}"

    def strict():
        a, b = run("typo"), run("typo", "--strict")
        return (a.code == 0 and a.files and refused(b, "mirorreflectance"),
                f"without: exit {a.code}; with: exit {b.code} {b.stderr[-300:]}")

    def camera():
        one, two, three = run("CENG477 XML", "--camera", "1"), run("CENG477 XML", "--camera", "2"), \
            run("CENG477 XML", "--camera", "3")
        stopped = refused(three, "camera 3")
        if export:
            return one.code == 0 and two.code == 0 and stopped, f"exit {one.code} {two.code} {three.code}"
        differ = one.code == 0 and two.code == 0 and not same_files(one.files, two.files) and one.files and two.files
        if row.endswith("DIR/`"):
            differ = differ and len(two.files) == 1
        return differ and stopped, f"exit {one.code} {two.code} {three.code}: {three.stderr[-300:]}"

    def varies(*pair, kind="model"):
        a, b = run(kind, *pair[0]), run(kind, *pair[1])
        if export:
            return a.code == 0 and b.code == 0, f"exit {a.code} {b.code}"
        return (a.code == 0 and b.code == 0 and a.files and not same_files(a.files, b.files),
                f"exit {a.code} {b.code} {b.stderr[-300:]}")

    def memory():
        lean, fast = run("handout XML", "--memory", "lean"), run("handout XML", "--memory", "fast")
        if renders:
            return lean.code == 0 and lean.files and same_files(lean.files, fast.files), f"exit {lean.code} {fast.code}"
        return lean.code == 2 and "does not apply" in lean.stderr and not lean.files, f"exit {lean.code}"

    checks = {
        "handout XML": lambda: opens("handout XML"),
        "CENG477 XML": lambda: opens("CENG477 XML"),
        "model": lambda: opens("model"),
        "`--strict`": strict,
        "`--camera N`": camera,
        "`--up`": lambda: varies(["--up", "y"], ["--up", "z"]),
        "`--resolution`": lambda: varies(["--resolution", "40x30"], ["--resolution", "48x20"]),
        "`--lights`": lambda: varies(["--lights", "file"], ["--lights", "kit"], kind="lit model"),
        "`--memory`": memory,
    }
    return checks, runs


def read_table(doc):
    text = open(doc).read()
    body = text.split("<!-- matrix -->")[1].split("<!-- /matrix -->")[0].strip().splitlines()
    cells = [[c.strip() for c in line.strip().strip("|").split("|")] for line in body]
    columns = cells[0][1:]
    return columns, [r[0] for r in cells[2:]]


def make_inputs(scratch):
    inputs = {}
    for name, mirror in (("handout XML", "mirrorreflectance"), ("typo", "mirorreflectance")):
        path = os.path.join(scratch, "inputs", name.split()[0] + ".xml")
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w") as f:
            f.write(HANDOUT.replace("{mirror}", mirror))
        inputs[name] = path
    cameras = CAMERA.format(k=1, x=0, w=32, h=24) + CAMERA.format(k=2, x=0.5, w=40, h=30)
    inputs["CENG477 XML"] = os.path.join(scratch, "inputs", "course.ceng477.xml")
    with open(inputs["CENG477 XML"], "w") as f:
        f.write(CENG477.format(cameras=cameras))
    inputs["model"] = os.path.join(scratch, "inputs", "tetra.ply")
    write_ply(inputs["model"])
    inputs["lit model"] = os.path.join(scratch, "inputs", "lit.gltf")
    write_lit_gltf(inputs["lit model"])
    for kind in ("handout XML", "model", "lit model", "typo"):
        base, ext = os.path.splitext(inputs[kind])
        inputs[kind + " copy"] = base + "_copy" + ext
        shutil.copy(inputs[kind], inputs[kind + " copy"])
    return inputs


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--rayview", required=True)
    parser.add_argument("--source", required=True)
    parser.add_argument("--scratch", required=True)
    # ctest runs the viewer's row on its own (it needs the one virtual display) while the commands run beside others.
    parser.add_argument("--rows", choices=("all", "commands", "viewer"), default="all")
    # The sanitizers a build has ("" for none): the mpirun rows, comparisons with one process of code the single-process
    # rows already run, are left to the plain build there.
    parser.add_argument("--sanitizers", default="")
    args = parser.parse_args()
    shutil.rmtree(args.scratch, ignore_errors=True)
    os.makedirs(args.scratch)
    columns, table_rows = read_table(os.path.join(args.source, "docs", "inputs-and-options.md"))
    rows = Rows(args, make_inputs(args.scratch))
    failures, skipped, left = [], [], []
    singles = {}
    for row in table_rows:
        mpi = row.startswith("`mpirun ")
        if (args.rows == "viewer") != (row == "viewer") and args.rows != "all":
            left.append(row)
            continue
        if mpi and args.sanitizers:
            print(f"  left to the build without sanitizers: {row} (compared with one process there)")
            left.append(row)
            continue
        if mpi and not rows.mpirun:
            skipped.append(row)
            continue
        if row == "viewer" and not rows.viewer:
            skipped.append(row)
            continue
        checks, runs = cell_checks(rows, row)
        if sorted(checks) != sorted(columns):
            failures.append(f"the doc's columns {columns} are not the checks {sorted(checks)}")
            break
        for column in columns:
            start = len(runs)
            ok, detail = checks[column]()
            print(f"  {'ok' if ok else 'FAILED'}: {row} x {column}")
            if not ok:
                failures.append(f"{row} x {column}: {detail}")
            if mpi:
                single = singles.get((row.replace("mpirun ", ""), column), [])
                for (kind, options, m), (_, _, s) in zip(runs[start:], single):
                    same = m.code == s.code and same_files(m.files, s.files) and m.first_message() == s.first_message()
                    if not same:
                        # Both runs' folders stay in the scratch folder, named here, to compare their files.
                        names = set(m.files) | set(s.files)
                        differ = sorted(n for n in names if not same_content(m.files.get(n), s.files.get(n)))
                        failures.append(f"{row} x {column} {kind} {' '.join(options)}: mpirun exit {m.code} "
                                        f"files {sorted(m.files)} '{m.first_message()}' in {m.out}; one process "
                                        f"exit {s.code} files {sorted(s.files)} '{s.first_message()}' in {s.out}; "
                                        f"differing files {differ}")
            else:
                singles[(row, column)] = runs[start:]
    rows.close()
    for row in skipped:
        why = "mpirun or rayview's MPI program" if row.startswith("`mpirun") else "Xvfb or the viewer"
        print(f"  skipped: {row} ({why} not found in this build)")
    for failure in failures:
        print(f"FAILED: {failure}")
    if len(skipped) + len(left) == len(table_rows):
        print("SKIPPED: no row of the table can run in this build")
        return 77
    total = (len(table_rows) - len(left)) * len(columns)
    print(f"{total - len(skipped) * len(columns) - len(failures)} passed, {len(failures)} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
