#!/usr/bin/env python3
"""The `rayview` command line as a user meets it: exit codes, output files written whole, the summary.

Usage: cli_test.py --rayview PATH --shared DIR --scratch DIR
Each check prints one line; the script exits 1 on the first failure.
"""
import argparse
import os
import re
import shutil
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from image_files import same_content, same_file  # noqa: E402


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
    # The sanitizers a build has ("" for none): under them an allocation that fails is the sanitizer's report,
    # and a limit on the address space stops the sanitizer itself from starting.
    parser.add_argument("--sanitizers", default="")
    a = parser.parse_args()
    if not os.path.isdir(os.path.join(a.shared, "conformance", "ceng477")):
        print(f"SKIPPED: needs {a.shared} (the course's scenes and images; configure with -DRAYVIEW_SHARED_DIR=PATH)")
        sys.exit(77)
    shutil.rmtree(a.scratch, ignore_errors=True)
    os.makedirs(a.scratch)
    scene = os.path.join(a.shared, "conformance", "ceng477", "bunny.xml")
    skeleton = os.path.join(a.shared, "handout", "skeleton_2024.xml")
    out_png = os.path.join(a.scratch, "bunny.png")

    r = run(["--version"], a.rayview)
    check(r.returncode == 0 and r.stdout.startswith("rayview "), "--version prints the version")
    check_one_executable(a)
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
    check_startup_line(r.stdout, "main()", "a plain start")
    check_memory_line(r.stdout, peak_of_children_kib())
    check("memory fast (estimated peak" in r.stdout, "a scene that fits renders fast, and the summary says why")
    with open(out_png, "rb") as f:
        png = f.read()
    check(png.startswith(b"\x89PNG"), "the output is a PNG")
    check(not [n for n in os.listdir(a.scratch) if ".tmp-" in n], "no temporary file is left behind")

    r = run(["render", scene, "-o", os.path.join(a.scratch, "one.png"), "--threads", "1", "--quiet"], a.rayview)
    check(r.returncode == 0 and r.stdout == "", "--quiet prints nothing on success")
    with open(os.path.join(a.scratch, "one.png"), "rb") as f:
        check(same_content(f.read(), png), "1 and 2 threads write the same image")

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
    check_output_is_never_an_input(a)
    check_interrupted_render_leaves_output(a, scene)
    default_png = os.path.join(a.scratch, "default.png")
    r = run(["render", "-o", default_png], a.rayview)
    check("1 point light," in r.stdout and "1 triangular light," in r.stdout and "light-samples 1," in r.stdout,
          "the summary says '1 point light', not '1 point lights'")

    # Each command's own help; a misspelt command is named as such.
    r = run(["render", "--help"], a.rayview)
    check(r.returncode == 0 and r.stdout.startswith("usage: rayview render") and "-o " in r.stdout
          and "--script" not in r.stdout and "--out" not in r.stdout and "bench tradeoff" not in r.stdout,
          "render --help prints render's usage and only its options")
    r = run(["compare", "--help"], a.rayview)
    check(r.returncode == 0 and r.stdout.startswith("usage: rayview compare") and "--min-within1" in r.stdout
          and "--threads" not in r.stdout, "compare --help prints compare's usage and options")
    r = run(["--help"], a.rayview)
    compare_line = [line for line in r.stdout.splitlines() if line.strip().startswith("--compare ")]
    check(r.returncode == 0 and len(compare_line) == 1 and compare_line[0].endswith("[viewer]"),
          "the viewer's --compare REF is in --help, marked [viewer]")
    r = run(["render", scene, "-o", os.path.join(a.scratch, "x.png"), "--compare", default_png], a.rayview)
    check(r.returncode == 2 and "'--compare' does not apply to 'rayview render'" in r.stderr,
          "--compare is the viewer's: 'rayview render' refuses it")
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
    check_bench_words(a, scene)
    check_inputs_are_never_replaced(a)
    check_signals_and_names(a)
    check_image_readers(a)
    check_out_of_memory_and_limits(a)
    check_compare_never_rounds_up(a)
    check_quantize_knob(a)
    check_far_scene_falls_back(a)
    check_embree_loaded_only_when_needed(a)
    check_lean_scene(a)
    check_ceng477_camera(a)
    print("cli: all checks passed")


