#!/usr/bin/env python3
"""The viewer in a real window under Xvfb (CTest label "viewer").

    viewer_test.py CASE --rayview PATH --output DIR

Cases:
  interaction  real input through xdotool: wait for the final pass, drag to orbit, Ctrl+S before and after,
               Ctrl+Shift+S ("save scene"), then `rayview render` of the saved scene equals the saved PNG (+-1)
  script       a --script: material edit, failing load (the error shows, the old scene stays), save-scene
  reload       the open file changes on disk: the viewer reloads it by itself; F5 reloads too
  screenshot   the whole window (panels and image) is captured and has both
  tradeoff     measure-tradeoff on a small scene: "tradeoff N points" (N >= 5), the plot and the panel on screen,
               then the render starts again
  hidpi        on a 192-dpi screen (content scale 2) the window, the text and the panels are twice as big
  idle-cpu     once the final pass is shown, the process uses (next to) no CPU
  no-display   without a display: exit code 1 and one line saying how to render headless
  keys         F5 after a failed open loads the asked-for file; Ctrl+O into a collapsed Scene section replaces
               the path with what is typed at once; Ctrl+S during a drag saves the final pass, not a coarse one;
               F9 hides and shows the panels
  small-window at 1000x640 the stats are one line
  undo         Ctrl+Z and Ctrl+Shift+Z undo and redo a script's material edit (images and title), a drag is one
               step, and Ctrl+Q with unsaved edits asks: Escape cancels, D discards and quits
  pick         `pick I J` names the mesh a pixel shows; a real click on the image picks, a double-click moves the
               pivot (the view turns), F then frames the picked mesh
  compare      --compare and the `compare` script command: exact=100% against `rayview render` of the scene, the
               headless figures against a modified reference; holding Space shows the reference, D the difference
               (viewer_compare_case.py)
  image-view   key 1 shows the image at 1:1 (pixels equal the headless render), the readout names the pixel under
               the cursor and its values, + zooms about the view's centre (4x4 blocks), Ctrl+wheel about the
               cursor, 0 fits (viewer_image_view_case.py)
  model        a PLY given on the command line equals `rayview render` of it; a truncated model is an error
               naming it and the model stays (viewer_model_case.py)
  display      exposure +1 by script: the image area is brighter as the mapping says, the render does not restart,
               raw saves (save-frame, Ctrl+S) equal `rayview render`, save-frame-displayed is mapped; the reference
               (Space) is mapped too, the difference (D) stays raw (viewer_display_case.py)
  saves        Ctrl+S saves the image of the moment it was pressed, not the orbit after it; with the panels
               hidden a toast shows each save's success and failure (viewer_saves_case.py)
  habits       E and Shift+E, Home, the wheel, F11, SCENE.png beside the scene, smoothing below 1:1
               (viewer_habits_case.py)
  help         F1 and ? show and hide the help over the image, Esc hides it; an orbit alone quits without asking
               (viewer_keeps_case.py)
  samples      a 16-sample render shows samples done of total and the time left (viewer_keeps_case.py)
  recovery     unsaved edits outlive kill -9 in a recovery file; the next start restores them by script and by a
               click on its panel; a save removes the file (viewer_keeps_case.py)
  ending       SIGTERM after an edit: the window and stderr say why it closes and where the edits are kept, the
               recovery file holds them, exit 143 (viewer_keeps_case.py)
  overlays     at 800x600, 1000x640 and 1280x800 the readout, a toast and the stats are apart and inside the image
               area (viewer_saves_case.py)

Each case runs itself under `xvfb-run` (skipped, exit 77, only when xvfb-run is not installed) and writes its
files under DIR/CASE. Standard library only: PNGs are decoded here with zlib.
"""

