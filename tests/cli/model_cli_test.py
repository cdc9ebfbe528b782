#!/usr/bin/env python3
"""Models on the command line: `rayview import`, `rayview export`, `rayview render MODEL`, as a user meets them.

Usage: model_cli_test.py --rayview PATH --scratch DIR
Makes its own models; each check prints one line; exits 1 on the first failure.
"""
import argparse
import base64
import json
import os
import re
import shutil
import struct
import subprocess
import sys
import zlib

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from image_files import same_file  # noqa: E402


def run(args, rayview):
    result = subprocess.run([rayview] + args, capture_output=True, text=True, timeout=300)
    print(f"  $ rayview {' '.join(args)} -> exit {result.returncode}")
    return result


def check(condition, message):
    if not condition:
        print(f"FAILED: {message}")
        sys.exit(1)
    print(f"  ok: {message}")


def png_size(path):
    with open(path, "rb") as f:
        head = f.read(24)
    return struct.unpack(">II", head[16:24])


def write_ply(path):
    # A box of 8 vertices and 6 quads at coordinates that need all 9 digits of a float.
    box = [(0, 0, 0), (2, 0, 0), (2, 1, 0), (0, 1, 0), (0, 0, 1.5), (2, 0, 1.5), (2, 1, 1.5), (0, 1, 1.5)]
    quads = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (2, 3, 7, 6), (1, 2, 6, 5), (0, 4, 7, 3)]
    header = ("ply\nformat binary_little_endian 1.0\nelement vertex 8\nproperty float x\nproperty float y\n"
              "property float z\nelement face 6\nproperty list uchar int vertex_indices\nend_header\n")
    with open(path, "wb") as f:
        f.write(header.encode())
        for v in box:
            f.write(struct.pack("<3f", *(c + 0.123456789 for c in v)))
        for q in quads:
            f.write(struct.pack("<B4i", 4, *q))