def check_far_scene_falls_back(a):
    """A vertex beyond what Embree can represent: one warning saying why, then the reference BVH renders it."""
    far = os.path.join(a.scratch, "far.xml")
    with open(far, "w") as f:
        f.write("<scene><maxraytracedepth>0</maxraytracedepth><background>0 0 0</background>"
                "<camera><position>0 0 0</position><gaze>0 0 -1</gaze><up>0 1 0</up><nearplane>-1 1 -1 1</nearplane>"
                "<neardistance>1</neardistance><imageresolution>8 8</imageresolution></camera>"
                "<lights><ambientlight>255 255 255</ambientlight></lights>"
                "<materials><material id=\"1\"><ambient>1 1 1</ambient><diffuse>0 0 0</diffuse><specular>0 0 0</specular>"
                "<phongexponent>1</phongexponent></material></materials>"
                "<vertexdata>-1e19 -1e19 -1e19 1e19 -1e19 -1e19 0 1e19 -1e19</vertexdata>"
                "<objects><mesh id=\"1\"><materialid>1</materialid><faces>1 2 3</faces></mesh></objects></scene>\n")
    r = run(["render", far, "-o", os.path.join(a.scratch, "far.png")], a.rayview)
    warnings = [line for line in r.stderr.splitlines() if "reference BVH instead" in line]
    # Built without Embree the packet BVH takes its place, with the same range: the same warning either way.
    check(r.returncode == 0 and len(warnings) == 1 and "a vertex is 1e+19 from the camera" in warnings[0]
          and "accel reference" in r.stdout, "a scene beyond Embree's range warns once and renders with the reference BVH")


def check_embree_loaded_only_when_needed(a):
    """Embree is loaded when a scene needs it: bunny (4968 triangles) renders on the packet BVH in a process that never
    loads libembree3 (2-3 ms of start-up saved), car (6619) loads it and renders with Embree. The dynamic loader's
    own log (LD_DEBUG=files) says which libraries a process loaded."""
    version = run(["--version"], a.rayview).stdout
    if "built without Embree" in version:
        # The packet BVH takes Embree's place (availableAccel), not the reference BVH.
        car = os.path.join(a.shared, "conformance", "ceng477", "car.xml")
        r = run(["render", car, "-o", os.path.join(a.scratch, "car.png"), "--threads", "2"], a.rayview)
        check(r.returncode == 0 and "accel packet" in r.stdout, "built without Embree, car renders with the packet BVH")
        return
    # Sanitizer builds link Embree (renderer/CMakeLists.txt): nothing to check there.
    if "loaded when a scene needs it" not in version:
        return
    env = dict(os.environ, LD_DEBUG="files")
    for name, accel, loads in (("bunny", "packet", False), ("car", "embree", True)):
        scene = os.path.join(a.shared, "conformance", "ceng477", name + ".xml")
        r = subprocess.run([a.rayview, "render", scene, "-o", os.path.join(a.scratch, name + ".png"), "--threads", "2"],
                           capture_output=True, text=True, timeout=300, env=env)
        loaded = "file=libembree3" in r.stderr
        check(r.returncode == 0 and f"accel {accel}" in r.stdout and loaded == loads,
              f"{name} renders with {accel} and {'loads' if loads else 'never loads'} libembree3")
    # Where Embree cannot be loaded (here a broken file found first), the packet BVH renders the same image.
    broken = os.path.join(a.scratch, "broken-embree")
    os.makedirs(broken, exist_ok=True)
    with open(os.path.join(broken, "libembree3.so.3"), "w") as f:
        f.write("not a library\n")
    env = dict(os.environ, LD_LIBRARY_PATH=broken)
    r = subprocess.run([a.rayview, "render", os.path.join(a.shared, "conformance", "ceng477", "car.xml"), "-o",
                        os.path.join(a.scratch, "car_packet.png"), "--threads", "2"],
                       capture_output=True, text=True, timeout=300, env=env)
    warnings = [line for line in r.stderr.splitlines() if "cannot load Embree" in line]
    same = same_file(os.path.join(a.scratch, "car.png"), os.path.join(a.scratch, "car_packet.png"))
    check(r.returncode == 0 and len(warnings) == 1 and "packet BVH instead" in warnings[0] and "accel packet" in r.stdout
          and same, "without a loadable Embree, car warns once and renders the same image with the packet BVH")


