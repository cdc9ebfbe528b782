"""The viewer's saves and overlays in a real window (viewer_test.py cases `saves` and `overlays`).

saves: Ctrl+S pressed during a drag saves the image of that moment, never the orbit that follows it (equal to
`rayview render` of the scene Ctrl+Shift+S saved at the same moment); with the panels hidden, a save that worked
and one that failed each show a toast over the image (its colour found in screenshots).
overlays: at 800x600, 1000x640 and 1280x800, with the cursor over the image (the readout) and a toast, the overlays
the viewer places (RAYVIEW_PRINT_OVERLAYS) are inside the image area and apart; a long full-resolution pass shows its
progress bar, apart from the rest too.
"""
import os
import time

from viewer_harness import (Failure, Viewer, copy_scene, expect_different, expect_same, key, read_png,
                            render_headless, save_now, viewer_window, xdotool, IMAGE_CENTRE)

# The toast's backgrounds (ui/viewer_app_overlays.cpp), as 8-bit colours.
SAVED_COLOUR = (28, 97, 51)
FAILED_COLOUR = (153, 28, 28)
# How long the script sleeps between screenshots while the test types.
STEP_SECONDS = 1.5


def is_frame_save(line):
    return line.startswith("saved ") and not line.startswith(("saved scene ", "saved view "))


def snapshot_save(args, work):
    scene = copy_scene(work)
    viewer = Viewer(args.rayview, [scene, "--threads", "2"], work)
    try:
        window = viewer_window(viewer)
        viewer.wait_final()
        x, y = IMAGE_CENTRE
        xdotool("mousedown", 1)
        for step in range(1, 4):
            time.sleep(0.05)
            xdotool("mousemove", "--window", window, x + 20 * step, y)
        time.sleep(0.2)
        # Ctrl+S, and the scene as it is at that moment (no move in between).
        xdotool("key", "ctrl+s")
        viewer.wait_for("saving when the final pass is ready")
        xdotool("key", "ctrl+shift+s")
        pressed_scene = viewer.wait_for("saved scene ").split(" ", 2)[2]
        # The orbit goes on after the press: the save must not follow it.
        for step in range(4, 10):
            time.sleep(0.05)
            xdotool("mousemove", "--window", window, x + 20 * step, y + 5 * step)
        xdotool("mouseup", 1)
        saved = viewer.wait_for("saved ", accept=is_frame_save).split(" ", 1)[1]
        viewer.wait_final(after_generation=0)
        orbited = save_now(viewer, window)
        expect_same(saved, render_headless(args.rayview, pressed_scene, os.path.join(work, "pressed.png")), 0)
        expect_different(saved, orbited)
        key(window, "ctrl+q")  # an orbit alone is no unsaved edit: no question
        viewer.finish()
    finally:
        viewer.kill()


def colour_pixels(path, colour, rows):
    width, height, pixels = read_png(path)
    found = 0
    for y in range(min(rows, height)):
        for x in range(width):
            p = pixels[(y * width + x) * 3:(y * width + x) * 3 + 3]
            found += all(abs(p[c] - colour[c]) <= 2 for c in range(3))
    return found


def toasts(args, work):
    scene = copy_scene(work, "toast.xml")
    shots = {name: os.path.join(work, f"toast_{name}.png") for name in ("none", "ok", "fail")}
    script = os.path.join(work, "toast.rvs")
    with open(script, "w") as f:
        # Hiding the panels (F9, during the first sleep) resizes the image and starts a new render: the second
        # wait-final lets it finish, so that the Ctrl+S after the first screenshot saves at once, not when a slow
        # (sanitized, loaded) final pass ends after the next screenshot.
        f.write(f"wait-final\nprint-state\nsleep {STEP_SECONDS}\nwait-final\nscreenshot {shots['none']}\n"
                f"sleep {STEP_SECONDS}\n"
                f"screenshot {shots['ok']}\nsleep {STEP_SECONDS}\nscreenshot {shots['fail']}\nquit\n")
    # Every numbered name but the first taken before the window opens: the first Ctrl+S takes toast_001.png, the next
    # one fails. Made here, not between the two saves, where the script's sleep would race 9998 file creations.
    for n in range(2, 10000):
        open(os.path.join(work, f"toast_{n:03d}.png"), "w").close()
    viewer = Viewer(args.rayview, [scene, "--threads", "2", "--script", script], work)
    try:
        viewer.wait_for("state ")
        window = viewer_window(viewer)
        key(window, "F9")
        viewer.wait_for("panels hidden")
        viewer.wait_for(f"screenshot {shots['none']}")
        key(window, "ctrl+s")
        viewer.wait_for("saved ", accept=is_frame_save)
        viewer.wait_for(f"screenshot {shots['ok']}")
        key(window, "ctrl+s")
        deadline = time.monotonic() + 10
        while not any("not saved" in line for line in viewer.stderr):
            if time.monotonic() > deadline:
                raise Failure("the failed save printed no 'not saved'\n" + viewer.output())
            time.sleep(0.05)
        viewer.wait_for(f"screenshot {shots['fail']}")
        if viewer.finish() != 0:
            raise Failure("the toast script failed\n" + viewer.output())
    finally:
        viewer.kill()
    order = viewer.stdout
    if order.index(f"screenshot {shots['ok']}") < next(i for i, l in enumerate(order) if is_frame_save(l)):
        raise Failure("the 'ok' screenshot was taken before the save: input too slow for the script's sleeps")
    # The toast sits at the top of the image area (the whole window with the panels hidden).
    counts = {name: (colour_pixels(path, SAVED_COLOUR, 80), colour_pixels(path, FAILED_COLOUR, 80))
              for name, path in shots.items()}
    print(f"  toast pixels (saved colour, failed colour): {counts}")
    if counts["none"][0] > 50 or counts["none"][1] > 50:
        raise Failure("the toast's colours are on screen before any save")
    if counts["ok"][0] < 1000:
        raise Failure("no 'saved' toast on screen with the panels hidden")
    if counts["fail"][1] < 1000:
        raise Failure("no 'not saved' toast on screen with the panels hidden")


