#!/usr/bin/env python3
"""Converts an X window dump (xwd -root, 24/32-bit ZPixmap) to PNG, with the standard library
only, so a screenshot taken under Xvfb can be kept and looked at. Usage: xwd2png.py IN OUT."""
import struct
import sys
import zlib


def main():
    data = open(sys.argv[1], "rb").read()
    fields = struct.unpack(">25I", data[:100])
    header_size, width, height = fields[0], fields[4], fields[5]
    byte_order, bits_per_pixel, bytes_per_line = fields[7], fields[11], fields[12]
    ncolors = fields[19]
    if bits_per_pixel != 32:
        sys.exit(f"xwd2png: {bits_per_pixel} bits per pixel is not supported (need 32)")
    offset = header_size + ncolors * 12
    rows = []
    for y in range(height):
        line = data[offset + y * bytes_per_line: offset + y * bytes_per_line + width * 4]
        out = bytearray(b"\x00")  # filter type none
        for x in range(0, len(line), 4):
            b0, b1, b2, _ = line[x:x + 4]
            # LSBFirst (0): bytes are B, G, R, pad.
            out += bytes((b2, b1, b0)) if byte_order == 0 else bytes((b1, b2, line[x + 3]))
        rows.append(bytes(out))

    def chunk(kind, payload):
        c = struct.pack(">I", len(payload)) + kind + payload
        return c + struct.pack(">I", zlib.crc32(kind + payload) & 0xFFFFFFFF)

    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(b"".join(rows), 6)) + chunk(b"IEND", b"")
    open(sys.argv[2], "wb").write(png)


if __name__ == "__main__":
    main()