def check_one_executable(a):
    """One program on the PATH: `rayview` beside nothing else but libexec/, and a viewer that cannot start is an
    error that says so, never an image written somewhere instead."""
    folder = os.path.dirname(a.rayview)
    programs = [n for n in os.listdir(folder) if os.path.isfile(os.path.join(folder, n)) and
                os.access(os.path.join(folder, n), os.X_OK)]
    check(programs == ["rayview"], f"the build's app folder holds one executable ({programs})")
    lonely = os.path.join(a.scratch, "lonely")
    os.makedirs(lonely, exist_ok=True)
    shutil.copy(a.rayview, os.path.join(lonely, "rayview"))
    r = subprocess.run([os.path.join(lonely, "rayview")], capture_output=True, text=True, timeout=60, cwd=lonely)
    check(r.returncode == 1 and "the viewer cannot start" in r.stderr and os.listdir(lonely) == ["rayview"],
          "without its viewer program, rayview says the viewer cannot start, exits 1 and writes nothing")


def check_ceng477_camera(a):
    """A course CENG477 file renders natively: --camera N picks one of its <Cameras>, giving the image of its
    conversion to the CSE 461 format byte for byte; a camera it does not have exits 2 and writes nothing."""
    folder = os.path.join(a.shared, "conformance", "ceng477")
    original = os.path.join(folder, "scienceTree_1080x1080.ceng477.xml")
    ours, theirs = os.path.join(a.scratch, "tree_c.png"), os.path.join(a.scratch, "tree.png")
    r = run(["render", original, "--camera", "2", "-o", ours, "--quiet"], a.rayview)
    check(r.returncode == 0, "a CENG477 file renders with --camera 2 (exit 0)")
    run(["render", os.path.join(folder, "scienceTree_1080x1080.xml"), "-o", theirs, "--quiet"], a.rayview)
    check(same_file(ours, theirs), "its camera 2 gives the image of its conversion, pixel for pixel")
    missing = os.path.join(a.scratch, "tree_9.png")
    r = run(["render", original, "--camera", "9", "-o", missing], a.rayview)
    check(r.returncode == 2 and "camera 9 was asked for, but <Cameras> has 3 cameras" in r.stderr
          and not os.path.exists(missing), "a camera the file does not have exits 2 and writes nothing")


def check_lean_scene(a):
    """A scene of 1e5 triangles renders fast by default (Embree), lean on request (rayview/lean_memory.h: the packet
    BVH with bigger leaves, the image deflated in bands): the same pixels either way, and as the packet BVH with
    leaves of one, to a PNG and to a PPM."""
    n = 224  # 2 * 224 * 224 = 100 352 triangles
    vertices = "\n".join(f"{i / n * 8 - 4:.6g} {0.3 * ((i * 7 + j * 13) % 5) / 5:.6g} {j / n * 8 - 4:.6g}"
                          for j in range(n + 1) for i in range(n + 1))
    faces = []
    for j in range(n):
        for i in range(n):
            v = j * (n + 1) + i + 1
            faces.append(f"{v} {v + n + 1} {v + 1}\n{v + 1} {v + n + 1} {v + n + 2}")
    lean = os.path.join(a.scratch, "lean.xml")
    with open(lean, "w") as f:
        f.write("<scene><maxraytracedepth>1</maxraytracedepth><background>10 20 30</background>"
                "<camera><position>0 3 6</position><gaze>0 -0.5 -1</gaze><up>0 1 0</up>"
                "<nearplane>-1 1 -0.75 0.75</nearplane><neardistance>1</neardistance>"
                "<imageresolution>96 72</imageresolution></camera>"
                "<lights><ambientlight>20 20 20</ambientlight><pointlight id=\"1\"><position>2 4 2</position>"
                "<intensity>6000 6000 6000</intensity></pointlight></lights>"
                "<materials><material id=\"1\"><ambient>1 1 1</ambient><diffuse>0.8 0.7 0.5</diffuse>"
                "<specular>0.3 0.3 0.3</specular><phongexponent>20</phongexponent>"
                "<mirrorreflectance>0.2 0.2 0.2</mirrorreflectance></material></materials>"
                f"<vertexdata>{vertices}</vertexdata><objects><mesh id=\"1\"><materialid>1</materialid>"
                f"<faces>{chr(10).join(faces)}</faces></mesh></objects></scene>\n")
    outputs = {}
    for name, extra, accel in (("lean.png", ["--memory", "lean"], "packet"), ("fast.png", [], "embree"),
                               ("lean_packet.png", ["--accel", "packet"], "packet"),
                               ("lean.ppm", ["--memory", "lean"], "packet")):
        outputs[name] = os.path.join(a.scratch, name)
        r = run(["render", lean, "-o", outputs[name], "--threads", "2"] + extra, a.rayview)
        if accel == "embree" and "built without Embree" in run(["--version"], a.rayview).stdout:
            accel = "packet"
        mode = "memory lean (requested)" if "lean" in extra else "memory fast ("
        check(r.returncode == 0 and "100352 triangles" in r.stdout and f"accel {accel}" in r.stdout
              and mode in r.stdout and "B/triangle" in r.stdout, f"a scene of 100 352 triangles renders to {name}")
    for other in ("fast.png", "lean_packet.png"):
        check(same_file(outputs["lean.png"], outputs[other]), f"the lean image equals {other}")
    r = run(["compare", outputs["lean.png"], outputs["lean.ppm"]], a.rayview)
    check(r.returncode == 0 and "exact=100" in r.stdout, "its PNG and its PPM hold the same pixels")


