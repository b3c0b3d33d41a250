#!/usr/bin/python3
"""Reads a multi-layer EXR of `nephele render --layers` with numpy alone (scan lines, no, ZIPS or
ZIP compression, half or float channels), checks the compositing identity
R,G,B = clouds.RGB + (1 - clouds.A) sky.RGB and, given an output name, draws the layers side by
side (tone-mapped at the exposure in the header, as nephele's PNGs are).

    /usr/bin/python3 scripts/exr_layers.py film.exr [layers.png]
"""
import struct
import sys
import zlib

import numpy as np


def _read_header(data):
    assert data[:4] == b"\x76\x2f\x31\x01", "not an EXR file"
    pos, attrs = 8, {}
    while data[pos] != 0:
        name_end = data.index(b"\0", pos)
        type_end = data.index(b"\0", name_end + 1)
        name = data[pos:name_end].decode()
        kind = data[name_end + 1:type_end].decode()
        (size,) = struct.unpack_from("<i", data, type_end + 1)
        value = data[type_end + 5:type_end + 5 + size]
        attrs[name] = (kind, value)
        pos = type_end + 5 + size
    return attrs, pos + 1


def _channels(value):
    out, pos = [], 0
    while value[pos] != 0:
        end = value.index(b"\0", pos)
        (pixel_type,) = struct.unpack_from("<i", value, end + 1)
        out.append((value[pos:end].decode(), pixel_type))
        pos = end + 17
    return out


def _unzip(block):
    """ZIP(S) scan lines: zlib, then the byte predictor and the two halves interleaved undone."""
    t = np.frombuffer(zlib.decompress(block), dtype=np.uint8).astype(np.int64)
    t[1:] -= 128  # t[i] = t[i-1] + t[i] - 128 (mod 256)
    t = (np.cumsum(t) & 0xFF).astype(np.uint8)
    half = (len(t) + 1) // 2
    out = np.empty_like(t)
    out[0::2], out[1::2] = t[:half], t[half:]
    return out.tobytes()


def read_exr(path):
    """The channels (name -> float32 array, rows top to bottom) and the header's values."""
    data = open(path, "rb").read()
    attrs, pos = _read_header(data)
    x0, y0, x1, y1 = struct.unpack("<4i", attrs["dataWindow"][1])
    width, height = x1 - x0 + 1, y1 - y0 + 1
    channels = sorted(_channels(attrs["channels"][1]))
    compression = attrs["compression"][1][0]
    lines = {0: 1, 2: 1, 3: 16}[compression]
    sizes = [2 if t == 1 else 4 for _, t in channels]
    dtypes = [np.float16 if t == 1 else (np.float32 if t == 2 else np.uint32) for _, t in channels]
    out = {name: np.zeros((height, width), np.float32) for name, _ in channels}
    chunks = (height + lines - 1) // lines
    offsets = struct.unpack_from("<%dQ" % chunks, data, pos)
    for offset in offsets:
        y, size = struct.unpack_from("<2i", data, offset)
        block = data[offset + 8:offset + 8 + size]
        n = min(lines, y1 + 1 - y)
        raw_size = n * width * sum(sizes)
        raw = block if compression == 0 or size == raw_size else _unzip(block)
        at = 0
        for row in range(n):
            for (name, _), s, dt in zip(channels, sizes, dtypes):
                out[name][y - y0 + row] = np.frombuffer(raw, dt, width, at).astype(np.float32)
                at += width * s
    header = {}
    for name, (kind, value) in attrs.items():
        if kind == "string":
            header[name] = value.decode()
        elif kind == "float":
            header[name] = struct.unpack("<f", value)[0]
    return out, header


def over(layers):
    """The clouds over the sky: the image again."""
    a = layers["clouds.A"]
    return np.stack([layers["clouds." + c] + (1.0 - a) * layers["sky." + c] for c in "RGB"], -1)


def to_8bit(values):
    """Display values as 8 bits: clipped to [0, 1] first (NaN as 0), so that 1.5 is 255, not the
    wrapped 127 of a bare cast."""
    return (np.clip(np.nan_to_num(values, nan=0.0), 0.0, 1.0) * 255 + 0.5).astype(np.uint8)


def _display(rgb, exposure):
    """The ACES fit and sRGB of nephele's PNGs, as 8 bits (exposure multiplies first)."""
    x = np.clip(rgb * exposure, 0.0, 1e4)
    y = np.clip((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0)
    y = np.where(y <= 0.0031308, 12.92 * y, 1.055 * np.power(y, 1 / 2.4) - 0.055)
    return to_8bit(y)


def figure(layers, header, path):
    from PIL import Image, ImageDraw
    e = header["nephele.exposure"]
    image = np.stack([layers[c] for c in "RGB"], -1)
    sky = np.stack([layers["sky." + c] for c in "RGB"], -1)
    clouds = np.stack([layers["clouds." + c] for c in "RGB"], -1)
    a = layers["clouds.A"][..., None]
    h, w = a.shape[:2]
    yy, xx = np.mgrid[0:h, 0:w]
    checker = np.where(((yy // 12 + xx // 12) % 2)[..., None] == 0, 0.35, 0.65)
    # Premultiplied: the clouds' display values plus what shows through of the checkerboard (their
    # sum may pass 1 where the clouds are bright; to_8bit clips it).
    clouds_on_checker = _display(clouds, e) / 255.0 + (1 - a) * checker
    depth = layers["clouds.depth_m"]
    d = np.where(depth > 0, 1.0 - np.clip(np.log(np.maximum(depth, 1.0) / 1500.0) / np.log(100.0), 0, 1), 0)
    panels = [("image (R,G,B)", _display(image, e)), ("sky", _display(sky, e)),
              ("clouds (premultiplied) over a checkerboard", to_8bit(clouds_on_checker)),
              ("clouds.A = 1 - transmittance", to_8bit(np.repeat(a, 3, -1))),
              ("clouds.depth_m (near bright, 1.5 to 150 km)", to_8bit(np.repeat(d[..., None], 3, -1))),
              ("clouds over sky (= image)", _display(over(layers), e))]
    gap, label = 6, 18
    out = Image.new("RGB", (3 * w + 2 * gap, 2 * (h + label) + gap), "white")
    draw = ImageDraw.Draw(out)
    for i, (name, pixels) in enumerate(panels):
        x, y = (i % 3) * (w + gap), (i // 3) * (h + label + gap)
        draw.text((x + 2, y + 3), name, fill="black")
        out.paste(Image.fromarray(pixels), (x, y + label))
    out.save(path)


def main():
    layers, header = read_exr(sys.argv[1])
    image = np.stack([layers[c] for c in "RGB"], -1)
    error = np.abs(image - over(layers)) / (np.abs(image) + 1e-3)
    print("channels:", ", ".join(sorted(layers)))
    print("EV100 %.2f, software %s" % (header["nephele.ev100"], header["software"]))
    print("largest relative difference of clouds over sky from the image: %.3g" % error.max())
    if len(sys.argv) > 2:
        figure(layers, header, sys.argv[2])


if __name__ == "__main__":
    main()