def case_saves(args, work):
    snapshot_save(args, work)
    toasts(args, work)


def rects(line):
    """{name: (x, y, w, h)} of an `overlays` line; 'none' left out."""
    found = {}
    for field in line.split()[2:]:
        name, _, value = field.partition("=")
        if value not in ("none", "0", "1"):
            found[name] = tuple(float(v) for v in value.split(","))
    return found


def expect_apart(line, window_width, window_height, need=("readout", "toast", "stats")):
    panel = min(400, window_width * 0.45)
    placed = rects(line)
    if any(name not in placed for name in need):
        raise Failure(f"expected {', '.join(need)}: " + line)
    for name, (x, y, w, h) in placed.items():
        if x < panel or x + w > window_width or y < 0 or y + h > window_height:
            raise Failure(f"{name} leaves the image area ({panel:.0f}..{window_width} x 0..{window_height}): {line}")
    items = list(placed.items())
    for i, (a, (ax, ay, aw, ah)) in enumerate(items):
        for b, (bx, by, bw, bh) in items[i + 1:]:
            if ax < bx + bw and bx < ax + aw and ay < by + bh and by < ay + ah:
                raise Failure(f"{a} and {b} overlap: {line}")
    print(f"  {window_width}x{window_height}: {line}")


def case_overlays(args, work):
    scene = copy_scene(work)
    sizes = [(800, 600), (1000, 640), (1280, 800)]
    script = os.path.join(work, "overlays.rvs")
    with open(script, "w") as f:
        for w, h in sizes:
            f.write(f"resize {w} {h}\nwait-frames 3\nwait-final\nprint-state\nsleep {STEP_SECONDS}\n")
        # A full-resolution pass long enough for its progress bar (shown after half a second): under a sanitizer
        # 4 light samples take 8 s, the bar shown after 1.5 s (16 took 16 s).
        samples = 4 if args.sanitizers else 16
        f.write(f"view image\nset light-samples {samples}\ncamera resolution 1600 1000\nwait-final 120\nprint-state\n"
                "quit\n")
    os.environ["RAYVIEW_PRINT_OVERLAYS"] = "1"
    os.environ["RAYVIEW_PRINT_READOUT"] = "1"
    viewer = Viewer(args.rayview, [scene, "--threads", "2", "--script", script], work)
    try:
        window = None
        for w, h in sizes:
            viewer.wait_for("state ")
            window = window or viewer_window(viewer)
            panel = min(400, w * 0.45)
            xdotool("mousemove", "--window", window, round(panel + (w - panel) / 2), round(h / 2))
            xdotool("key", "--clearmodifiers", "ctrl+s")
            viewer.wait_for("saved ", accept=is_frame_save)
            time.sleep(0.3)  # a frame or two with the toast of this save
            # The placement is printed when it changes: the last one at this size is what is on screen now.
            lines = [l for l in list(viewer.stdout) if l.startswith(f"overlays view={w - panel:.0f}x{h} ")]
            if not lines:
                raise Failure(f"no overlays line at {w}x{h}\n" + viewer.output())
            expect_apart(lines[-1], w, h)
        line = viewer.wait_for("overlays ", timeout=120, accept=lambda l: "progress=none" not in l)
        expect_apart(line, 1280, 800, need=("progress", "stats"))
        if viewer.finish(timeout=120) != 0:
            raise Failure("the overlays script failed\n" + viewer.output())
    finally:
        viewer.kill()
