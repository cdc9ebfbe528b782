"""Whether two image files written by separate rayview processes hold the same image.

PNG files are compared by their header and inflated rows, not their bytes: ISA-L's deflate, which writes them at
the default level, encodes a stream's first rows differently (other matches, as valid) in about one process of
2,500, so two renders of one image can differ in their bytes though never in their pixels. Every other file
(PPM, text) is compared byte for byte. A file compared with itself before and after (left untouched) is a byte
comparison and does not belong here.
"""
import struct
import zlib


def png_image(data):
    """The IHDR and the inflated IDAT data of a PNG file's bytes; None when they are not a whole PNG."""
    if not data.startswith(b"\x89PNG\r\n\x1a\n"):
        return None
    at, header, idat = 8, None, b""
    while at + 8 <= len(data):
        length, kind = struct.unpack(">I4s", data[at:at + 8])
        body = data[at + 8:at + 8 + length]
        if kind == b"IHDR":
            header = body
        elif kind == b"IDAT":
            idat += body
        elif kind == b"IEND":
            try:
                return header, zlib.decompress(idat)
            except zlib.error:
                return None
        at += 12 + length
    return None


def same_content(a, b):
    """Whether two files' bytes hold the same image (PNG) or are equal (anything else)."""
    if a == b:
        return True
    if a is None or b is None:  # a file missing from one listing
        return False
    image = png_image(a)
    return image is not None and image == png_image(b)


def same_file(path_a, path_b):
    with open(path_a, "rb") as f, open(path_b, "rb") as g:
        return same_content(f.read(), g.read())


def same_files(a, b):
    """Two {name: bytes} listings: the same names, each pair of files the same content."""
    return sorted(a) == sorted(b) and all(same_content(a[n], b[n]) for n in a)
