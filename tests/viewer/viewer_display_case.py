"""The `display` case of viewer_test.py, in a file of its own: exposure and gamma change the image on screen, never
the render.

A script sets exposure +1 once the final pass is on screen: the image area shows every channel doubled (clamped to
255) with no new pass and no restart; save-frame and a real Ctrl+S still write exactly `rayview render`'s image,
save-frame-displayed writes the doubled one. With a reference identical to the render, Space shows it doubled too
(like and like), while the difference view (D) stays raw. Then gamma 2 saves as the mapping says.
"""
import math
import os

from viewer_harness import (
    flip_then_difference,
    Failure,
    Viewer,
    copy_scene,
    expect_same,
    key,
    read_png,
    render_headless,
    viewer_window)

# How long the script waits between its screenshots while the test holds or presses a key.
KEY_SECONDS = 3
# Image pixels compared on screen: a grid over the 480x300 image, without its bottom-right corner, where the stats
# box covers the image (the label of the reference or difference view is above the image).
GRID = [(column, row) for column in range(2, 480, 12) for row in range(2, 300, 12)
        if not (column >= 250 and row >= 160)]


def display_level(level, stops, gamma):
    """The viewer's mapping of an 8-bit level (ui/display_mapping.cpp), rounded half up as lround rounds it."""
    exposed = min(1.0, level / 255.0 * 2.0 ** stops)
    return math.floor(255.0 * exposed ** (1.0 / gamma) + 0.5)


def mapped(pixels, stops, gamma):
    table = [display_level(level, stops, gamma) for level in range(256)]
    return bytes(table[v] for v in pixels)


def image_pixel(width, pixels, column, row):
    start = (row * width + column) * 3
    return tuple(pixels[start:start + 3])


def screen_pixel(column, row):
    """The screenshot pixel whose centre is nearest the centre of image pixel (column, row), in the initial 1280x800
    window (image_point rounds to the nearest mouse position instead, which can land on a pixel's edge)."""
    scale = 880 / 480
    return math.floor(400 + (column + 0.5) * scale), math.floor((800 - 300 * scale) / 2 + (row + 0.5) * scale)


def expect_screen(name, shot_path, width, expected_pixels):
    """The screenshot shows `expected_pixels` (the 480x300 image's bytes) at every pixel of GRID."""
    shot_width, _, shot = read_png(shot_path)
    wrong = []
    for column, row in GRID:
        got = image_pixel(shot_width, shot, *screen_pixel(column, row))
        want = image_pixel(width, expected_pixels, column, row)
        if got != want:
            wrong.append(f"({column}, {row}) shows {got}, expected {want}")
    if wrong:
        raise Failure(f"{name}: {len(wrong)} of {len(GRID)} image pixels wrong, e.g. " + "; ".join(wrong[:3]))
    print(f"  {name}: {len(GRID)} image pixels as expected")


def expect_file(name, path, width, height, expected_pixels):
    file_width, file_height, pixels = read_png(path)
    if (file_width, file_height) != (width, height):
        raise Failure(f"{name}: {path} is {file_width}x{file_height}, expected {width}x{height}")
    worst = max(abs(a - b) for a, b in zip(pixels, expected_pixels))
    if worst:
        raise Failure(f"{name}: {path} differs from the expected image by up to {worst} per channel")
    print(f"  {name}: {os.path.basename(path)} as expected, every pixel")


def field(state, name):
    return next(part.split("=", 1)[1] for part in state.split() if part.startswith(name + "="))