import argparse
import os
import shutil
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from viewer_compare_case import case_compare  # noqa: E402
from viewer_image_view_case import case_image_view  # noqa: E402
from viewer_display_case import case_display  # noqa: E402
from viewer_model_case import case_model  # noqa: E402
from viewer_window_view_case import case_window_view  # noqa: E402
from viewer_saves_case import case_saves, case_overlays  # noqa: E402
from viewer_habits_case import case_habits  # noqa: E402
from viewer_keeps_case import case_ending, case_help, case_recovery, case_samples  # noqa: E402
from viewer_harness import (  # noqa: E402
    run_script,
    last_generation,
    title_of,
    save_now,
    image_point,
    set_screen_dpi,
    cpu_seconds,
    Failure,
    HERE,
    IMAGE_CENTRE,
    SCENE,
    SCREEN,
    SCREENS,
    Viewer,
    copy_scene,
    expect_different,
    expect_same,
    key,
    read_png,
    render_headless,
    run_case,
    viewer_environment,
    viewer_window,
    xdotool)


def case_interaction(args, work):
    scene = copy_scene(work)
    viewer = Viewer(args.rayview, [scene, "--threads", "2"], work)
    try:
        generation = viewer.wait_final()
        window = viewer_window(viewer)

        key(window, "ctrl+s")
        before = viewer.wait_for("saved ").split(" ", 1)[1]
        expect_same(before, render_headless(args.rayview, scene, os.path.join(work, "file_camera_reference.png")))

        # Orbit: press on the image, move in steps, release (pauses so each reaches the window as it happens).
        x, y = IMAGE_CENTRE
        xdotool("mousemove", "--window", window, x, y)
        time.sleep(0.2)
        xdotool("mousedown", 1)
        for step in range(1, 13):
            time.sleep(0.05)
            xdotool("mousemove", "--window", window, x + 14 * step, y + 4 * step)
        time.sleep(0.2)
        xdotool("mouseup", 1)
        generation = viewer.wait_final(after_generation=generation)

        key(window, "ctrl+s")
        after = viewer.wait_for("saved ").split(" ", 1)[1]
        if after == before:
            raise Failure("the second Ctrl+S overwrote the first file")
        expect_different(before, after)

        key(window, "ctrl+shift+s")
        saved_scene = viewer.wait_for("saved scene ").split(" ", 2)[2]
        expect_same(after, render_headless(args.rayview, saved_scene, os.path.join(work, "orbited_reference.png")))

        key(window, "ctrl+q")
        code = viewer.finish()
        if code != 0:
            raise Failure(f"rayview exited with {code} after Ctrl+Q\n" + viewer.output())
    finally:
        viewer.kill()


