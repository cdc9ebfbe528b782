#!/usr/bin/env python3
"""image_files: two encodings of one image (other deflate, other row filters) are the same content; a changed pixel, size or non-PNG byte is not."""
import os
import struct
import sys
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from image_files import png_image, same_content, same_files  # noqa: E402


def png(width, height, rows, level, sub=False):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xffffffff)
    # Filter 1 (sub) stores each byte less the one a pixel (3 bytes) before it.
    raw = b"".join(b"\1" + bytes((r[x] - (r[x - 3] if x >= 3 else 0)) & 255 for x in range(len(r))) if sub
                   else b"\0" + r for r in rows)
    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, level)) +
            chunk(b"IEND", b""))


def main():
    rows = [bytes((x * 7 + y * 3) % 256 for x in range(3 * 40)) for y in range(30)]
    fast, small = png(40, 30, rows, 1), png(40, 30, rows, 9)
    changed = [bytearray(r) for r in rows]
    changed[29][119] ^= 1
    checks = [
        (fast != small, "the two encodings differ in their bytes"),
        (same_content(fast, small), "two encodings of one image are the same content"),
        (same_content(fast, png(40, 30, rows, 1, sub=True)), "rows stored with another filter, the same pixels"),
        (not same_content(fast, png(40, 30, [bytes(r) for r in changed], 1)), "one channel of one pixel changed differs"),
        (not same_content(fast, png(30, 40, [r[:90] for r in rows] + [rows[0][:90]] * 10, 1)), "another size differs"),
        (not same_content(b"P6\n1 1\n255\n\0\0\0", b"P6\n1 1\n255\n\0\0\1"), "other files compare byte for byte"),
        (png_image(fast[:-12]) is None, "a PNG without its end is not read as one"),
        (same_files({"a.png": fast, "b.txt": b"x"}, {"a.png": small, "b.txt": b"x"}), "listings of the same content"),
        (not same_files({"a.png": fast}, {"a.png": fast, "b.png": fast}), "a file missing from one listing"),
        (not same_files({"a.png": fast}, {"b.png": fast}), "another name"),
    ]
    failed = [what for ok, what in checks if not ok]
    for what in failed:
        print(f"FAILED: {what}")
    print(f"{len(checks) - len(failed)} passed, {len(failed)} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
