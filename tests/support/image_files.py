"""Whether two image files written by separate rayview processes hold the same image.

PNG files are compared by their size and pixels (decode_png, which the viewer tests read screenshots with), not
their bytes: ISA-L's deflate, which writes them at
the default level, encodes a stream's first rows differently (other matches, as valid) in about one process of
2,500, so two renders of one image can differ in their bytes though never in their pixels. Every other file
(PPM, text) is compared byte for byte. A file compared with itself before and after (left untouched) is a byte
comparison and does not belong here.
"""
import struct
import zlib


def decode_png(data):
    """(width, height, channels, pixel bytes) of an 8-bit RGB (3) or RGBA (4), non-interlaced PNG file's bytes, its
    rows unfiltered. Raises ValueError for anything else."""
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("not a PNG file")
    pos, idat, header = 8, b"", None
    while pos + 8 <= len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR" and len(body) == 13:
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        elif kind == b"IEND":
            break
        pos += 12 + length
    else:
        raise ValueError("no IEND chunk: not a whole PNG file")
    if header is None:
        raise ValueError("no IHDR chunk")
    width, height, depth, colour, _, _, interlace = header
    if depth != 8 or colour not in (2, 6) or interlace:
        raise ValueError(f"unsupported PNG (depth {depth}, colour type {colour}, interlace {interlace})")
    channels = 3 if colour == 2 else 4
    try:
        raw = zlib.decompress(idat)
    except zlib.error as error:
        raise ValueError(f"its image data does not inflate: {error}") from None
    stride = width * channels
    if len(raw) != height * (stride + 1):
        raise ValueError(f"{len(raw)} bytes of rows for {width}x{height}")
    rows, previous = [], bytearray(stride)
    for y in range(height):
        start = y * (stride + 1)
        kind, line = raw[start], bytearray(raw[start + 1:start + 1 + stride])
        # Filter 0 (none), what rayview writes on every row: the bytes as they are, without the per-byte loop below
        # (0.75 s of a 1280x800 screenshot's decoding).
        for x in range(stride) if kind else ():
            a = line[x - channels] if x >= channels else 0
            b = previous[x]
            c = previous[x - channels] if x >= channels else 0
            if kind == 1:
                line[x] = (line[x] + a) & 255
            elif kind == 2:
                line[x] = (line[x] + b) & 255
            elif kind == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        previous = line
    return width, height, channels, b"".join(rows)


def png_image(data):
    """decode_png's answer, or None when the bytes are not such a PNG."""
    try:
        return decode_png(data)
    except ValueError:
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