def peak_of_children_kib():
    """The largest peak resident set of any child this script has waited for (ru_maxrss, KiB): at least the
    last render's, whose process was one of them."""
    import resource
    return resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss


def check_memory_line(stdout, children_kib):
    """Memory is judged in bytes per triangle: the summary reports the process's peak memory, per triangle, and the peak
    as it stood after each stage (load, build, render, write). The stages' figures never fall, the last is the peak, the
    per-triangle figure is the peak over the scene line's triangle count, and the peak is no more than the kernel's own
    count for the process (ru_maxrss, which also covers the fork before the exec). A unit slip (KiB taken for bytes or
    bytes for KiB) fails one of these."""
    line = next((line for line in stdout.splitlines() if line.startswith("memory ")), "")
    scene = next((line for line in stdout.splitlines() if line.startswith("scene ")), "")
    m = re.match(r"memory +peak ([\d.]+) MiB, (\d+) B/triangle; peak after load ([\d.]+), BVH build ([\d.]+), "
                 r"render ([\d.]+), write ([\d.]+) MiB$", line)
    t = re.search(r": (\d+) triangles?,", scene)
    check(m is not None and t is not None, f"the summary has a memory line ({line!r})")
    peak, per_triangle = float(m.group(1)), int(m.group(2))
    stages = [float(m.group(k)) for k in range(3, 7)]
    check(stages == sorted(stages) and stages[-1] == peak and peak >= 1.0,
          f"the stages' peaks never fall and the last is the peak ({line})")
    expected = peak * 1024 * 1024 / int(t.group(1))
    check(abs(per_triangle - expected) <= 0.001 * expected + 60, "B/triangle is the peak over the triangles")
    # Within 1 MiB: the kernel adds each thread's page faults to the process's count in batches
    # (app/process_memory.h), and the line's figures are rounded to 0.1 MiB.
    check(peak * 1024 <= children_kib + 1024, f"the peak is no more than ru_maxrss ({children_kib} KiB) and 1 MiB")


def check_startup_line(stdout, origin, how):
    """Start-up (process start to the first ray, less load and build) is reported with each render, so a user can
    see the fixed cost, and the write of the image is timed: the figures are there and are durations (their size is
    bench/'s)."""
    times = next((line for line in stdout.splitlines() if line.startswith("time ")), "")
    check(", write " in times and times.endswith(" ms"), f"the summary times the write ({how})")
    line = next((line for line in stdout.splitlines() if line.startswith("start-up ")), "")
    words = line.split()
    ok = len(words) > 3 and words[2] == "ms:" and f"ms: {origin} to the first ray" in line
    check(ok and float(words[1]) >= 0.0, f"the summary reports start-up from {origin} ({how})")