def gltf_triangles(indices, normals=None):
    """A glTF of 4 vertices and the given triangle indices (and normals), its buffer inline."""
    positions = struct.pack("<12f", 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0)
    index_bytes = struct.pack(f"<{len(indices)}H", *indices)
    index_bytes += b"\0" * (len(index_bytes) % 4)
    data = positions + index_bytes + (struct.pack("<12f", *normals) if normals else b"")
    views = [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
             {"buffer": 0, "byteOffset": 48, "byteLength": 2 * len(indices)}]
    accessors = [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
                 {"bufferView": 1, "componentType": 5123, "count": len(indices), "type": "SCALAR"}]
    attributes = {"POSITION": 0}
    if normals:
        views.append({"buffer": 0, "byteOffset": 48 + len(index_bytes), "byteLength": 48})
        accessors.append({"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC3"})
        attributes["NORMAL"] = 2
    return json.dumps({
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": attributes, "indices": 1}]}],
        "buffers": [{"byteLength": len(data), "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
        "bufferViews": views, "accessors": accessors})


def check_broken_models(a, s):
    """Models other readers would draw in part: refused, the file named, nothing written."""
    broken = {
        "index.gltf": gltf_triangles([0, 1, 2, 1, 3, 7]),
        "short.off": "OFF\n4 3 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n",
        "index.off": "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 3 9\n",
        "uv.obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/99 2/1 3/1\n",
    }
    for name, text in broken.items():
        with open(s(name), "w") as f:
            f.write(text)
        r = run(["import", s(name), "-o", s(name + ".xml")], a.rayview)
        check(r.returncode == 2 and name in r.stderr and not os.path.exists(s(name + ".xml")),
              f"{name}: exit 2, the file named, nothing written: " + r.stderr.strip())
    check("uv.obj:5:" in r.stderr, "an OBJ's bad index is refused with its line")
    # One normal of no length: only the triangle that uses it loses its normals, and the summary says so.
    with open(s("zero_normal.gltf"), "w") as f:
        f.write(gltf_triangles([0, 1, 2, 1, 3, 2], normals=[0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 0]))
    r = run(["import", s("zero_normal.gltf"), "-o", s("zero_normal.xml")], a.rayview)
    check(r.returncode == 0 and "dropped: the normals of 1 triangles" in r.stdout,
          "a zero normal drops only its triangle's normals: " + r.stdout.strip())


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--rayview", required=True)
    parser.add_argument("--scratch", required=True)
    a = parser.parse_args()
    shutil.rmtree(a.scratch, ignore_errors=True)
    os.makedirs(a.scratch)
    s = lambda name: os.path.join(a.scratch, name)
    write_ply(s("box.ply"))

    ldd = subprocess.run(["ldd", a.rayview], capture_output=True, text=True)
    check(ldd.returncode == 0 and "assimp" not in ldd.stdout, "rayview does not load libassimp")

    r = run(["import", s("box.ply"), "-o", s("box.xml"), "--resolution", "320x200"], a.rayview)
    check(r.returncode == 0 and re.search(r"12 triangles, 1 mesh, 1 material, texture none; made up: .*camera", r.stdout),
          "import prints one summary line: " + r.stdout.strip())
    xml = open(s("box.xml")).read()
    check("<imageresolution>320 200</imageresolution>" in xml, "--resolution sets the image size")
    body = xml.split("-->", 1)[1]  # after the "written by rayview X.Y.Z" comment
    numbers = re.findall(r">([^<]*\d[^<]*)<", body)
    numbers = [n for text in numbers for n in text.split()]
    vertices = xml.split("<vertexdata>")[1].split("</vertexdata>")[0].split()
    check(len(vertices) == 24 and all(len(re.sub(r"e.*|[-.]", "", n).lstrip("0")) <= 9 for n in numbers),
          f"every number ({len(numbers)}) is written with at most 9 significant digits")
    faces = [int(i) for i in re.findall(r"\d+", "".join(xml.split("<faces>")[1:]).split("</faces>")[0])]
    check(min(faces) == 1 and max(faces) == 8, "faces are 1-based")
    r = run(["render", s("box.xml"), "-o", s("from_xml.png")], a.rayview)
    check(r.returncode == 0 and png_size(s("from_xml.png")) == (320, 200), "the imported scene renders")
    r = run(["render", s("box.ply"), "-o", s("direct.png"), "--up", "z"], a.rayview)
    check(r.returncode == 0 and png_size(s("direct.png")) == (1280, 720), "render MODEL renders it directly, 1280x720")

    with open(s("broken.ply"), "wb") as f:
        f.write(open(s("box.ply"), "rb").read()[:-20])
    r = run(["import", s("broken.ply"), "-o", s("broken.xml")], a.rayview)
    check(r.returncode == 2 and "broken.ply" in r.stderr and not os.path.exists(s("broken.xml")),
          "a truncated model: exit 2, the file named, nothing written: " + r.stderr.strip())
    r = run(["render", s("broken.ply"), "-o", s("broken.png")], a.rayview)
    check(r.returncode == 2 and r.stderr.count("\n") == 1 and not os.path.exists(s("broken.png")),
          "render of a broken model: one line, exit 2, nothing written")

    for ext in ["obj", "ply", "stl", "gltf", "glb"]:
        r = run(["export", s("box.xml"), "-o", s("out." + ext)], a.rayview)
        check(r.returncode == 0 and os.path.getsize(s("out." + ext)) > 0, f"export writes .{ext}")
        r = run(["render", s("out." + ext), "-o", s(f"back_{ext}.png")], a.rayview)
        check(r.returncode == 0, f"the exported .{ext} opens again")
    check(os.path.exists(s("out.mtl")) and os.path.exists(s("out.bin")), "export writes the .mtl and the .bin beside")
    check('"doubleSided": true' in open(s("out.gltf")).read(), "two-sided materials are exported doubleSided")
    check(not [n for n in os.listdir(a.scratch) if n.startswith(".rayview-export")], "no staging directory is left")
    r = run(["export", s("box.xml"), "-o", s("out.fbx")], a.rayview)
    check(r.returncode == 2 and not os.path.exists(s("out.fbx")), "export to an unknown format exits 2")
    check_broken_models(a, s)
    r = run(["import", "--help"], a.rayview)
    check(r.returncode == 0 and "--up" in r.stdout and "--lights" in r.stdout and "file|auto" in r.stdout,
          "import --help names --up, --camera file|auto and --lights")
    r = run(["import", s("box.ply"), "-o", s("own.xml"), "--camera", "auto", "--lights", "kit"], a.rayview)
    check(r.returncode == 0 and "camera, key/fill/back lights" in r.stdout,
          "--camera auto --lights kit: rayview's framing and light kit")
    r = run(["import", s("box.ply"), "-o", s("no.xml"), "--lights", "sun"], a.rayview)
    check(r.returncode == 2 and "--lights expects file or kit" in r.stderr and not os.path.exists(s("no.xml")),
          "an unknown --lights word: exit 2, nothing written")
    r = run(["import", s("box.ply"), "-o", s("no.xml"), "--camera", "best"], a.rayview)
    check(r.returncode == 2 and "--camera" in r.stderr and not os.path.exists(s("no.xml")),
          "an unknown --camera word: exit 2")
    check("<twosided>1</twosided>" in xml, "imported materials are two-sided")
    check_fifos(a.rayview, s)
    check_referenced_files_kept(a.rayview, s)
    check_texture_outside_the_folder(a.rayview, s)
    check_windows_texture_paths(a.rayview, s)
    check_export_on_full_disk(a.rayview, s)
    check_export_keeps_the_texture(a.rayview, s)
    check_every_material_keeps_its_texture(a.rayview, s)
    check_metal_keeps_its_map(a.rayview, s)
    check_unusable_values_name_the_model(a.rayview, s)


def write_png16(path):
    # A 2x2 16-bit RGBA PNG: what rayview would write in its place (8-bit RGB) shows in its bytes.
    row = b"\x00" + bytes(range(16))
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 2, 2, 16, 6, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(row * 2)) + chunk(b"IEND", b""))


