#!/usr/bin/env python3
"""Writes the OBJ files behind docs/dependencies.md's OBJ figures, to time `rayview render` on them.

    bench/obj_files.py materials DIR [N]   DIR/m.obj + m.mtl: N materials (default 100000), one `usemtl` and face each
    bench/obj_files.py groups DIR [N]      DIR/g.obj: N groups (default 100000), one `g` line and face each
    bench/obj_files.py grid DIR [SIDE]     DIR/big.obj: a bumpy grid of SIDE x SIDE quads (default 707: 999 698 triangles)

Then e.g. `/usr/bin/time -f "%e s %M KB" build/release/app/rayview render DIR/m.obj -o m.png --resolution 64x64`.
"""
import math
import os
import sys

SIDE = 317  # a grid of 317 x 317 quads holds the 100 000 faces of the materials and groups files


def grid_vertices(f, side):
    for y in range(side + 1):
        for x in range(side + 1):
            f.write(f"v {x} {y} {((x * 7 + y * 3) % 11) * 0.1}\n")


def faces(count):
    """1-based corners of `count` triangles, one per quad of the SIDE grid."""
    k = 0
    for y in range(SIDE):
        for x in range(SIDE):
            if k == count:
                return
            a = y * (SIDE + 1) + x + 1
            yield a, a + 1, a + SIDE + 2
            k += 1


def materials(out, n):
    with open(os.path.join(out, "m.mtl"), "w") as f:
        for i in range(n):
            f.write(f"newmtl m{i}\nKd {(i % 7) / 7:.3f} {(i % 5) / 5:.3f} {(i % 3) / 3:.3f}\nKs 0.1 0.1 0.1\nNs 10\n\n")
    with open(os.path.join(out, "m.obj"), "w") as f:
        f.write("mtllib m.mtl\n")
        grid_vertices(f, SIDE)
        for i, (a, b, c) in enumerate(faces(n)):
            f.write(f"usemtl m{i}\nf {a} {b} {c}\n")


def groups(out, n):
    with open(os.path.join(out, "g.obj"), "w") as f:
        grid_vertices(f, SIDE)
        for i, (a, b, c) in enumerate(faces(n)):
            f.write(f"g g{i}\nf {a} {b} {c}\n")


def grid(out, side):
    with open(os.path.join(out, "big.obj"), "w") as f:
        for y in range(side + 1):
            for x in range(side + 1):
                f.write(f"v {x * 0.01:.4f} {math.sin(x * 0.1) * math.cos(y * 0.1) * 0.05:.6f} {y * 0.01:.4f}\n")
        for y in range(side):
            for x in range(side):
                a = y * (side + 1) + x + 1
                f.write(f"f {a} {a + 1} {a + side + 2}\nf {a} {a + side + 2} {a + side + 1}\n")


def main():
    kinds = {"materials": (materials, 100000), "groups": (groups, 100000), "grid": (grid, 707)}
    if len(sys.argv) not in (3, 4) or sys.argv[1] not in kinds:
        print(__doc__, file=sys.stderr)
        return 2
    write, default = kinds[sys.argv[1]]
    n = int(sys.argv[3]) if len(sys.argv) == 4 else default
    if sys.argv[1] != "grid" and n > SIDE * SIDE:
        print(f"at most {SIDE * SIDE} faces", file=sys.stderr)
        return 2
    os.makedirs(sys.argv[2], exist_ok=True)
    write(sys.argv[2], n)
    return 0


if __name__ == "__main__":
    sys.exit(main())