def check_bench_words(a, scene):
    """`rayview bench tradeoff` calls the highest-quality image the best image: "reference" is a traversal."""
    out = os.path.join(a.scratch, "tradeoff")
    # At 1/40 (13x13): the words are checked, not the figures; at 1/10 a sanitizer build's renders are timed alone
    # and repeated, with pauses, whenever the other tests hold the cores (16 s under ASan, against 2 s).
    r = run(["bench", "tradeoff", scene, "--out", out, "--scale", "0.025", "--threads", "2"], a.rayview)
    check(r.returncode == 0, "bench tradeoff measures bunny at 1/40 (exit 0)")
    lines = [line.split() for line in r.stdout.splitlines()]
    at = next((i for i, words in enumerate(lines) if words[:2] == ["knob", "setting"]), None)
    check(at is not None and lines[at][2:6] == ["time", "ms", "x", "best"],
          "the table compares each time with the best image's ('x best')")
    rows = [words for words in lines[at + 1:] if words and not words[0].startswith("wrote")]
    check(rows and rows[0][0] == "best_image" and "accel=reference" in rows[0], "the first row is the best image")
    check(any(row[:2] == ["accel", "reference"] for row in rows), "the reference BVH keeps its knob choice name")
    check(not any(row[0] == "reference" for row in rows), "no knob row is called 'reference'")
    check("  best image: Max ray depth" in r.stdout and "Traversal reference BVH" in r.stdout
          and "  baseline: Max ray depth" in r.stdout, "the table says what the best image and the baseline are")
    with open(os.path.join(out, "tradeoff.csv")) as f:
        csv = f.read().splitlines()
    check(csv[1].startswith("bunny,best_image,") and not any(line.startswith("bunny,reference,") for line in csv)
          and any(line.startswith("bunny,accel,reference,") for line in csv),
          "the CSV's knob column: best_image for the best image, accel,reference for the back-end")


def check_output_is_never_an_input(a):
    """Never overwrite an input: `rayview render s.png -o s.png` once replaced its own input. The output is refused
    when it is the scene or its texture image by any path: the same name, ./, a symlink, a hard link."""
    d = os.path.join(a.scratch, "same")
    os.makedirs(d)
    texture = os.path.join(d, "tex.png")
    shutil.copy(os.path.join(a.scratch, "bunny.png"), texture)
    with open(os.path.join(a.shared, "conformance", "ceng477", "bunny.xml")) as f:
        xml = f.read()
    scene_png = os.path.join(d, "s.png")  # a scene file named .png: the one name that can be both
    with open(scene_png, "w") as f:
        f.write(xml.replace("</Scene>", "<textureimage>tex.png</textureimage></Scene>")
                   .replace("</scene>", "<textureimage>tex.png</textureimage></scene>"))
    os.symlink("s.png", os.path.join(d, "link.png"))
    os.link(scene_png, os.path.join(d, "hard.png"))
    os.symlink("tex.png", os.path.join(d, "texlink.png"))
    before = {n: open(os.path.join(d, n), "rb").read() for n in ("s.png", "tex.png")}
    for out in ("s.png", "./s.png", "link.png", "hard.png", os.path.join("..", "same", "s.png")):
        r = subprocess.run([a.rayview, "render", "s.png", "-o", out, "--quiet"], capture_output=True, text=True,
                           timeout=300, cwd=d)
        check(r.returncode == 2 and "is the scene file s.png" in r.stderr,
              f"-o {out} (the scene itself) exits 2 naming it: {r.stderr.strip()}")
    for out in ("tex.png", "texlink.png"):
        r = subprocess.run([a.rayview, "render", "s.png", "-o", out, "--quiet"], capture_output=True, text=True,
                           timeout=300, cwd=d)
        check(r.returncode == 2 and "is the scene's texture image" in r.stderr,
              f"-o {out} (the texture image) exits 2 naming it: {r.stderr.strip()}")
    for n, data in before.items():
        check(open(os.path.join(d, n), "rb").read() == data, f"{n} is byte-identical afterwards")
    check(not [n for n in os.listdir(d) if ".tmp-" in n], "no temporary file is left behind")


def png_bytes(width, height, rows, bit_depth=8, colour_type=2):
    """A PNG of `rows` (bytes each, filter 0 added here), no colour chunks: what a 16-bit export without gAMA is."""
    import struct
    import zlib

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xffffffff)
    header = struct.pack(">IIBBBBB", width, height, bit_depth, colour_type, 0, 0, 0)
    raw = b"".join(b"\0" + row for row in rows)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw)) +
            chunk(b"IEND", b""))