def case_display(args, work):
    scene = copy_scene(work)
    reference = render_headless(args.rayview, scene, os.path.join(work, "reference.png"))
    width, height, raw = read_png(reference)
    brighter = mapped(raw, 1.0, 1.0)
    if brighter == raw:
        raise Failure("the test scene should have levels below 128 for exposure +1 to change")

    files = {name: os.path.join(work, f"{name}.png")
             for name in ("before", "brighter", "raw", "displayed", "held", "difference", "gamma")}
    script = os.path.join(work, "display.rvs")
    with open(script, "w") as f:
        f.write(f"""view image
wait-final
print-state
screenshot {files['before']}
set exposure 1
screenshot {files['brighter']}
print-state
save-frame {files['raw']}
save-frame-displayed {files['displayed']}
save-frame-displayed
compare {reference}
sleep {KEY_SECONDS}
screenshot {files['held']}
sleep {KEY_SECONDS}
screenshot {files['difference']}
sleep {KEY_SECONDS}
set exposure 0
set gamma 2
save-frame-displayed {files['gamma']}
print-state
quit
""")
    viewer = Viewer(args.rayview, [scene, "--threads", "2", "--script", script], work)
    try:
        # While the script sleeps: hold Space for one screenshot, press D for the next, then Ctrl+S.
        # The figures compare the raw images: exposure changes what is shown, not what is compared.
        figures = viewer.wait_for(f"compare {reference} ")
        if not figures.endswith(" exact=100.000% within1=100.000% maxdiff=0 psnr=inf"):
            raise Failure("with exposure +1 the final pass should still be identical to `rayview render`: " + figures)
        window = viewer_window(viewer)
        flip_then_difference(viewer, window, files['held'], files['difference'], KEY_SECONDS)
        key(window, "ctrl+s")  # with exposure +1 on screen and "Frame as displayed" off: raw
        saved_by_key = viewer.wait_for("saved ", timeout=KEY_SECONDS).split(" ", 1)[1]
        if viewer.finish() != 0:
            raise Failure("the display script failed\n" + viewer.output())
    finally:
        viewer.kill()
    out = viewer.stdout

    # No restart and no new pass: one final pass, and the generation before and after the exposure is the same.
    states = [line for line in out if line.startswith("state ")]
    finals = [line for line in out if line.startswith("final pass generation")]
    if len(states) != 3 or len(finals) != 1:
        raise Failure(f"expected 3 state lines and 1 final pass, got {len(states)} and {len(finals)}\n" +
                      viewer.output())
    generations = [field(state, "generation") for state in states]
    if len(set(generations)) != 1 or finals[0].split()[-1] != generations[0]:
        raise Failure(f"exposure and gamma restarted the render: generations {generations}, {finals[0]!r}")
    if [field(s, "final") for s in states] != ["1", "1", "1"]:
        raise Failure("the final pass should stay on screen through the display changes\n" + viewer.output())
    exposures = [(field(s, "exposure"), field(s, "gamma")) for s in states]
    if exposures != [("0", "1"), ("1", "1"), ("0", "2")]:
        raise Failure(f"print-state should show the exposure and gamma set: {exposures}")
    print(f"  generation {generations[0]} throughout, one final pass; exposure, gamma: {exposures}")
    # The process's memory as the stats overlay shows it, read with each pass shown: resident and its peak.
    memory = [(float(field(s, "memory_mib")), float(field(s, "peak_mib"))) for s in states]
    if not all(1.0 < resident <= peak < 1 << 20 for resident, peak in memory):
        raise Failure(f"print-state should give the viewer's resident memory and its peak in MiB: {memory}")
    print(f"  memory (MiB, resident / peak): {memory[0]}")

    # The screen: brighter as the mapping says, the reference alike under Space, the difference raw.
    expect_screen("before.png (exposure 0: the render as computed)", files["before"], width, raw)
    expect_screen("brighter.png (exposure +1: every channel doubled)", files["brighter"], width, brighter)
    expect_screen("held.png (Space: the identical reference, doubled too)", files["held"], width, brighter)
    quarter = bytes(v // 4 for v in raw)  # identical images: the reference at a quarter, not exposed
    expect_screen("difference.png (D: raw, the reference at a quarter)", files["difference"], width, quarter)

    # The files: raw saves are `rayview render`'s image (+-0), displayed saves are mapped.
    expect_same(files["raw"], reference, 0)
    expect_same(saved_by_key, reference, 0)
    if os.path.basename(saved_by_key) != "scene_001.png":
        raise Failure(f"Ctrl+S should save scene_001.png, saved {saved_by_key}")
    expect_file("save-frame-displayed, exposure +1", files["displayed"], width, height, brighter)
    numbered = os.path.join(work, "scene_displayed_001.png")
    if f"saved {numbered}" not in out:
        raise Failure(f"save-frame-displayed without a path should save {numbered}\n" + viewer.output())
    expect_file("save-frame-displayed (numbered), exposure +1", numbered, width, height, brighter)
    expect_file("save-frame-displayed, gamma 2", files["gamma"], width, height, mapped(raw, 0.0, 2.0))