def textured_obj(s, name, texture):
    with open(s(name + ".mtl"), "w") as f:
        f.write(f"newmtl a\nKd 1 1 1\nmap_Kd {texture}\n")
    with open(s(name + ".obj"), "w") as f:
        f.write(f"mtllib {name}.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl a\nf 1/1 2/2 3/3\n")


def check_referenced_files_kept(rayview, s):
    # The files a model makes the importer read (its MTL, its texture) are inputs: no output lands on them.
    write_png16(s("wood.png"))
    textured_obj(s, "wooden", "wood.png")
    before = open(s("wood.png"), "rb").read()
    r = run(["render", s("wooden.obj"), "-o", s("wood.png")], rayview)
    check(r.returncode == 2 and "wood.png" in r.stderr and open(s("wood.png"), "rb").read() == before,
          "render onto the model's texture is refused, the texture kept: " + r.stderr.strip())
    r = run(["render", s("wooden.obj"), "-o", s("wooden.mtl.png")], rayview)
    check(r.returncode == 0, "the same model renders to another name")
    # import's own copy of the texture takes another name when the model's texture already has it.
    write_png16(s("mine_texture.png"))
    textured_obj(s, "taken", "mine_texture.png")
    before = open(s("mine_texture.png"), "rb").read()
    r = run(["import", s("taken.obj"), "-o", s("mine.xml")], rayview)
    check(r.returncode == 0 and open(s("mine_texture.png"), "rb").read() == before and
          os.path.exists(s("mine_texture-2.png")) and "mine_texture-2.png" in open(s("mine.xml")).read() and
          "mine_texture-2.png" in r.stderr,
          "import keeps a file named as its texture copy and says which name it took: " + r.stderr.strip())


