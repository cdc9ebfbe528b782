"""What the window keeps and tells, with real keys (viewer_test.py cases `help` and `samples`).
help: F1 shows the help over the image (its screenshot differs from the image alone), `?` hides it, Esc hides it
too; orbiting alone is no unsaved edit, so Ctrl+Q quits at once without asking.
samples: a 16-sample render shows the whole render's progress: samples done of total and the time left.
recovery: unsaved edits outlive a kill -9 in a recovery file, and the next start restores them (script and click).
ending: SIGTERM makes the window say why it closes and where the edits are kept; exit 143.
"""
import os
import signal
import time

from viewer_harness import (Failure, Viewer, copy_scene, expect_same, image_point, key, read_png, save_now,
                            viewer_window, xdotool)


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
        # The file's 480x300: a quarter of the pixels of 960x600 (38 s under ASan, against 10 s) still takes long
        # enough for the bar to show each sample's progress and a time left.
        f.write("wait-final\nview image\nset light-samples 4\nset samples 16\nwait-final 120\nprint-state\nquit\n")
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


def recovery_files(directory):
    return sorted(os.listdir(directory)) if os.path.isdir(directory) else []


def wait_for_file(directory, seconds):
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        if recovery_files(directory):
            return os.path.join(directory, recovery_files(directory)[0])
        time.sleep(0.05)
    raise Failure(f"no recovery file in {directory} within {seconds} s of the edit")


def case_recovery(args, work):
    """Killed (kill -9) after an edit, the viewer leaves its unsaved edits in a recovery file within a few seconds;
    the next start offers them: a script restores them (`recovery restore`), is killed again, and a real click on
    the panel's Restore brings them back; the image equals the edited one, and a save removes the file."""
    scene = copy_scene(work)
    recovery = os.path.join(work, "recovery")
    os.environ["RAYVIEW_RECOVERY_DIR"] = recovery
    os.environ["RAYVIEW_PRINT_OVERLAYS"] = "1"
    edited, restored, clicked = (os.path.join(work, f"{name}.png") for name in ("edited", "restored", "clicked"))
    try:
        edit = os.path.join(work, "edit.rvs")
        with open(edit, "w") as f:
            f.write(f"wait-final\nset material red diffuse 0.1 0.2 0.9\ncamera orbit 0.3 0.1\nwait-final\n"
                    f"save-frame {edited}\nprint-state\nsleep 60\n")
        kill_after_recovery(args, scene, edit, recovery, "unsaved=1")
        with open(edit, "w") as f:
            f.write(f"wait-final\nprint-state\nrecovery restore\nwait-final\nsave-frame {restored}\nprint-state\n"
                    f"sleep 60\n")
        state = kill_after_recovery(args, scene, edit, recovery, "recovery=none")
        if " unsaved=1 " not in state:
            raise Failure("restored edits are unsaved edits: " + state)
        expect_same(restored, edited, 0)
        restore_by_click(args, scene, recovery, clicked, work)
        expect_same(clicked, edited, 0)
    finally:
        del os.environ["RAYVIEW_RECOVERY_DIR"]
        del os.environ["RAYVIEW_PRINT_OVERLAYS"]


def kill_after_recovery(args, scene, script, recovery, expect):
    """Runs the viewer on `script` until its last print-state (which must contain `expect`) and the recovery file
    holds its edits, then kills it with SIGKILL. Returns that state line."""
    viewer = Viewer(args.rayview, [scene, "--threads", "2", "--script", script], work_of(scene))
    try:
        state = viewer.wait_for("state ", timeout=60, accept=lambda line: expect in line)
        # Written at most kRecoveryInterval (1 s) after the edit; the rest is margin for a loaded machine.
        path = wait_for_file(recovery, 4)
        time.sleep(1.5)  # the file is whole whenever it exists; this lets a second write (the orbit) land too
        viewer.process.kill()
        viewer.process.wait()
    finally:
        viewer.kill()
    if not os.path.exists(path):
        raise Failure("the recovery file should outlive the killed viewer")
    print(f"  killed with its edits in {path}")
    return state


def work_of(scene):
    return os.path.dirname(scene)


def restore_by_click(args, scene, recovery, shot, work):
    viewer = Viewer(args.rayview, [scene, "--threads", "2"], work)
    try:
        viewer.wait_for("recovery offered ")
        viewer.wait_final()
        # The panel's place once it has its size (its first frame measures it).
        panel = [line for line in viewer.stdout if line.startswith("recovery panel ")][-1]
        x, y, w, h = (float(v) for v in panel.split("restore=")[1].split()[0].split(","))
        window = viewer_window(viewer)
        xdotool("mousemove", "--window", window, round(x + w / 2), round(y + h / 2))
        xdotool("click", 1)
        viewer.wait_for("recovery restored", timeout=10)
        viewer.wait_final(after_generation=1)
        saved = save_now(viewer, window)
        os.replace(saved, shot)
        # A save of the scene leaves nothing unsaved: the file goes, and Ctrl+Q does not ask.
        key(window, "ctrl+shift+s")
        viewer.wait_for("saved scene ")
        deadline = time.monotonic() + 4
        while recovery_files(recovery) and time.monotonic() < deadline:
            time.sleep(0.05)
        if recovery_files(recovery):
            raise Failure(f"a saved scene should remove its recovery file: {recovery_files(recovery)}")
        key(window, "ctrl+q")
        if viewer.finish() != 0:
            raise Failure("the viewer should quit at once after the save\n" + viewer.output())
    finally:
        viewer.kill()


def case_ending(args, work):
    """SIGTERM (kill, or mpirun ending the job after a rank died) a second after an edit: the window says why it
    closes and where the edits are (on stderr too), the recovery file holds them, the exit status is 143."""
    scene = copy_scene(work)
    recovery = os.path.join(work, "state", "rayview")
    script = os.path.join(work, "ending.rvs")
    with open(script, "w") as f:
        f.write("wait-final\nset material green diffuse 0.9 0.1 0.1\nwait-final\nprint-state\nsleep 60\n")
    os.environ["RAYVIEW_PRINT_OVERLAYS"] = "1"
    try:
        viewer = Viewer(args.rayview, [scene, "--threads", "2", "--script", script], work)
        try:
            viewer.wait_for("state ", timeout=60)
            viewer.process.send_signal(signal.SIGTERM)
            viewer.wait_for("ending shown", timeout=5)
            code = viewer.finish(timeout=5)
        finally:
            viewer.kill()
    finally:
        del os.environ["RAYVIEW_PRINT_OVERLAYS"]
    said = "\n".join(viewer.stderr)
    if code != 143:
        raise Failure(f"SIGTERM should end the viewer with 143, not {code}\n" + viewer.output())
    files = recovery_files(recovery)
    if len(files) != 1 or f"your unsaved edits are kept in {os.path.join(recovery, files[0])}" not in said:
        raise Failure(f"the viewer should say where the edits are kept ({files})\n" + viewer.output())
    if "being ended (SIGTERM)" not in said:
        raise Failure("the viewer should say it is being ended\n" + viewer.output())