def write(path, data):
    with open(path, "wb" if isinstance(data, bytes) else "w") as f:
        f.write(data)
    return path


def read(path):
    with open(path, "rb") as f:
        return f.read()


def check_inputs_are_never_replaced(a):
    """No output replaces a file the command reads, by any path: compare's reference, a texture that did not decode."""
    d = os.path.join(a.scratch, "inputs")
    os.makedirs(os.path.join(d, "sub"))
    image = os.path.join(d, "img.png")
    run(["render", "-o", image, "--quiet"], a.rayview)
    ref = write(os.path.join(d, "ref.png"), read(image))
    for diff in (ref, "./ref.png", os.path.join("sub", "..", "ref.png"), os.path.join("..", "inputs", "ref.png")):
        r = subprocess.run([a.rayview, "compare", "img.png", "ref.png", "--diff", diff], capture_output=True, text=True,
                           timeout=60, cwd=d)
        check(r.returncode == 2 and "is the reference image" in r.stderr and r.stdout == "" and read(ref) == read(image),
              f"compare --diff {diff} (the reference) exits 2 and leaves it as it was")
    scene = write(os.path.join(d, "s.xml"), SLOW_SCENE.replace("1024 1024", "8 8").replace(
        "</scene>", "<textureimage>tex.ppm</textureimage></scene>"))
    texture = write(os.path.join(d, "tex.ppm"), b"P6\n2 2\n255\n truncated")
    for out in ("tex.ppm", "./tex.ppm", os.path.join("sub", "..", "tex.ppm")):
        r = subprocess.run([a.rayview, "render", "s.xml", "-o", out, "--quiet"], capture_output=True, text=True,
                           timeout=60, cwd=d)
        check(r.returncode == 2 and "is the scene's texture image" in r.stderr
              and read(texture) == b"P6\n2 2\n255\n truncated",
              f"render -o {out} (a texture that did not decode) exits 2 and leaves it as it was")
    check(not [n for n in os.listdir(d) if ".tmp-" in n], "no temporary file is left behind")


