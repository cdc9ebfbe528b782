"""The `compare` case of viewer_test.py, in a file of its own: comparing the render with a reference image.

A reference rendered headless by `rayview render` of the same scene is identical to the viewer's final pass; a copy
with a block changed by 128 in every channel (written as PPM) is not. Holding Space shows the reference in the image
area, D shows the false-colour difference (red where the block differs, the reference dimmed elsewhere); a wrong-size
reference and a missing one are messages naming the file, never a crash.
"""
import os
import subprocess

from viewer_harness import (
    flip_then_difference,
    Failure,
    Viewer,
    copy_scene,
    image_point,
    read_png,
    render_headless,
    viewer_environment,
    viewer_window)

# The block of the test scene's 480x300 image that the modified reference changes (columns, rows; end excluded):
# over the red box and the floor, clear of the stats (bottom right) and the view's label (above the image).
BLOCK = (100, 60, 220, 140)
INSIDE = [(110, 70), (160, 100), (215, 135)]
OUTSIDE = [(20, 20), (300, 30), (440, 60), (40, 250), (260, 200)]
# How long the script waits between its screenshots while the test holds or presses a key.
KEY_SECONDS = 3


def write_ppm(path, width, height, pixels):
    with open(path, "wb") as f:
        f.write(b"P6\n%d %d\n255\n" % (width, height) + bytes(pixels))


def pixel_of(width, pixels, column, row):
    start = (row * width + column) * 3
    return tuple(pixels[start:start + 3])


def screen_pixel(shot, column, row):
    """The screenshot's pixel showing image pixel (column, row) in the initial 1280x800 window."""
    width, _, pixels = shot
    return pixel_of(width, pixels, *image_point(column, row))


def expect_pixels(name, shot, expected):
    for (column, row), want in expected.items():
        got = screen_pixel(shot, column, row)
        if got != tuple(want):
            raise Failure(f"{name}: image pixel ({column}, {row}) shows {got}, expected {tuple(want)}")
    print(f"  {name}: {len(expected)} sampled pixels as expected")


def figures(line):
    """'compare PATH exact=... psnr=...' -> 'exact=... psnr=...'."""
    return line[line.index(" exact=") + 1:]


def case_compare(args, work):
    scene = copy_scene(work)
    reference = render_headless(args.rayview, scene, os.path.join(work, "reference.png"))
    width, height, ref = read_png(reference)
    modified_pixels = bytearray(ref)
    x0, y0, x1, y1 = BLOCK
    for y in range(y0, y1):
        for x in range(x0, x1):
            for c in range(3):
                i = (y * width + x) * 3 + c
                modified_pixels[i] = (modified_pixels[i] + 128) % 256
    modified = os.path.join(work, "modified.ppm")
    write_ppm(modified, width, height, modified_pixels)
    # What the headless command says of the viewer's final pass (identical to `reference`) against the modified one.
    result = subprocess.run([args.rayview, "compare", reference, modified], stdout=subprocess.PIPE, text=True)
    headless = result.stdout.strip()
    if result.returncode != 1:
        raise Failure(f"`rayview compare` of the modified reference should exit 1: {result.returncode} {headless}")

    shots = {name: os.path.join(work, f"{name}.png") for name in ("render", "held", "difference")}
    script = os.path.join(work, "compare.rvs")
    with open(script, "w") as f:
        f.write(f"wait-final\ncompare {reference}\ncompare {modified}\nscreenshot {shots['render']}\n"
                f"sleep {KEY_SECONDS}\nscreenshot {shots['held']}\nsleep {KEY_SECONDS}\n"
                f"screenshot {shots['difference']}\ncompare {reference}\nquit\n")
    viewer = Viewer(args.rayview, [scene, "--threads", "2", "--compare", reference, "--script", script], work)
    try:
        identical = viewer.wait_for(f"compare {reference} ")
        if figures(identical) != "exact=100.000% within1=100.000% maxdiff=0 psnr=inf":
            raise Failure("the final pass should be identical to `rayview render` of the same scene: " + identical)
        different = viewer.wait_for(f"compare {modified} ")
        if figures(different) != headless or "exact=100.000%" in different:
            raise Failure(f"against the modified reference: {different!r}; `rayview compare` says {headless!r}")

        # While the script sleeps: hold Space for the next screenshot, then release it and press D for the last.
        viewer.wait_for(f"screenshot {shots['render']}")
        window = viewer_window(viewer)
        flip_then_difference(viewer, window, shots['held'], shots['difference'], KEY_SECONDS)
        again = viewer.wait_for(f"compare {reference} ")
        if "exact=100.000%" not in again:
            raise Failure("loading the identical reference again should give exact=100%: " + again)
        if viewer.finish() != 0:
            raise Failure("the compare script failed\n" + viewer.output())
    finally:
        viewer.kill()

    # Each screenshot was taken while the view it checks was on (the keys reached the window in time).
    out = viewer.stdout
    for view, shot in (("reference", "held"), ("difference", "difference")):
        shown, taken = out.index(f"showing {view}"), out.index(f"screenshot {shots[shot]}")
        if not shown < taken or any(line.startswith("showing ") for line in out[shown + 1:taken]):
            raise Failure(f"the {view} was not on screen when {shot}.png was taken\n" + viewer.output())

    sampled = INSIDE + OUTSIDE
    original = {p: pixel_of(width, ref, *p) for p in sampled}
    expect_pixels("render.png (the render)", read_png(shots["render"]), original)
    held = {**original, **{p: pixel_of(width, modified_pixels, *p) for p in INSIDE}}
    expect_pixels("held.png (Space held: the modified reference)", read_png(shots["held"]), held)
    difference = {p: (255, 0, 0) for p in INSIDE}
    difference.update({p: tuple(v // 4 for v in pixel_of(width, modified_pixels, *p)) for p in OUTSIDE})
    expect_pixels("difference.png (D: red where they differ, the reference dimmed elsewhere)",
                  read_png(shots["difference"]), difference)

    # A reference of another size and one that cannot be read: messages naming the file, and the viewer goes on.
    small = os.path.join(work, "small.ppm")
    write_ppm(small, width // 2, height // 2, bytes(width // 2 * (height // 2) * 3))
    missing = os.path.join(work, "missing.png")
    bad = os.path.join(work, "bad.rvs")
    with open(bad, "w") as f:
        f.write(f"wait-final\nprint-state\ncompare {missing}\n")
    result = subprocess.run([args.rayview, scene, "--threads", "2", "--compare", small, "--script", bad],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=work, timeout=120,
                            env=viewer_environment())
    if f"{small} is {width // 2}x{height // 2} but the image is {width}x{height}" not in result.stderr:
        raise Failure(f"a reference of the wrong size should be refused, naming it: {result.stderr}")
    if result.returncode != 1 or f"bad.rvs:3: compare: cannot read {missing}" not in result.stderr:
        raise Failure(f"compare of a missing file should fail the script at line 3: {result.returncode}: "
                      f"{result.stderr}")
    if not any(line.startswith("state ") for line in result.stdout.splitlines()):
        raise Failure("the viewer should go on after refusing the wrong-size reference\n" + result.stdout)
    print("  wrong size and missing: " + " | ".join(result.stderr.strip().splitlines()))
