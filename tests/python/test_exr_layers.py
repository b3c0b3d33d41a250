"""scripts/exr_layers.py (the reader and figure of `nephele render --layers` EXRs): display
values above 1 are clipped before their 8-bit cast, so bright clouds over the checkerboard are
white, not wrapped into neon fringes (issue 41). No render: the layers are made here."""
import importlib.util
import os

import numpy as np
import pytest

SCRIPT = os.environ.get(
    "NEPHELE_EXR_LAYERS",
    os.path.join(os.path.dirname(__file__), "..", "..", "scripts", "exr_layers.py"))


def load_script():
    spec = importlib.util.spec_from_file_location("exr_layers", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_values_are_clipped_before_the_8_bit_cast():
    exr_layers = load_script()
    codes = exr_layers.to_8bit(np.array([1.5, 1.0, 0.5, 0.0, -0.2, np.nan, np.inf], np.float32))
    assert codes.dtype == np.uint8
    assert codes.tolist() == [255, 255, 128, 0, 0, 0, 255]


def test_bright_clouds_over_the_checkerboard_are_white_not_wrapped(tmp_path):
    pytest.importorskip("PIL")
    from PIL import Image
    exr_layers = load_script()
    h, w = 24, 24
    layers = {}
    # Clouds bright enough to saturate (display 1) and half transparent: 1 + 0.5 x 0.35 or 0.65
    # of the checkerboard, over 1 before the clip (the old bare cast wrapped them to 43 and 81).
    for c in "RGB":
        layers["sky." + c] = np.full((h, w), 2000.0, np.float32)
        layers["clouds." + c] = np.full((h, w), 1e6, np.float32)
        layers[c] = layers["clouds." + c] + 0.5 * layers["sky." + c]
    layers["clouds.A"] = np.full((h, w), 0.5, np.float32)
    layers["clouds.depth_m"] = np.full((h, w), 3000.0, np.float32)
    path = str(tmp_path / "layers.png")
    exr_layers.figure(layers, {"nephele.exposure": 1e-4}, path)
    out = np.asarray(Image.open(path).convert("RGB"))
    gap, label = 6, 18  # figure's layout: the checkerboard panel is the third of the top row
    panel = out[label:label + h, 2 * (w + gap):2 * (w + gap) + w]
    assert panel.shape == (h, w, 3)
    assert np.all(panel == 255), np.unique(panel)
    alpha = out[2 * label + h + gap:2 * (label + h) + gap, :w]  # clouds.A, 0.5 everywhere
    assert np.all(np.abs(alpha.astype(int) - 128) <= 1), np.unique(alpha)