def check_signals_and_names(a):
    """Writes are whole or absent under every signal that ends the process, and any legal name works."""
    import resource
    d = os.path.join(a.scratch, "signals")
    os.makedirs(d)
    out = write(os.path.join(d, "out.png"), b"the previous image")
    # A file-size limit makes the kernel send SIGXFSZ in the middle of the image's write itself.
    limit = lambda: resource.setrlimit(resource.RLIMIT_FSIZE, (4096, 4096))
    r = subprocess.run([a.rayview, "render", "-o", out, "--quiet"], capture_output=True, timeout=120, preexec_fn=limit)
    check(r.returncode == 128 + signal.SIGXFSZ and read(out) == b"the previous image" and os.listdir(d) == ["out.png"],
          f"SIGXFSZ during the write exits {128 + signal.SIGXFSZ} (was {r.returncode}), the old output intact, "
          "no temporary file")
    slow = os.path.join(a.scratch, "slow.xml")
    for sig in (signal.SIGHUP, signal.SIGQUIT):
        p = subprocess.Popen([a.rayview, "render", slow, "-o", out, "--light-samples", "4096", "--threads", "1"],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        time.sleep(1.0)
        p.send_signal(sig)
        p.communicate(timeout=60)
        check(p.returncode == 128 + sig and read(out) == b"the previous image" and os.listdir(d) == ["out.png"],
              f"{sig.name} during a render exits {128 + sig}, the old output intact, no temporary file")
    for length in (241, 250, 255):
        name = os.path.join(d, "n" * (length - 4) + ".png")
        r = run(["render", "-o", name, "--quiet"], a.rayview)
        check(r.returncode == 0 and os.path.getsize(name) > 1000, f"an output name of {length} bytes is written")


def check_image_readers(a):
    """Every reader gives the values the file holds: 16-bit PNG as stored, PPM maxval scaled; truncated data refused."""
    d = os.path.join(a.scratch, "readers")
    os.makedirs(d)
    width, height = 64, 8
    rows8 = [b"".join(bytes((x * 4, y * 30, (x * y) % 256)) for x in range(width)) for y in range(height)]
    rows16 = [b"".join(bytes((v, v)) for v in row) for row in rows8]  # v * 257: the same value in 16 bits
    png8 = write(os.path.join(d, "a8.png"), png_bytes(width, height, rows8))
    png16 = write(os.path.join(d, "a16.png"), png_bytes(width, height, rows16, bit_depth=16))
    r = run(["compare", png8, png16], a.rayview)
    check(r.returncode == 0 and r.stdout.startswith("exact=100.000%"), "a 16-bit copy of an 8-bit PNG compares exact")
    ppm = write(os.path.join(d, "a.ppm"), b"P6\n%d %d\n255\n" % (width, height) + b"".join(rows8))
    ppm16 = write(os.path.join(d, "a16.ppm"), b"P6\n%d %d\n65535\n" % (width, height) + b"".join(rows16))
    r = run(["compare", ppm, ppm16], a.rayview)
    check(r.returncode == 0 and r.stdout.startswith("exact=100.000%"), "a 16-bit PPM reads as its 8-bit copy")
    white1 = write(os.path.join(d, "white1.ppm"), b"P6\n2 1\n1\n\1\1\1\1\1\1")
    white = write(os.path.join(d, "white.ppm"), b"P6\n2 1\n255\n" + b"\xff" * 6)
    r = run(["compare", white1, white], a.rayview)
    check(r.returncode == 0 and r.stdout.startswith("exact=100.000%"), "a maxval-1 white PPM reads as white")
    jpeg = os.path.join(a.shared, "peer-scenes", "aeakyuz__ray_tracer", "textures", "capsule0.jpg")
    if os.path.exists(jpeg):
        half = write(os.path.join(d, "half.jpg"), read(jpeg)[: len(read(jpeg)) // 2])
        r = run(["compare", half, half], a.rayview)
        check(r.returncode == 2 and "half.jpg" in r.stderr and r.stdout == "", "a truncated JPEG is refused (exit 2)")
    truncated = write(os.path.join(d, "cut.png"), read(png8)[:-30])
    r = run(["compare", truncated, png8], a.rayview)
    check(r.returncode == 2 and "cut.png" in r.stderr, "a truncated PNG is refused (exit 2)")


def check_out_of_memory_and_limits(a):
    """Declared sizes are checked before allocating, against one limit; an allocation that fails is a message and
    exit 3, never an abort."""
    import resource
    import struct
    import zlib
    d = os.path.join(a.scratch, "memory")
    os.makedirs(d)
    tall = write(os.path.join(d, "tall.ppm"), b"P6\n1 268435456\n255\n")
    r = run(["compare", tall, tall], a.rayview)
    check(r.returncode == 2 and "1 x 268435456 pixels is too large" in r.stderr, "a 1 x 268435456 image is refused")
    # A valid 16384 x 16384 header with too little memory to hold it: the allocation fails, cleanly.
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xffffffff)
    big = write(os.path.join(d, "big.png"), b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 16384, 16384, 8, 2, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(b"\0" * 1000)) + chunk(b"IEND", b""))
    limit = lambda: resource.setrlimit(resource.RLIMIT_AS, (600 << 20, 600 << 20))
    huge = write(os.path.join(d, "huge.xml"), SLOW_SCENE.replace("1024 1024", "16384 16384"))
    for args in [] if a.sanitizers else (["compare", big, big],
                                          ["render", huge, "-o", os.path.join(d, "huge.png"), "--quiet"]):
        r = subprocess.run([a.rayview] + args, capture_output=True, text=True, timeout=120, preexec_fn=limit)
        print(f"  $ rayview {args[0]} ... (600 MiB of address space) -> exit {r.returncode}")
        check(r.returncode == 3 and "out of memory" in r.stderr, f"{args[0]} out of memory: a message and exit 3, "
              f"not an abort ({r.stderr.strip()[-200:]})")
    check(not os.path.exists(os.path.join(d, "huge.png")), "nothing is written")
    r = run(["bench", "tradeoff", huge, "--out", os.path.join(d, "t"), "--scale", "4"], a.rayview)
    check(r.returncode == 2 and "65536 x 65536 pixels is too large" in r.stderr,
          "bench tradeoff --scale refuses a scaled image over the limit before any work")


def check_compare_never_rounds_up(a):
    """One pixel in 262 144 off by 2: 99.9996 % within 1 is printed as 99.999 %, never as the 100 % required."""
    d = os.path.join(a.scratch, "rounding")
    os.makedirs(d)
    size = 512
    zeros = bytearray(size * size * 3)
    write(os.path.join(d, "a.ppm"), b"P6\n512 512\n255\n" + bytes(zeros))
    zeros[0] = 2
    write(os.path.join(d, "b.ppm"), b"P6\n512 512\n255\n" + bytes(zeros))
    r = run(["compare", os.path.join(d, "b.ppm"), os.path.join(d, "a.ppm"), "--min-within1", "100"], a.rayview)
    check(r.returncode == 1 and "within1=99.999%" in r.stdout and "100.000" not in r.stdout + r.stderr
          and "262143 of 262144" in r.stderr, f"a failing figure never reads as the requirement met: {r.stderr.strip()}")


def check_quantize_knob(a):
    """--quantize: round (the default, images unchanged) or truncate (the 2017-2020 course references)."""
    d = os.path.join(a.scratch, "quantize")
    os.makedirs(d)
    paths = {q: os.path.join(d, q + ".ppm") for q in ("default", "round", "truncate")}
    for q, path in paths.items():
        run(["render", "-o", path, "--quiet"] + ([] if q == "default" else ["--quantize", q]), a.rayview)
    default, rounded, truncated = (read(paths[q])[15:] for q in ("default", "round", "truncate"))
    check(default == rounded, "--quantize round is the default")
    check(truncated != rounded and all(t <= r <= t + 1 for t, r in zip(truncated, rounded)),
          "--quantize truncate gives each channel the rounded value or one less")


# A quad under a triangular light at 1024 x 1024: with 4096 light samples a render takes minutes.
SLOW_SCENE = """<scene>
<maxraytracedepth>0</maxraytracedepth><background>0 0 0</background>
<camera><position>0 0 0</position><gaze>0 0 -1</gaze><up>0 1 0</up><nearplane>-1 1 -1 1</nearplane>
<neardistance>1</neardistance><imageresolution>1024 1024</imageresolution></camera>
<lights><ambientlight>0 0 0</ambientlight><triangularlight id="1"><vertex1>-1 1 -1</vertex1>
<vertex2>1 1 -1</vertex2><vertex3>0 1 -2</vertex3><intensity>100 100 100</intensity></triangularlight></lights>
<materials><material id="1"><ambient>0 0 0</ambient><diffuse>1 1 1</diffuse><specular>0 0 0</specular>
<phongexponent>1</phongexponent><mirrorreflectance>0 0 0</mirrorreflectance></material></materials>
<vertexdata>-5 -1 0 5 -1 0 5 -1 -10 -5 -1 -10</vertexdata>
<objects><mesh id="floor"><materialid>1</materialid><faces>1 2 3 1 3 4</faces></mesh></objects>
</scene>
"""


def check_interrupted_render_leaves_output(a, scene):
    """SIGINT or SIGTERM during a render: exit 130 / 143, the existing output byte-identical, no temporary
    file left in the directory."""
    d = os.path.join(a.scratch, "interrupt")
    os.makedirs(d)
    out = os.path.join(d, "out.png")
    with open(out, "wb") as f:
        f.write(b"the previous image")
    slow = os.path.join(a.scratch, "slow.xml")  # outside d: d must hold only out.png
    with open(slow, "w") as f:
        f.write(SLOW_SCENE)
    for sig, code in ((signal.SIGINT, 130), (signal.SIGTERM, 143)):
        p = subprocess.Popen([a.rayview, "render", slow, "-o", out, "--light-samples", "4096", "--threads", "1"],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        time.sleep(1.5)
        check(p.poll() is None, f"the slow render is still running after 1.5 s (before {sig.name})")
        p.send_signal(sig)
        p.wait(timeout=60)
        print(f"  $ rayview render ... then {sig.name} -> exit {p.returncode}")
        check(p.returncode == code, f"{sig.name} during the render exits {code}")
        with open(out, "rb") as f:
            check(f.read() == b"the previous image", f"after {sig.name} the old output is byte-identical")
        check(os.listdir(d) == ["out.png"], f"after {sig.name} no temporary file remains")


if __name__ == "__main__":
    main()
