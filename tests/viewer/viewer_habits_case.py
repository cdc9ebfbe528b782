"""Habits from other viewers, with real keys and wheel (viewer_test.py case `habits`): E and Shift+E change the
exposure, Home frames everything, the wheel dollies, F11 goes fullscreen and back, SCENE.png beside SCENE.xml fills
the Compare panel's field, and an image shown smaller than 1:1 is smoothed (blends no nearest sampling has).
"""
import os
import re

from viewer_harness import (Failure, Viewer, copy_scene, image_point, key, read_png, render_headless, viewer_window,
                            xdotool)


def field(state, name):
    return re.search(rf" {name}=(\S+)", state).group(1)


def case_habits(args, work):
    scene = copy_scene(work)
    beside = render_headless(args.rayview, scene, os.path.join(work, "scene.png"))
    small = os.path.join(work, "small.png")
    script = os.path.join(work, "habits.rvs")
    with open(script, "w") as f:
        f.write(f"wait-final\nprint-state\nsleep 6\nprint-state\nresize 600 400\nwait-frames 3\nview image\n"
                f"set exposure 0\ncamera reset\nwait-frames 3\nwait-final\nscreenshot {small}\nquit\n")
    viewer = Viewer(args.rayview, [scene, "--threads", "2", "--script", script], work)
    try:
        viewer.wait_for(f"reference beside the scene {beside}")
        before = viewer.wait_for("state ")
        window = viewer_window(viewer)
        for keys, stops in (("e", "0.5"), ("e", "1"), ("shift+e", "0.5")):
            key(window, keys)
            viewer.wait_for(f"exposure {stops}", timeout=5)
        generation = int(field(before, "generation"))
        key(window, "Home")
        generation = viewer.wait_final(after_generation=generation)
        xdotool("mousemove", "--window", window, *image_point(160, 130))
        xdotool("click", 4)  # one wheel notch up: closer
        generation = viewer.wait_final(after_generation=generation)
        key(window, "F11")
        viewer.wait_for("fullscreen on", timeout=5)
        geometry = xdotool("getwindowgeometry", window)
        if "1600x1000" not in geometry:
            raise Failure("F11 should fill the 1600x1000 screen: " + geometry)
        key(window, "F11")
        viewer.wait_for("fullscreen off", timeout=5)
        after = viewer.wait_for("state ", timeout=20)
        if viewer.finish() != 0:
            raise Failure("the habits script failed\n" + viewer.output())
    finally:
        viewer.kill()
    if field(after, "exposure") != "0.5":
        raise Failure("E, E, Shift+E should leave the exposure at 0.5 stops: " + after)
    if field(after, "position") == field(before, "position"):
        raise Failure("Home and the wheel should have moved the camera: " + after)
    smoothed_share(small, beside)


def smoothed_share(shot, render):
    """In the 600x400 window the 480x300 image is fitted into the 330x400 area at 0.69: smoothed, many of its screen
    pixels blend neighbouring pixels of the render into colours it does not have (nearest sampling has none)."""
    width, _, pixels = read_png(shot)
    _, _, rendered = read_png(render)
    colours = {rendered[i:i + 3] for i in range(0, len(rendered), 3)}
    blended = total = 0
    for y in range(110, 290):
        for x in range(280, 590):
            total += 1
            blended += pixels[(y * width + x) * 3:(y * width + x) * 3 + 3] not in colours
    share = blended / total
    print(f"  {shot}: {share:.1%} of the image's screen pixels are blends")
    if share < 0.01:  # nearest sampling gives 0 %
        raise Failure(f"the image shown at 0.69:1 is not smoothed: only {share:.1%} of its pixels are blends")
