#!/usr/bin/env python3
"""How bright the default look shows each .vox model, against its palette.

For every .vox file given, renders the default look and `--flat` (the
palette's own colors) at 480x270 on a transparent background and prints
the sum of the luminance of the model's pixels (those `--flat` covers) in
the default look over the same sum in `--flat`: 1.0 would be every face
in full light. Extra flags after `--` go to both renders.

    python3 benches/vox_brightness.py target/release/voxtrace ../shared/scenes/vox/*.vox docs/terrain.vox
"""

import os
import statistics
import struct
import subprocess
import sys
import tempfile


def bmp_pixels(path):
    """(width, height, bytes per pixel, BGRA bytes) of an uncompressed BMP."""
    data = open(path, "rb").read()
    offset = struct.unpack_from("<I", data, 10)[0]
    width, height = struct.unpack_from("<ii", data, 18)
    depth = struct.unpack_from("<H", data, 28)[0] // 8
    return width, abs(height), depth, data[offset : offset + width * abs(height) * depth]


def luminance(b, g, r):
    return 0.2126 * r + 0.7152 * g + 0.0722 * b


def brightness(binary, model, extra, scratch):
    sums = {}
    flat_cover = None
    for look, flags in (("flat", ["--flat"]), ("default", [])):
        out = os.path.join(scratch, look + ".bmp")
        args = [binary, "--vox", model, "--width", "480", "--height", "270"]
        args += ["--background", "transparent", "--format", "bmp", "--out", out]
        subprocess.run(args + flags + extra, check=True, capture_output=True)
        _, _, depth, pixels = bmp_pixels(out)
        if flat_cover is None:
            flat_cover = [pixels[i + 3] > 0 for i in range(0, len(pixels), depth)]
        total = 0.0
        for n, i in enumerate(range(0, len(pixels), depth)):
            if flat_cover[n]:
                total += luminance(pixels[i], pixels[i + 1], pixels[i + 2])
        sums[look] = total
    return sums["default"] / max(sums["flat"], 1.0)


def main():
    args = sys.argv[1:]
    extra = args[args.index("--") + 1 :] if "--" in args else []
    args = args[: args.index("--")] if "--" in args else args
    binary, models = args[0], args[1:]
    ratios = []
    with tempfile.TemporaryDirectory() as scratch:
        for model in models:
            ratio = brightness(binary, model, extra, scratch)
            ratios.append(ratio)
            print(f"{os.path.basename(model):32s} {ratio:.3f}")
    print(f"{'median':32s} {statistics.median(ratios):.3f}")


if __name__ == "__main__":
    main()