def check_texture_outside_the_folder(rayview, s):
    # A model may name any image on the machine: one outside its folder is used with a warning naming it, and import
    # copies it beside the scene only when asked (--copy-textures); one in a subfolder is the model's own.
    for folder in ("model", "tex", "out", "model/maps"):
        os.makedirs(s("outside/" + folder), exist_ok=True)
    write_png16(s("outside/tex/wood.png"))
    write_png16(s("outside/model/maps/own.png"))
    textured_obj(lambda f: s("outside/model/" + f), "far", "../tex/wood.png")
    textured_obj(lambda f: s("outside/model/" + f), "near", "maps/own.png")
    wood = os.path.realpath(s("outside/tex/wood.png"))
    r = run(["render", s("outside/model/far.obj"), "-o", s("outside/far.png")], rayview)
    check(r.returncode == 0 and "outside the model's folder" in r.stderr and wood in r.stderr,
          "a texture outside the model's folder is used, the warning naming it: " + r.stderr.strip())
    r = run(["render", s("outside/model/near.obj"), "-o", s("outside/near.png")], rayview)
    check(r.returncode == 0 and "outside" not in r.stderr, "a texture in the model's subfolder draws no warning")
    scene = s("outside/out/far.xml")
    r = run(["import", s("outside/model/far.obj"), "-o", scene], rayview)
    check(r.returncode == 0 and not os.path.exists(s("outside/out/far_texture.png")) and
          "../tex/wood.png" in open(scene).read() and "--copy-textures" in r.stderr,
          "import names an outside texture where it lies, copies nothing and says how to copy: " + r.stderr.strip())
    r = run(["render", scene, "-o", s("outside/far_scene.png")], rayview)
    check(r.returncode == 0 and same_file(s("outside/far_scene.png"), s("outside/far.png")),
          "the imported scene finds the texture where it lies and renders as the model did: " + r.stderr.strip())
    copied = s("outside/out/copied.xml")
    r = run(["import", s("outside/model/far.obj"), "-o", copied, "--copy-textures"], rayview)
    check(r.returncode == 0 and os.path.exists(s("outside/out/copied_texture.png")) and
          "copied_texture.png" in open(copied).read() and "copied beside the scene" in r.stderr,
          "import --copy-textures copies it beside the scene and says so: " + r.stderr.strip())


def check_windows_texture_paths(rayview, s):
    # A texture path written on Windows or another machine, whose file lies beside the model: used, with a warning
    # naming the file read, and the image is the one the plain name gives.
    os.makedirs(s("windows"), exist_ok=True)
    write_png16(s("windows/wood2.png"))
    in_windows = lambda f: s("windows/" + f)
    textured_obj(in_windows, "plain", "wood2.png")
    r = run(["render", in_windows("plain.obj"), "-o", in_windows("plain.png")], rayview)
    check(r.returncode == 0 and "warning" not in r.stderr, "a texture named as it lies draws no warning")
    for name, written in (("dot", ".\\wood2.png"), ("drive", "D:\\work\\maps\\wood2.png")):
        textured_obj(in_windows, name, written)
        r = run(["render", in_windows(name + ".obj"), "-o", in_windows(name + ".png")], rayview)
        check(r.returncode == 0 and "is not where the model says" in r.stderr and "wood2.png" in r.stderr and
              same_file(in_windows(name + ".png"), in_windows("plain.png")),
              f"the Windows path {written} finds the texture beside the model, with a warning: " + r.stderr.strip())


