"""The `window-view` case of viewer_test.py, in a file of its own: the default view renders the image area's own
pixels, and Ctrl+S still saves the file's image.

In the initial 1280x800 window the image area is 880x800 (panels 400 wide). The viewer renders 880x800 pixels: the
test scene's 480x300 view with its near plane extended about its centre to 880:800, never cropped. The screenshot's
image area is exactly `rayview render` of the scene with that camera (computed here from the file's), at a grid of
pixels away from the stats and the readout. A real Ctrl+S saves the 480x300 image `rayview render` writes, rendered in the
background. The readout names the file's pixel under the cursor too. V (a real key) switches to the image view (480x300 rendered, print-state says so) and back; a resize
renders the new area's size.
"""
import os
import re

from viewer_harness import Failure, Viewer, copy_scene, expect_same, read_png, render_headless, viewer_window, xdotool

AREA = (400, 0, 880, 800)  # x, y, width, height of the image area in the initial window
KEY_SECONDS = 4


def extended_scene(scene, path, width, height):
    """The scene file with the window view's camera: resolution width x height, the near plane extended about its
    centre to width:height (rayview/view_camera.h), everything else as in the file."""
    with open(scene) as f:
        text = f.read()
    l, r, b, t = map(float, re.search(r"<nearplane>([^<]*)</nearplane>", text).group(1).split())
    aspect = width / height
    if aspect >= (r - l) / (t - b):
        half, centre = 0.5 * (t - b) * aspect, 0.5 * (l + r)
        l, r = centre - half, centre + half
    else:
        half, centre = 0.5 * (r - l) / aspect, 0.5 * (b + t)
        b, t = centre - half, centre + half
    text = re.sub(r"<nearplane>[^<]*</nearplane>", f"<nearplane>{l!r} {r!r} {b!r} {t!r}</nearplane>", text)
    text = re.sub(r"<imageresolution>[^<]*</imageresolution>", f"<imageresolution>{width} {height}</imageresolution>",
                  text)
    with open(path, "w") as f:
        f.write(text)
    return path


def state_field(line, name):
    return next(part.split("=", 1)[1] for part in line.split() if part.startswith(name + "="))


def case_window_view(args, work):
    scene = copy_scene(work)
    x0, y0, width, height = AREA
    window_reference = render_headless(args.rayview, extended_scene(scene, os.path.join(work, "window.xml"), width,
                                                                    height), os.path.join(work, "window_reference.png"))
    file_reference = render_headless(args.rayview, scene, os.path.join(work, "file_reference.png"))
    shot = os.path.join(work, "window.png")
    script = os.path.join(work, "window_view.rvs")
    with open(script, "w") as f:
        f.write(f"wait-final\nprint-state\nscreenshot {shot}\nsleep {3 * KEY_SECONDS}\nwait-final\nprint-state\n"
                f"sleep {KEY_SECONDS}\nwait-final\nprint-state\nresize 1000 700\nwait-final\nprint-state\nquit\n")
    os.environ["RAYVIEW_PRINT_READOUT"] = "1"
    viewer = Viewer(args.rayview, [scene, "--threads", "2", "--script", script], work)
    try:
        viewer.wait_for(f"screenshot {shot}")
        window = viewer_window(viewer)
        # The readout also names the file's pixel under the cursor: the 480x300 image spans the area's width,
        # 550 pixels high from row 125, so area pixel (440, 400) is file pixel (240, 150).
        xdotool("mousemove", "--window", window, x0 + 440, y0 + 400)
        readout = viewer.wait_for("readout pixel 440, 400:", timeout=KEY_SECONDS)
        if "(file pixel 240, 150)" not in readout:
            raise Failure(f"the window view's readout should name file pixel 240, 150: {readout!r}")
        print("  " + readout)
        # A real Ctrl+S: the file's image, rendered in the background, never the window's pixels.
        xdotool("key", "--window", window, "ctrl+s")
        saved = viewer.wait_for("saved ", timeout=2 * KEY_SECONDS).split(" ", 1)[1]
        xdotool("key", "--window", window, "v")
        viewer.wait_for("view image", timeout=KEY_SECONDS)
        viewer.wait_for("state ", timeout=4 * KEY_SECONDS, accept=lambda line: "view=image" in line)
        xdotool("key", "--window", window, "v")
        viewer.wait_for("view window", timeout=2 * KEY_SECONDS)
        code = viewer.finish(timeout=60)
    finally:
        viewer.kill()
    if code != 0:
        raise Failure(f"the script failed ({code})\n" + viewer.output())
    states = [line for line in viewer.stdout if line.startswith("state ")]
    print("  " + "\n  ".join(s[:90] + " ..." for s in states))
    if len(states) != 4:
        raise Failure("expected four print-state lines\n" + viewer.output())
    expected = [("window", f"{width}x{height}"), ("image", "480x300"), ("window", f"{width}x{height}"),
                ("window", f"600x700")]
    for line, (view, shown) in zip(states, expected):
        if state_field(line, "view") != view or state_field(line, "shown") != shown or state_field(line, "final") != "1":
            raise Failure(f"expected view={view} shown={shown} final=1 in: {line}")
        if state_field(line, "resolution") != "480x300":
            raise Failure(f"the file's resolution is not an edit of the view: {line}")

    # The screenshot's image area is the extended camera's render, pixel for pixel, away from the stats box.
    shot_width, _, shot_pixels = read_png(shot)
    ref_width, _, ref_pixels = read_png(window_reference)
    wrong = []
    checked = 0
    for j in range(1, height, 13):
        for i in range(1, width, 17):
            if (i >= width - 440 and j >= height - 240) or j >= height - 45:
                continue  # the stats box, and the pixel readout's line at the bottom (the pointer may be on the image)
            a = (((y0 + j) * shot_width) + x0 + i) * 3
            b = (j * ref_width + i) * 3
            checked += 1
            if shot_pixels[a:a + 3] != ref_pixels[b:b + 3]:
                wrong.append((i, j, tuple(shot_pixels[a:a + 3]), tuple(ref_pixels[b:b + 3])))
    if wrong:
        raise Failure(f"{len(wrong)} of {checked} image-area pixels differ from the extended camera's render, "
                      f"e.g. {wrong[:3]}")
    print(f"  window.png: {checked} image-area pixels equal rayview render of the extended 880x800 camera")
    expect_same(saved, file_reference, 0)
