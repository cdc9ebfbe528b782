"""The `image-view` case of viewer_test.py, in a file of its own: the image at 1:1, zoomed about the cursor, the
pixel readout.

Key 1 shows the 480x300 test image at 1:1 (one screen pixel per image pixel, centred in the 880x800 image area):
the screenshot's pixels are the headless render's, exactly. The readout names the pixel under the cursor and its
values (RAYVIEW_PRINT_READOUT puts it on stdout). `+` twice zooms to 4:1 about the view's centre: each image pixel
is a 4x4 block, the one under the cursor still under it; save-view writes that image area alone. Ctrl+wheel zooms
about the cursor; 0 fits again.
"""
import os

from viewer_harness import Failure, Viewer, copy_scene, read_png, render_headless, viewer_window, xdotool

KEY_SECONDS = 4
VIEW_CENTRE = (840, 400)          # of the image area in the initial 1280x800 window (panels 400 wide)
ONE_TO_ONE_ORIGIN = (600, 250)    # where image pixel (0, 0) is at 1:1: the centre less half the 480x300 image
CURSOR_PIXEL = (123, 77)          # the image pixel the readout is asked for


def pixel(shot, x, y):
    width, _, pixels = shot
    start = (y * width + x) * 3
    return tuple(pixels[start:start + 3])


def find_image(shot, ref_pixel, size, zoom, near, slack):
    """Where image pixel (0, 0)'s top-left corner is in the screenshot, for an image shown at `zoom` screen
    pixels per image pixel with nearest filtering: the position within `slack` of `near` at which every
    sampled image pixel is a zoom x zoom block of its render value. None when there is none."""
    width, height = size
    samples = [(i, j) for j in range(3, height, 23) for i in range(5, width, 29)]
    for oy in range(near[1] - slack, near[1] + slack + 1):
        for ox in range(near[0] - slack, near[0] + slack + 1):
            if all(pixel(shot, ox + zoom * i + dx, oy + zoom * j + dy) == ref_pixel(i, j)
                   for i, j in samples for dx, dy in {(0, 0), (zoom - 1, 0), (0, zoom - 1), (zoom - 1, zoom - 1)}):
                return ox, oy
    return None


def case_image_view(args, work):
    scene = copy_scene(work)
    reference = render_headless(args.rayview, scene, os.path.join(work, "reference.png"))
    width, height, ref = read_png(reference)

    def ref_pixel(i, j):
        start = (j * width + i) * 3
        return tuple(ref[start:start + 3])

    shots = {name: os.path.join(work, f"{name}.png") for name in ("one", "zoom", "view")}
    script = os.path.join(work, "image_view.rvs")
    with open(script, "w") as f:
        f.write(f"wait-final\nsleep {KEY_SECONDS}\nscreenshot {shots['one']}\nsleep {KEY_SECONDS}\n"
                f"screenshot {shots['zoom']}\nsave-view {shots['view']}\nsleep {KEY_SECONDS}\nquit\n")
    os.environ["RAYVIEW_PRINT_READOUT"] = "1"
    viewer = Viewer(args.rayview, [scene, "--threads", "2", "--script", script], work)
    try:
        viewer.wait_for("final pass generation")
        window = viewer_window(viewer)
        xdotool("key", "1")
        viewer.wait_for("image view zoom 1.000", timeout=KEY_SECONDS)
        viewer.wait_for(f"screenshot {shots['one']}", timeout=2 * KEY_SECONDS)
        # At 1:1 every pixel is the render's, centred in the image area (to a pixel: the panel column's width
        # is rounded).
        one = find_image(read_png(shots["one"]), ref_pixel, (width, height), 1, ONE_TO_ONE_ORIGIN, 2)
        if not one:
            raise Failure("one.png: the image at 1:1 is not the headless render, centred in the image area")
        print(f"  one.png: at 1:1, image pixel (0, 0) at {one}; sampled pixels equal the headless render")

        cursor = (one[0] + CURSOR_PIXEL[0], one[1] + CURSOR_PIXEL[1])
        xdotool("mousemove", "--window", window, *cursor)
        readout = viewer.wait_for("readout pixel 123, 77:", timeout=KEY_SECONDS)
        want = "readout pixel 123, 77: render %d %d %d" % ref_pixel(*CURSOR_PIXEL)
        if readout != want:
            raise Failure(f"the readout should name the pixel and its values: {readout!r}, expected {want!r}")
        # Zoom in about the view's centre, twice: 4:1.
        xdotool("mousemove", "--window", window, *VIEW_CENTRE)
        xdotool("key", "equal")
        xdotool("key", "equal")
        viewer.wait_for("image view zoom 4.000", timeout=KEY_SECONDS)
        viewer.wait_for(f"screenshot {shots['zoom']}", timeout=2 * KEY_SECONDS)
        viewer.wait_for(f"saved view {shots['view']}", timeout=KEY_SECONDS)
        # Ctrl+wheel zooms about the cursor; 0 fits again.
        xdotool("keydown", "ctrl")
        try:
            xdotool("click", "4")
        finally:
            xdotool("keyup", "ctrl")
        viewer.wait_for("image view zoom 5.000", timeout=KEY_SECONDS)
        xdotool("key", "0")
        viewer.wait_for("image view fit", timeout=KEY_SECONDS)
        if viewer.finish() != 0:
            raise Failure("the image-view script failed\n" + viewer.output())
    finally:
        viewer.kill()
        del os.environ["RAYVIEW_PRINT_READOUT"]

    # 4:1 about the view's centre: what was at the centre stays there, everything else 4 times as far from it.
    # The region checked is clear of the stats (bottom right) and the readout (bottom left).
    near = (round(VIEW_CENTRE[0] - 4 * (VIEW_CENTRE[0] - one[0])), round(VIEW_CENTRE[1] - 4 * (VIEW_CENTRE[1] - one[1])))
    zoomed = find_image(read_png(shots["zoom"]), lambda i, j: ref_pixel(i + 150, j + 100), (160, 80), 4,
                        (near[0] + 4 * 150, near[1] + 4 * 100), 8)
    if not zoomed:
        raise Failure("zoom.png: at 4:1 about the view's centre the image pixels should be 4x4 blocks of the render")
    print(f"  zoom.png: at 4:1, image pixel (150, 100) at {zoomed}; sampled pixels are 4x4 blocks of the render")

    # "Save view as seen" (save-view) of the same 4:1 view: the image area alone, 880x800, with no stats,
    # readout or label over it: render pixels as 4x4 blocks right into its corners.
    view = read_png(shots["view"])
    if view[:2] != (880, 800):
        raise Failure(f"view.png should be the 880x800 image area, not {view[:2]}")
    corner = (zoomed[0] - 400 + 4 * (130 - 150), zoomed[1] + 4 * (50 - 100))
    if find_image(view, lambda i, j: ref_pixel(i + 130, j + 50), (220, 200), 4, corner, 0) != corner:
        raise Failure("view.png: the saved view should be the image area as seen at 4:1, with nothing over it")
    print("  view.png: 880x800, the 4:1 view with nothing over it (render blocks into its corners)")