def write_png8(path, pixels):
    # An 8-bit RGB PNG of rows of (r, g, b) pixels.
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    raw = b"".join(b"\x00" + bytes(c for p in row for c in p) for row in pixels)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", len(pixels[0]), len(pixels), 8, 2, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def check_export_keeps_the_texture(rayview, s):
    # An exported model names its texture, written beside it as a PNG, and opens again looking as it did: the same
    # image from .obj, the texture the right way up (four texels of four colours). PLY and STL carry no texture: none is written.
    os.makedirs(s("painted/out"), exist_ok=True)
    in_painted = lambda f: s("painted/" + f)
    write_png8(in_painted("paint.png"), [[(255, 0, 0), (0, 255, 0)], [(0, 0, 255), (255, 255, 255)]])
    textured_obj(in_painted, "paint", "paint.png")
    r = run(["render", in_painted("paint.obj"), "-o", in_painted("original.png")], rayview)
    check(r.returncode == 0, "the textured model renders: " + r.stderr.strip())
    original = open(in_painted("original.png"), "rb").read()
    for ext, companion in (("obj", "exported_obj.mtl"), ("gltf", "exported_gltf.gltf")):
        model = in_painted(f"out/exported_{ext}.{ext}")
        texture = in_painted(f"out/exported_{ext}_texture.png")
        r = run(["export", in_painted("paint.obj"), "-o", model], rayview)
        check(r.returncode == 0 and os.path.exists(texture) and texture in r.stdout and
              os.path.basename(texture) in open(in_painted("out/" + companion)).read(),
              f"export to .{ext} writes the texture beside the model and names it: " + r.stdout.strip() + r.stderr.strip())
        back = in_painted(f"back_{ext}.png")
        r = run(["render", model, "-o", back], rayview)
        if ext == "obj":
            check(r.returncode == 0 and open(back, "rb").read() == original,
                  "the exported .obj renders as the model did, texture included: " + r.stderr.strip())
        else:
            # glTF has no Phong specular: the model opens again with a dielectric's 0.04, a highlight of at most 3
            # levels; a texture upside down or a colour lost would differ by up to 255.
            c = run(["compare", back, in_painted("original.png")], rayview)
            m = re.search(r"maxdiff=(\d+)", c.stdout)
            check(r.returncode == 0 and m and int(m.group(1)) <= 3,
                  "the exported .gltf renders as the model did, texture included (largest difference at most 3): " +
                  c.stdout.strip())
    r = run(["export", in_painted("paint.obj"), "-o", in_painted("out/plain.ply")], rayview)
    check(r.returncode == 0 and not os.path.exists(in_painted("out/plain_texture.png")),
          "export to .ply writes no texture")


def read_ppm(path):
    # The pixels of a binary PPM that rayview wrote, as (r, g, b) tuples.
    data = open(path, "rb").read()
    fields = data.split(maxsplit=4)
    width, height = int(fields[1]), int(fields[2])
    pixels = fields[4][:width * height * 3]
    return [tuple(pixels[i:i + 3]) for i in range(0, len(pixels), 3)]


def check_every_material_keeps_its_texture(rayview, s):
    # Two materials, two textures of two colours each (red|green, blue|yellow): every material shows its own texels,
    # where one texture per scene would average the other to grey; import writes both beside the scene, and the scene
    # and an exported OBJ render as the model does. At 320x180: the colours, not the detail, are checked.
    os.makedirs(s("two/out"), exist_ok=True)
    in_two = lambda f: s("two/" + f)
    write_png8(in_two("ab.png"), [[(255, 0, 0), (0, 255, 0)]])
    write_png8(in_two("cd.png"), [[(0, 0, 255), (255, 255, 0)]])
    with open(in_two("two.mtl"), "w") as f:
        f.write("newmtl a\nKd 1 1 1\nmap_Kd ab.png\nnewmtl b\nKd 1 1 1\nmap_Kd cd.png\n")
    with open(in_two("two.obj"), "w") as f:
        f.write("mtllib two.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 1.2 0 0\nv 2.2 0 0\nv 2.2 1 0\nv 1.2 1 0\n"
                "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl a\nf 1/1 2/2 3/3 4/4\nusemtl b\nf 5/1 6/2 7/3 8/4\n")
    r = run(["render", in_two("two.obj"), "-o", in_two("model.ppm"), "--resolution", "320x180"], rayview)
    check(r.returncode == 0 and "averaged" not in r.stderr, "a model with two textures renders: " + r.stderr.strip())
    pixels = read_ppm(in_two("model.ppm"))
    hues = {"red": lambda p: p[0] > p[1] + 40 and p[0] > p[2] + 40, "green": lambda p: p[1] > p[0] + 40 and p[1] > p[2] + 40,
            "blue": lambda p: p[2] > p[0] + 40 and p[2] > p[1] + 40, "yellow": lambda p: min(p[0], p[1]) > p[2] + 40}
    shown = {name: sum(1 for p in pixels if test(p)) for name, test in hues.items()}
    check(all(n > 500 for n in shown.values()), f"each material shows its own texels: {shown}")
    r = run(["import", in_two("two.obj"), "-o", in_two("out/two.xml"), "--resolution", "320x180"], rayview)
    xml = open(in_two("out/two.xml")).read() if r.returncode == 0 else ""
    check(r.returncode == 0 and "textures ab.png (2x1), cd.png (2x1)" in r.stdout and
          xml.count("<textureimage>") == 2 and os.path.exists(in_two("out/two_texture.png")) and
          os.path.exists(in_two("out/two_texture-2.png")),
          "import keeps both, written beside the scene and named by their materials: " + r.stdout.strip())
    for made, args in (("scene", ["render", in_two("out/two.xml")]),
                       ("exported OBJ", ["export", in_two("two.obj"), "-o", in_two("out/again.obj")])):
        r = run(args + ["-o", in_two("again.ppm")] if made == "scene" else args, rayview)
        if made != "scene":
            check(r.returncode == 0 and "its textures as" in r.stdout, "export writes both textures: " + r.stdout.strip())
            r = run(["render", in_two("out/again.obj"), "-o", in_two("again.ppm"), "--resolution", "320x180"], rayview)
        check(r.returncode == 0 and read_ppm(in_two("again.ppm")) == pixels,
              f"the {made} renders as the model does, both textures included: " + r.stderr.strip())


