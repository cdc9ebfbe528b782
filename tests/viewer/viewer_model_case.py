"""The `model` case of viewer_test.py, in a file of its own: the viewer opens a model (a binary PLY box) given on
the command line, its final pass equals `rayview render` of the same model; opening a truncated model shows the
error naming it and the box stays on screen; the Scene panel's Up axis (the script's `model-up z`) reads it again
as `rayview render --up z` frames it.
"""
import os
import struct

from viewer_harness import Failure, expect_different, expect_same, read_png, render_headless, run_script

BOX = [(0, 0, 0), (2, 0, 0), (2, 1, 0), (0, 1, 0), (0, 0, 1.5), (2, 0, 1.5), (2, 1, 1.5), (0, 1, 1.5)]
QUADS = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (2, 3, 7, 6), (1, 2, 6, 5), (0, 4, 7, 3)]


def write_box_ply(path):
    header = ("ply\nformat binary_little_endian 1.0\nelement vertex 8\nproperty float x\nproperty float y\n"
              "property float z\nelement face 6\nproperty list uchar int vertex_indices\nend_header\n")
    with open(path, "wb") as f:
        f.write(header.encode())
        for v in BOX:
            f.write(struct.pack("<3f", *v))
        for q in QUADS:
            f.write(struct.pack("<B4i", 4, *q))


def case_model(args, work):
    model = os.path.join(work, "box.ply")
    write_box_ply(model)
    broken = os.path.join(work, "broken.ply")
    with open(model, "rb") as f:
        data = f.read()
    with open(broken, "wb") as f:
        f.write(data[:-30])
    script = os.path.join(work, "model.rvs")
    with open(script, "w") as f:
        f.write(f"""wait-final
save-frame {work}/viewer.png
open {broken}
expect-error broken.ply:
wait-final
save-frame {work}/after_error.png
print-state
model-up z
wait-final
save-frame {work}/up_z.png
print-state
quit
""")
    viewer = run_script(args.rayview, [model, "--threads", "2", "--script", script], work)
    state = [line for line in viewer.stdout if line.startswith("state ")]
    if not state or "error=1" not in state[0] or not state[0].endswith("scene=" + model):
        raise Failure("after the broken model the error should show and the box stay open\n" + viewer.output())
    headless = render_headless(args.rayview, model, os.path.join(work, "headless.png"))
    expect_same(os.path.join(work, "viewer.png"), headless)
    expect_same(os.path.join(work, "after_error.png"), headless)
    # The Scene panel's Up axis (the script's model-up): the model read again with z up, as `render --up z` frames it.
    if len(state) < 2 or " up=0,0,1 " not in state[1]:
        raise Failure("after model-up z the camera's up should be the model's z\n" + viewer.output())
    up_z = render_headless(args.rayview, model, os.path.join(work, "headless_up_z.png"), ["--up", "z"])
    expect_same(os.path.join(work, "up_z.png"), up_z)
    expect_different(up_z, headless)
    # The box is on screen: the image is not the background alone.
    width, height, pixels = read_png(headless)
    centre = (height // 2 * width + width // 2) * 3
    background = tuple(pixels[0:3])
    if tuple(pixels[centre:centre + 3]) == background:
        raise Failure("the centre of the model's image is background")
    print(f"  the box at the centre: {tuple(pixels[centre:centre + 3])} on {background}")
