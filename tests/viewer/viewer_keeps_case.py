"""What the window keeps and tells, with real keys (viewer_test.py cases `help` and `samples`).
help: F1 shows the help over the image (its screenshot differs from the image alone), `?` hides it, Esc hides it
too; orbiting alone is no unsaved edit, so Ctrl+Q quits at once without asking.
samples: a 16-sample render shows the whole render's progress: samples done of total and the time left.
"""
import os

from viewer_harness import Failure, Viewer, copy_scene, image_point, key, read_png, viewer_window, xdotool


def centre_difference(a_path, b_path):
    """Share of the pixels of the image area's middle (the help's place) that differ between two screenshots."""
    width, _, a = read_png(a_path)
    _, _, b = read_png(b_path)
    differ = total = 0
    for y in range(250, 550, 2):
        for x in range(560, 1120, 2):
            i = (y * width + x) * 3
            total += 1
            differ += a[i:i + 3] != b[i:i + 3]
    return differ / total


def case_help(args, work):
    scene = copy_scene(work)
    shots = {name: os.path.join(work, f"{name}.png") for name in ("before", "help", "after")}
    script = os.path.join(work, "help.rvs")
    with open(script, "w") as f:
        # The script takes the screenshots while the test presses the keys (each sleep leaves time for one key).
        f.write(f"wait-final\nscreenshot {shots['before']}\nprint-state\nsleep 4\nscreenshot {shots['help']}\n"
                f"print-state\nsleep 4\nscreenshot {shots['after']}\nprint-state\nsleep 30\n")
    viewer = Viewer(args.rayview, [scene, "--threads", "2", "--script", script], work)
    try:
        window = viewer_window(viewer)
        viewer.wait_for("state ")
        key(window, "F1")
        viewer.wait_for("help shown", timeout=4)
        viewer.wait_for("state ", timeout=10)
        key(window, "question")
        viewer.wait_for("help hidden", timeout=4)
        viewer.wait_for("state ", timeout=10)
        key(window, "F1")
        viewer.wait_for("help shown", timeout=4)
        key(window, "Escape")
        viewer.wait_for("help hidden", timeout=4)
        # An orbit is looking, not editing: Ctrl+Q quits without the unsaved-edits question.
        x, y = image_point(240, 150)
        xdotool("mousemove", "--window", window, x, y)
        xdotool("mousedown", 1)
        for step in range(1, 8):
            xdotool("mousemove", "--window", window, x + 15 * step, y + 4 * step)
        xdotool("mouseup", 1)
        viewer.wait_final(after_generation=1)
        key(window, "ctrl+q")
        if viewer.finish() != 0:
            raise Failure("Ctrl+Q after an orbit should quit at once\n" + viewer.output())
    finally:
        viewer.kill()
    if any(line.startswith("unsaved edits") for line in viewer.stdout):
        raise Failure("an orbit alone asked to be saved\n" + viewer.output())
    shown = centre_difference(shots["before"], shots["help"])
    gone = centre_difference(shots["before"], shots["after"])
    print(f"  the help changes {shown:.0%} of the image area's middle; after ? {gone:.0%} differs")
    if shown < 0.3:
        raise Failure(f"F1 should cover the middle of the image with the help: only {shown:.0%} of it changed")
    if gone > 0.01:
        raise Failure(f"? should hide the help again: {gone:.0%} of the middle still differs")


def case_samples(args, work):
    scene = copy_scene(work)
    script = os.path.join(work, "samples.rvs")
    with open(script, "w") as f:
        f.write("wait-final\nview image\ncamera resolution 960 600\nset light-samples 4\nset samples 16\n"
                "wait-final 120\nprint-state\nquit\n")
    os.environ["RAYVIEW_PRINT_OVERLAYS"] = "1"
    try:
        viewer = Viewer(args.rayview, [scene, "--threads", "1", "--script", script], work)
        try:
            state = viewer.wait_for("state ", timeout=120)
            if viewer.finish() != 0:
                raise Failure("the samples script failed\n" + viewer.output())
        finally:
            viewer.kill()
    finally:
        del os.environ["RAYVIEW_PRINT_OVERLAYS"]
    if " samples=16/16" not in state:
        raise Failure("the render should have ended with its 16 samples: " + state)
    shown = [line for line in viewer.stdout if line.startswith("progress samples ")]
    if not shown:
        raise Failure("a 16-sample render showed no progress of the whole render\n" + viewer.output())
    if not all("/16, " in line and "% of the render" in line for line in shown):
        raise Failure("each progress line should say the samples done of 16 and the share: " + "\n".join(shown))
    if not any(line.endswith(" left") for line in shown):
        raise Failure("the progress should say the time left: " + "\n".join(shown))
    done = [int(line.split()[2].split("/")[0]) for line in shown]
    if done != sorted(done) or done[-1] < 2:
        raise Failure(f"the samples done should count up through the render: {done}")