def check_metal_keeps_its_map(rayview, s):
    # A glTF quad whose metallic-roughness map is plastic on the left and polished metal on the right: import keeps
    # the map per texel, and the imported scene and a re-exported glTF render exactly as the model does.
    os.makedirs(s("metal/out"), exist_ok=True)
    in_metal = lambda f: s("metal/" + f)
    write_png8(in_metal("mr.png"), [[(0, 255, 0), (0, 51, 255)]])
    data = struct.pack("<12f", 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0) + struct.pack("<8f", 0, 1, 1, 1, 1, 0, 0, 0) + \
        struct.pack("<6H", 0, 1, 2, 0, 2, 3) + b"\0\0"
    with open(in_metal("quad.bin"), "wb") as f:
        f.write(data)
    gltf = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
            "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": 0}]}],
            "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.6, 0.4, 1], "metallicFactor": 1,
                                                    "roughnessFactor": 1, "metallicRoughnessTexture": {"index": 0}}}],
            "textures": [{"source": 0}], "images": [{"uri": "mr.png"}],
            "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
                          {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
                          {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}],
            "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 32},
                            {"buffer": 0, "byteOffset": 80, "byteLength": 12}],
            "buffers": [{"uri": "quad.bin", "byteLength": len(data)}]}
    with open(in_metal("quad.gltf"), "w") as f:
        json.dump(gltf, f)
    size = ["--resolution", "160x90"]
    r = run(["render", in_metal("quad.gltf"), "-o", in_metal("model.ppm")] + size, rayview)
    check(r.returncode == 0, "a glTF with a metallic-roughness map renders: " + r.stderr.strip())
    pixels = read_ppm(in_metal("model.ppm"))
    r = run(["import", in_metal("quad.gltf"), "-o", in_metal("out/quad.xml")] + size, rayview)
    xml = open(in_metal("out/quad.xml")).read() if r.returncode == 0 else ""
    check(r.returncode == 0 and "<metallicroughnessimage>quad_texture.png</metallicroughnessimage>" in xml and
          "<metallicroughness>1 1</metallicroughness>" in xml and os.path.exists(in_metal("out/quad_texture.png")),
          "import keeps the map beside the scene, with the base colour and the factors: " + r.stdout.strip())
    r = run(["render", in_metal("out/quad.xml"), "-o", in_metal("scene.ppm")], rayview)
    check(r.returncode == 0 and read_ppm(in_metal("scene.ppm")) == pixels, "the scene renders as the model does")
    r = run(["export", in_metal("quad.gltf"), "-o", in_metal("out/again.gltf")], rayview)
    exported = json.load(open(in_metal("out/again.gltf"))) if r.returncode == 0 else {}
    pbr = exported.get("materials", [{}])[0].get("pbrMetallicRoughness", {})
    check(r.returncode == 0 and "metallicRoughnessTexture" in pbr, "export writes the map as glTF's: " + str(pbr))
    r = run(["render", in_metal("out/again.gltf"), "-o", in_metal("again.ppm")] + size, rayview)
    again = read_ppm(in_metal("again.ppm")) if r.returncode == 0 else []
    close = sum(1 for p, q in zip(pixels, again) if max(abs(a - b) for a, b in zip(p, q)) <= 1)
    check(len(again) == len(pixels) and close >= 0.99 * len(pixels),
          f"the exported glTF renders as the model does: {close} of {len(pixels)} pixels within 1")


