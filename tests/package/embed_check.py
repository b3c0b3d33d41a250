"""Checks nephele-embed's screenshots (tests/package/embed_test.sh).

Arguments: the frame with the host's mountain, the frame without it, and the mountain's mask
(white where the host's depth buffer holds it). Under an overcast deck whose bottom lies below the
summit, the mountain's pixels are of two kinds: where the view ray meets the deck before the
mountain, the deck covers the mountain and the frame is the frame without it; lower down, the
mountain hides the deck behind it and the frame differs. Away from the mountain the sky is the
same in both.
"""
import sys

import numpy as np
from PIL import Image


def load(path):
    return np.asarray(Image.open(path).convert("RGB"), dtype=np.float64)


def main():
    with_mountain, without, mask = (load(p) for p in sys.argv[1:4])
    mountain = mask[..., 0] > 127
    share = mountain.mean()
    assert 0.03 < share < 0.5, f"the mountain covers {share:.3f} of the frame"
    difference = np.abs(with_mountain - without).max(axis=2)
    covered = mountain & (difference <= 6)
    visible = mountain & (difference > 20)
    rows = np.arange(mountain.shape[0])[:, None] * np.ones(mountain.shape[1])
    print(f"mountain: {mountain.sum()} pixels; the deck covers {covered.sum()} (mean row {rows[covered].mean():.1f}),"
          f" the mountain shows in {visible.sum()} (mean row {rows[visible].mean():.1f})")
    assert covered.sum() > 0.15 * mountain.sum(), "the deck in front of the summit should cover it"
    assert visible.sum() > 0.3 * mountain.sum(), "the mountain should hide the deck behind it"
    assert rows[covered].mean() < rows[visible].mean(), "the deck covers the top, not the foot"
    # Away from the mountain (3 pixels and more), nothing changed.
    near = mountain.copy()
    for axis in (0, 1):
        for shift in (-3, -2, -1, 1, 2, 3):
            near |= np.roll(mountain, shift, axis=axis)
    away = difference[~near]
    print(f"away from the mountain: mean difference {away.mean():.2f}, largest {away.max():.0f} (of 255)")
    assert away.mean() < 1.0 and np.percentile(away, 99) <= 4


if __name__ == "__main__":
    main()