def case_script(args, work):
    scene = copy_scene(work)
    other = copy_scene(work, "other.xml")
    with open(SCENE) as f:
        text = f.read()
    broken = os.path.join(work, "broken.xml")
    with open(broken, "w") as f:
        f.write(text[: len(text) * 2 // 3])  # a truncated file: an error, never a partial scene
    script = os.path.join(work, "edit.rvs")
    with open(script, "w") as f:
        f.write(f"""# material edit, failing load, saving
wait-final
save-frame {work}/before.png
set material red diffuse 0.1 0.8 0.9
set light sun intensity 9000 7000 5000
wait-final
save-frame {work}/edited.png
save-scene {work}/edited.xml
open {broken}
expect-error broken.xml:
wait-final
save-frame {work}/after_error.png
print-state
set light-samples 128
set tri-light directional
open {other}
print-state
set accel reference
wait-final
print-state
quit
""")
    viewer = run_script(args.rayview, [scene, "--threads", "2", "--script", script], work)
    print("  " + "\n  ".join(viewer.stdout))
    state = [line for line in viewer.stdout if line.startswith("state ")]
    if not state or "error=1" not in state[0] or not state[0].endswith("scene=" + scene):
        raise Failure("print-state should show the error and the first scene still open\n" + viewer.output())
    # Another scene: the light samples go back to the command line's (here the default, 1); the model stays.
    if len(state) != 3 or "light_samples=1 " not in state[1] or "tri_light=directional" not in state[1]:
        raise Failure("after opening another scene the light samples should be 1 again\n" + viewer.output())
    # The traversal shown is the back-end built, not the setting: Embree is asked for, and a scene this small
    # gets rayview's packet BVH; asking for the reference BVH rebuilds with it.
    if " traversal=packet " not in state[1] or " traversal=reference " not in state[2]:
        raise Failure("print-state should show the packet BVH built for the small scene, then the reference BVH\n" +
                      viewer.output())
    if not any("broken.xml:" in line and "error" in line for line in viewer.stderr):
        raise Failure("the located load error should also be on stderr\n" + viewer.output())
    expect_same(f"{work}/before.png", render_headless(args.rayview, scene, f"{work}/before_reference.png"), 0)
    expect_different(f"{work}/before.png", f"{work}/edited.png")
    expect_same(f"{work}/edited.png", f"{work}/after_error.png", 0)
    expect_same(f"{work}/edited.png", render_headless(args.rayview, f"{work}/edited.xml", f"{work}/edited_reference.png"))

    # A script with a mistake fails before any window opens, naming the line.
    bad = os.path.join(work, "bad.rvs")
    with open(bad, "w") as f:
        f.write("wait-final\nset material red diffuse 1 2\n")
    result = subprocess.run([args.rayview, scene, "--script", bad], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            env=viewer_environment(),
                            text=True, cwd=work)
    if result.returncode != 2 or "bad.rvs:2:" not in result.stderr:
        raise Failure(f"a bad script should fail with exit code 2 and bad.rvs:2, got {result.returncode}: {result.stderr}")
    print("  bad script: " + result.stderr.strip())

    # A failed expectation exits non-zero with the script line.
    failing = os.path.join(work, "failing.rvs")
    with open(failing, "w") as f:
        f.write("wait-final\nset material nosuch diffuse 1 1 1\nquit\n")
    result = subprocess.run([args.rayview, scene, "--script", failing], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            env=viewer_environment(),
                            text=True, cwd=work, timeout=120)
    if result.returncode != 1 or "failing.rvs:2:" not in result.stderr or "red" not in result.stderr:
        raise Failure(f"a failing script should exit 1 naming line 2 and the materials: {result.returncode}: {result.stderr}")
    print("  failing script: " + result.stderr.strip())


def case_reload(args, work):
    scene = copy_scene(work)
    viewer = Viewer(args.rayview, [scene, "--threads", "2"], work)
    try:
        viewer.wait_for("loaded ")
        generation = viewer.wait_final()
        window = viewer_window(viewer)
        key(window, "ctrl+s")
        before = viewer.wait_for("saved ").split(" ", 1)[1]

        with open(scene) as f:
            text = f.read()
        with open(scene + ".new", "w") as f:
            f.write(text.replace("<background>40 48 64</background>", "<background>200 120 40</background>"))
        time.sleep(1.1)  # a modification time the watcher can tell apart, on any file system
        os.replace(scene + ".new", scene)
        viewer.wait_for("reloading ", timeout=10)
        viewer.wait_for("loaded ")
        generation = viewer.wait_final(after_generation=generation)
        key(window, "ctrl+s")
        changed = viewer.wait_for("saved ").split(" ", 1)[1]
        expect_different(before, changed)
        expect_same(changed, render_headless(args.rayview, scene, os.path.join(work, "changed_reference.png")))

        key(window, "F5")
        viewer.wait_for("loaded ")
        viewer.wait_final(after_generation=generation)
        key(window, "ctrl+q")
        if viewer.finish() != 0:
            raise Failure("rayview did not exit cleanly\n" + viewer.output())
    finally:
        viewer.kill()


def case_keys(args, work):
    """Keys where the viewer once misbehaved: F5 after a failed open, Ctrl+O into a collapsed Scene section, Ctrl+S
    while refining, failed saves."""
    scene = os.path.join(work, "missing.xml")
    other = copy_scene(work, "other.xml")
    viewer = Viewer(args.rayview, [scene, "--threads", "2"], work)
    try:
        deadline = time.monotonic() + 30
        while not any("missing.xml" in line for line in viewer.stderr):
            if time.monotonic() > deadline:
                raise Failure("no load error for the missing file\n" + viewer.output())
            time.sleep(0.05)
        window = viewer_window(viewer)
        # The file appears; F5 loads it (not the embedded default scene).
        copy_scene(work, "missing.xml")
        key(window, "F5")
        viewer.wait_for("loaded ", accept=lambda line: line.startswith(f"loaded {scene} "))
        generation = viewer.wait_final()

        # Collapse the Scene section (its header is the panel's first line), then Ctrl+O and type at once: the
        # section opens, the field's text is selected and replaced, and no typed character is lost.
        xdotool("mousemove", "--window", window, 150, 17)
        xdotool("click", 1)
        time.sleep(0.3)
        xdotool("mousemove", "--window", window, *IMAGE_CENTRE)
        xdotool("key", "--clearmodifiers", "ctrl+o")
        xdotool("type", "--delay", "5", other)
        time.sleep(0.3)
        xdotool("key", "Return")
        viewer.wait_for("loaded ", accept=lambda line: line.startswith(f"loaded {other} "))
        generation = viewer.wait_final(after_generation=generation)
        # Ctrl+O, the path and Enter in one burst (one xdotool run): Enter comes before the field has the focus, or
        # pressed and released between two frames; either way it is not lost.
        xdotool("key", "--clearmodifiers", "ctrl+o", "type", "--delay", "0", "--args", "1", scene, "key", "Return")
        viewer.wait_for("loaded ", timeout=20, accept=lambda line: line.startswith(f"loaded {scene} "))
        generation = viewer.wait_final(after_generation=generation)

        # Ctrl+S while a drag holds the coarse preview: it waits for the final pass and saves that.
        x, y = IMAGE_CENTRE
        xdotool("mousedown", 1)
        for step in range(1, 6):
            time.sleep(0.05)
            xdotool("mousemove", "--window", window, x + 20 * step, y)
        time.sleep(0.2)
        xdotool("key", "ctrl+s")
        viewer.wait_for("saving when the final pass is ready")
        time.sleep(0.3)
        if any(line.startswith("saved ") for line in viewer.stdout):
            raise Failure("Ctrl+S saved a coarse pass during the drag\n" + viewer.output())
        xdotool("mouseup", 1)
        saved = viewer.wait_for("saved ").split(" ", 1)[1]
        key(window, "ctrl+shift+s")
        saved_scene = viewer.wait_for("saved scene ").split(" ", 2)[2]
        expect_same(saved, render_headless(args.rayview, saved_scene, os.path.join(work, "dragged_reference.png")), 0)
        # Saved to another file: the open one still lacks the orbit, so the title keeps its '*'.
        if not title_of(window).endswith(" *"):
            raise Failure(f"after saving to {saved_scene} the open file is unchanged: the title should keep '*'")

        # F9 hides the panel column and shows it again.
        key(window, "F9")
        viewer.wait_for("panels hidden")
        key(window, "F9")
        viewer.wait_for("panels shown")

        key(window, "ctrl+q")
        if viewer.finish() != 0:
            raise Failure("rayview did not exit cleanly\n" + viewer.output())
    finally:
        viewer.kill()


def case_undo(args, work):
    scene = copy_scene(work)
    script = os.path.join(work, "edit.rvs")
    with open(script, "w") as f:
        f.write(f"wait-final\nsave-frame {work}/original.png\nset material red diffuse 0.1 0.8 0.9\nwait-final\n"
                f"save-frame {work}/edited.png\nprint-state\n")
    viewer = Viewer(args.rayview, [scene, "--threads", "2", "--script", script], work)
    try:
        state = viewer.wait_for("state ")
        if " unsaved=1 undo=1 redo=0 " not in state:
            raise Failure("after one edit print-state should say unsaved=1 undo=1 redo=0: " + state)
        generation = last_generation(viewer)
        window = viewer_window(viewer)
        if not title_of(window).endswith(" *"):
            raise Failure(f"the title should end with '*' while edits are unsaved: {title_of(window)!r}")

        key(window, "ctrl+z")
        generation = viewer.wait_final(after_generation=generation)
        expect_same(save_now(viewer, window), f"{work}/original.png", 0)
        if title_of(window).endswith("*"):
            raise Failure(f"undone back to the file, the title should lose its '*': {title_of(window)!r}")
        key(window, "ctrl+shift+z")
        generation = viewer.wait_final(after_generation=generation)
        expect_same(save_now(viewer, window), f"{work}/edited.png", 0)

        # A drag of many moves is one step: one Ctrl+Z goes back to before it.
        x, y = IMAGE_CENTRE
        xdotool("mousedown", 1)
        for step in range(1, 8):
            time.sleep(0.05)
            xdotool("mousemove", "--window", window, x + 15 * step, y + 3 * step)
        time.sleep(0.2)
        xdotool("mouseup", 1)
        generation = viewer.wait_final(after_generation=generation)
        key(window, "ctrl+z")
        generation = viewer.wait_final(after_generation=generation)
        expect_same(save_now(viewer, window), f"{work}/edited.png", 0)

        # Quitting with unsaved edits asks; Escape cancels, D discards and quits.
        key(window, "ctrl+q")
        viewer.wait_for("unsaved edits: save, discard or cancel?")
        key(window, "Escape")
        viewer.wait_for("answered cancel")
        time.sleep(0.3)
        if viewer.process.poll() is not None:
            raise Failure("Cancel should keep the viewer open\n" + viewer.output())
        key(window, "ctrl+q")
        viewer.wait_for("unsaved edits: save, discard or cancel?")
        key(window, "d")
        viewer.wait_for("answered discard")
        if viewer.finish() != 0:
            raise Failure("rayview did not exit cleanly after Discard\n" + viewer.output())
    finally:
        viewer.kill()


def orange_pixels(path):
    """Pixels of the image area (right of the 400-pixel panels) in the picked mesh's outline colour (255, 150, 30)."""
    width, height, pixels = read_png(path)
    found = 0
    for y in range(height):
        for x in range(400, width):
            r, g, b = pixels[(y * width + x) * 3:(y * width + x) * 3 + 3]
            found += r > 200 and 110 < g < 190 and b < 90
    return found


def case_pick(args, work):
    scene = copy_scene(work)
    script = os.path.join(work, "pick.rvs")
    with open(script, "w") as f:
        f.write(f"wait-final\nscreenshot {work}/plain.png\npick 160 130\nwait-frames 2\nscreenshot {work}/picked.png\n"
                "pick 5 5\npick 160 130\nprint-state\n")
    viewer = Viewer(args.rayview, [scene, "--threads", "2", "--script", script], work)
    try:
        line = viewer.wait_for("picked ")
        if not line.startswith("picked mesh=box material=red triangle="):
            raise Failure("pixel (160, 130) shows the red box: " + line)
        viewer.wait_for("picked nothing")
        if " picked=box " not in viewer.wait_for("state "):
            raise Failure("print-state should name the picked mesh\n" + viewer.output())
        # The picked box is outlined in orange over the image.
        outline = {name: orange_pixels(os.path.join(work, f"{name}.png")) for name in ("plain", "picked")}
        print(f"  orange outline pixels: {outline}")
        if outline["picked"] - outline["plain"] < 100:
            raise Failure(f"no outline around the picked box: {outline}")
        generation = last_generation(viewer)
        window = viewer_window(viewer)
        # A real click on the green wedge.
        xdotool("mousemove", "--window", window, *image_point(300, 150))
        time.sleep(0.2)
        xdotool("click", 1)
        line = viewer.wait_for("picked ")
        if not line.startswith("picked mesh=wedge material=green triangle="):
            raise Failure("a click on the wedge should pick it: " + line)
        # A double-click on the box puts the pivot there: the view turns to it.
        xdotool("mousemove", "--window", window, *image_point(130, 110))
        time.sleep(0.2)
        xdotool("click", "--repeat", "2", "--delay", "80", 1)
        generation = viewer.wait_final(after_generation=generation)
        # F frames the picked box (not the whole scene): the view changes again.
        key(window, "f")
        viewer.wait_final(after_generation=generation)
        # Picks, the pivot and F only moved the view: quitting does not ask.
        key(window, "ctrl+q")
        if viewer.finish() != 0:
            raise Failure("rayview did not exit cleanly\n" + viewer.output())
    finally:
        viewer.kill()


def case_screenshot(args, work):
    shot = os.path.join(work, "viewer.png")
    script = os.path.join(work, "screenshot.rvs")
    with open(script, "w") as f:
        f.write(f"resize 1280 800\nwait-frames 3\nwait-final\nscreenshot {shot}\nquit\n")
    # The embedded default scene: what `rayview` alone shows.
    run_script(args.rayview, ["--threads", "2", "--script", script], work, "the screenshot script")
    width, height, pixels = read_png(shot)
    if (width, height) != (1280, 800):
        raise Failure(f"the screenshot is {width}x{height}, expected the 1280x800 window")

    def region_colours(x0, x1, y0, y1):
        return {pixels[(y * width + x) * 3:(y * width + x) * 3 + 3] for y in range(y0, y1, 2) for x in range(x0, x1, 2)}

    panel = region_colours(10, 390, 10, 790)
    image = region_colours(420, 1270, 150, 650)
    if len(panel) < 8:
        raise Failure(f"the panel column looks empty ({len(panel)} colours)")
    if len(image) < 200:
        raise Failure(f"the image area looks empty ({len(image)} colours)")
    if len(panel & image) > 0.5 * len(panel):
        raise Failure("the panel column and the image area look alike")
    print(f"  screenshot {shot}: {len(panel)} colours in the panels, {len(image)} in the image")
    if os.environ.get("RAYVIEW_UPDATE_DOCS_IMAGES"):
        target = os.path.join(HERE, "..", "..", "docs", "images", "viewer.png")
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(shot, target)
        print(f"  copied to {os.path.normpath(target)}")


def case_small_window(args, work):
    """At 1000x640 the stats take one line at the image's bottom right, not a box covering it."""
    shot = os.path.join(work, "small.png")
    script = os.path.join(work, "small.rvs")
    with open(script, "w") as f:
        f.write(f"resize 1000 640\nwait-frames 3\nwait-final\nscreenshot {shot}\nquit\n")
    run_script(args.rayview, ["--threads", "2", "--script", script], work, "the small-window script")
    width, height, pixels = read_png(shot)
    if (width, height) != (1000, 640):
        raise Failure(f"the screenshot is {width}x{height}, expected 1000x640")
    # The stats box's dark translucent background and text; the full box is 12 lines (about 200 pixels) high.
    # Rows above the bottom 40 pixels at the right edge must be the image's (same as a few pixels further left).
    text_rows = set()
    for y in range(height - 260, height):
        # The right edge only: the pointer (Xvfb puts it at the screen's centre) may raise a readout at the left,
        # placed above the stats line.
        row = {pixels[(y * width + x) * 3:(y * width + x) * 3 + 3] for x in range(width - 120, width - 10)}
        if b"\xff\xff\xff" in row:
            text_rows.add(y)
    if not text_rows:
        raise Failure("no stats text at the bottom right")
    if min(text_rows) < height - 40:
        raise Failure(f"the stats reach {height - min(text_rows)} pixels above the bottom: not one line")
    print(f"  {shot}: the stats take the bottom {height - min(text_rows)} pixels")


def case_tradeoff(args, work):
    scene = copy_scene(work)
    shot = os.path.join(work, "tradeoff.png")
    script = os.path.join(work, "tradeoff.rvs")
    with open(script, "w") as f:
        f.write(f"resize 1280 800\nopen {scene}\nwait-final\nmeasure-tradeoff 0.1 240\nscreenshot {shot}\n"
                "wait-final\ntradeoff-apply light-samples 4\nwait-final\nprint-state\nundo\nwait-final\n"
                "print-state\nquit\n")
    # The embedded default scene first: `open` replaces it with the small test scene.
    viewer = Viewer(args.rayview, ["--threads", "2", "--script", script], work)
    try:
        if viewer.finish(timeout=280) != 0:
            raise Failure("the tradeoff script failed\n" + viewer.output())
    finally:
        viewer.kill()
    lines = [line for line in viewer.stdout if line.startswith("tradeoff") and not line.startswith("tradeoff applied")]
    if len(lines) != 1 or len(lines[0].split()) != 3 or lines[0].split()[2] != "points":
        raise Failure("expected one 'tradeoff N points' line\n" + viewer.output())
    points = int(lines[0].split()[1])
    if points < 5:
        raise Failure(f"only {points} points measured (at least 5: the reference and the preview levels)")
    # The render starts again after the measurement: a final pass after the screenshot.
    after = viewer.stdout[viewer.stdout.index(f"screenshot {shot}"):]
    if not any(line.startswith("final pass generation") for line in after):
        raise Failure("no final pass after the measurement\n" + viewer.output())

    width, height, pixels = read_png(shot)
    if (width, height) != (1280, 800):
        raise Failure(f"the screenshot is {width}x{height}, expected the 1280x800 window")

    def region(x0, x1, y0, y1):
        return [pixels[(y * width + x) * 3:(y * width + x) * 3 + 3] for y in range(y0, y1, 2) for x in range(x0, x1, 2)]

    panel = set(region(10, 390, 10, 790))
    if len(panel) < 8:
        raise Failure(f"the panel column looks uniform ({len(panel)} colours)")
    # The plot floats over the image area: a white chart with coloured series and text.
    plot = region(430, 1260, 60, 540)
    white = sum(p == b"\xff\xff\xff" for p in plot) / len(plot)
    if white < 0.3 or len(set(plot)) < 20:
        raise Failure(f"no plot over the image ({white:.0%} white, {len(set(plot))} colours)")
    # Apply sets the row's knob as the Render panel does: a new final pass, one undo step.
    if "tradeoff applied Light samples 4" not in viewer.stdout:
        raise Failure("tradeoff-apply did not apply the row\n" + viewer.output())
    after = viewer.stdout[viewer.stdout.index("tradeoff applied Light samples 4"):]
    states = [line for line in after if line.startswith("state ")]
    if not any(line.startswith("final pass generation") for line in after) or len(states) != 2 \
            or "light_samples=4 " not in states[0] or " undo=1 redo=0 " not in states[0] \
            or "light_samples=1 " not in states[1] or " undo=0 redo=1 " not in states[1]:
        raise Failure("Apply should restart the render as one undoable edit\n" + viewer.output())
    print(f"  {points} points; screenshot {shot}: {len(panel)} colours in the panels, plot {white:.0%} white; "
          "applied Light samples 4, undone")


def case_hidpi(args, work):
    set_screen_dpi(192)
    shot = os.path.join(work, "hidpi.png")
    script = os.path.join(work, "hidpi.rvs")
    with open(script, "w") as f:
        f.write(f"wait-final\nscreenshot {shot}\nquit\n")
    run_script(args.rayview, ["--threads", "2", "--script", script], work, "the hidpi script")
    width, height, pixels = read_png(shot)
    if (width, height) != (2560, 1600):
        raise Failure(f"at content scale 2 the 1280x800 window should open at 2560x1600, not {width}x{height}")

    def pixel(x, y):
        return pixels[(y * width + x) * 3:(y * width + x) * 3 + 3]

    # The column's top padding row, above its first button: panel background out to about twice the 400-pixel
    # width (760, short of the scrollbar the column has when its panels are taller than the window), then the
    # image area. (Not a row below the last panel header: whether there is one depends on how many panels fit.)
    panel = pixel(20, 6)
    if pixel(760, 6) != panel or pixel(840, 6) == panel:
        raise Failure("the panel column should be about 800 pixels wide at content scale 2")
    print(f"  {shot}: 2560x1600, panel column about 800 pixels wide")


def case_idle_cpu(args, work):
    scene = copy_scene(work)
    viewer = Viewer(args.rayview, [scene, "--threads", "2"], work)
    try:
        viewer.wait_final()
        time.sleep(0.5)  # the frames drawn right after the final pass settle
        start, used_before = time.monotonic(), cpu_seconds(viewer.process.pid)
        time.sleep(2.0)
        used = cpu_seconds(viewer.process.pid) - used_before
        share = used / (time.monotonic() - start)
        print(f"  idle: {used * 1000:.0f} ms of CPU in 2 s ({share:.1%} of one core)")
        if share >= 0.10:
            raise Failure(f"the idle viewer used {share:.1%} of a core (at most 10% allowed)")
    finally:
        viewer.kill()


def case_anti_aliasing(args, work):
    """`set samples 6`: the viewer refines past the first full-resolution pass, one pass per sample, and its final
    pass (and save-frame) is `rayview render --samples 6` exactly; undo goes back to one sample, the course's image."""
    scene = copy_scene(work)
    script = os.path.join(work, "aa.rvs")
    with open(script, "w") as f:
        f.write(f"""wait-final
set samples 6
wait-final
print-state
save-frame {work}/aa.png
undo
wait-final
print-state
save-frame {work}/one.png
quit
""")
    viewer = run_script(args.rayview, [scene, "--threads", "2", "--script", script], work)
    state = [line for line in viewer.stdout if line.startswith("state ")]
    print("  " + "\n  ".join(state))
    if len(state) != 2 or " samples=6/6 final=1 " not in state[0] or " samples=1/1 final=1 " not in state[1]:
        raise Failure("print-state should show 6 of 6 samples, then 1 of 1 after undo\n" + viewer.output())
    expect_same(f"{work}/aa.png", render_headless(args.rayview, scene, f"{work}/aa_reference.png", ["--samples", "6"]), 0)
    expect_same(f"{work}/one.png", render_headless(args.rayview, scene, f"{work}/one_reference.png"), 0)
    expect_different(f"{work}/aa.png", f"{work}/one.png")


def case_no_display(args, work):
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    result = subprocess.run([args.rayview, SCENE], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env,
                            timeout=30)
    lines = result.stderr.strip().splitlines()
    if result.returncode != 1 or len(lines) != 1 or "no display" not in lines[0] or "rayview render" not in lines[0]:
        raise Failure(f"without a display: exit code {result.returncode}, stderr {result.stderr!r}")
    print("  " + lines[0])


CASES = {"interaction": case_interaction, "script": case_script, "reload": case_reload,
         "screenshot": case_screenshot, "tradeoff": case_tradeoff, "hidpi": case_hidpi, "idle-cpu": case_idle_cpu,
         "no-display": case_no_display, "keys": case_keys, "small-window": case_small_window,
         "undo": case_undo, "pick": case_pick, "compare": case_compare, "display": case_display,
         "image-view": case_image_view, "anti-aliasing": case_anti_aliasing, "window-view": case_window_view,
         "model": case_model, "saves": case_saves, "overlays": case_overlays, "habits": case_habits,
         "help": case_help, "samples": case_samples, "recovery": case_recovery,
         "ending": case_ending}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("case", choices=sorted(CASES))
    parser.add_argument("--rayview", required=True)
    parser.add_argument("--output", required=True)
    # The sanitizers the build has ("" for none): there a case may render less where the time buys nothing.
    parser.add_argument("--sanitizers", default="")
    args = parser.parse_args()
    args.rayview = os.path.abspath(args.rayview)

    return run_case(__file__, CASES, args, screen=SCREENS.get(args.case, SCREEN),
                    needs_display=args.case != "no-display")


if __name__ == "__main__":
    sys.exit(main())