def check_export_on_full_disk(rayview, s):
    # A file system of 8 KiB in a mount namespace of its own: the export's files do not fit. The old files stay.
    full = s("full")
    os.makedirs(full, exist_ok=True)
    script = ('mount -t tmpfs -o size=8k tmpfs "$1" || exit 99; echo old > "$1/out.mtl"; echo old > "$1/out.obj"; '
              '"$2" export "$3" -o "$1/out.obj"; echo "exit $?"; cat "$1/out.mtl" "$1/out.obj"; ls -a "$1"')
    try:
        r = subprocess.run(["unshare", "-m", "sh", "-c", script, "sh", full, rayview, s("box.xml")],
                           capture_output=True, text=True, timeout=120)
    except FileNotFoundError:
        print("  skipped: export on a full disk (no unshare here)")
        return
    if r.returncode == 99 or "exit " not in r.stdout:
        print("  skipped: export on a full disk (cannot mount a small file system here: " + r.stderr.strip() + ")")
        return
    print("  " + r.stdout.replace("\n", " | "))
    check("exit 1" in r.stdout and "out.obj" in r.stderr and "No space left" in r.stderr and
          r.stdout.count("old\n") == 2 and ".rayview-export" not in r.stdout,
          "export on a full disk: exit 1, the path and the reason, the old .obj and .mtl as they were: " +
          r.stderr.strip())


def check_unusable_values_name_the_model(rayview, s):
    # A NaN colour, or vertices whose made-up lights overflow: the message names the model, never a line of the XML
    # rayview made up from it (which the user has never seen).
    with open(s("nan.mtl"), "w") as f:
        f.write("newmtl a\nKd nan 1 1\n")
    with open(s("nan.obj"), "w") as f:
        f.write("mtllib nan.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n")
    with open(s("huge.obj"), "w") as f:
        f.write("v 0 0 0\nv 3e38 0 0\nv 0 3e38 0\nf 1 2 3\n")
    for model in ["nan.obj", "huge.obj"]:
        r = run(["render", s(model), "-o", s("unusable.png")], rayview)
        check(r.returncode == 2 and r.stderr.startswith(s(model) + ": error:") and
              not os.path.exists(s("unusable.png")),
              f"{model}: exit 2, the model named with no line of generated XML: " + r.stderr.strip())
        if model == "nan.obj":
            check("nan.mtl, line 2: Kd: 'nan'" in r.stderr and "<" not in r.stderr,
                  "the NaN is found where the user wrote it, the MTL's line, and no tag of generated XML is named")


def check_fifos(rayview, s):
    # A FIFO named inside a model blocks its reader without using CPU: it is refused at once, by name.
    os.mkfifo(s("pipe.mtl"))
    with open(s("fifo.obj"), "w") as f:
        f.write("mtllib pipe.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    os.mkfifo(s("pipe.bin"))
    with open(s("fifo.gltf"), "w") as f:
        f.write('{"asset":{"version":"2.0"},"buffers":[{"uri":"pipe.bin","byteLength":36}],'
                '"bufferViews":[{"buffer":0,"byteLength":36}],"accessors":[{"bufferView":0,"componentType":5126,'
                '"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}],"meshes":[{"primitives":[{"attributes":'
                '{"POSITION":0}}]}],"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0}')
    for model, named in [("fifo.obj", "pipe.mtl"), ("fifo.gltf", "pipe.bin")]:
        try:
            r = subprocess.run([rayview, "render", s(model), "-o", s("fifo.png")], capture_output=True, text=True,
                               timeout=30)
        except subprocess.TimeoutExpired:
            check(False, f"render of {model}, which names a FIFO, does not hang")
        check(r.returncode == 2 and model in r.stderr and named in r.stderr and not os.path.exists(s("fifo.png")),
              f"a FIFO named by {model} is refused at once, named: " + r.stderr.strip())


if __name__ == "__main__":
    main()
