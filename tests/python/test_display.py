"""nephele.render's statistics (stats=True) and nephele.display, the CLI's PNG from a rendered
frame by nephele's own exposure, tone map and sRGB code (issue 41): against the PNG and the
--stats-json of the built `nephele` for the same scene file. Renders of 64 x 48 pixels without
the light volume (a second each on lavapipe)."""
import json
import os
import subprocess

import numpy as np
import pytest

import nephele

WIDTH, HEIGHT = 64, 48


def cli_path():
    """The built CLI: $NEPHELE_CLI, else beside the module's folder (build/python/..)."""
    path = os.environ.get("NEPHELE_CLI") or os.path.join(
        os.path.dirname(os.path.abspath(nephele.__file__)), "..", "nephele")
    return os.path.abspath(path)


@pytest.fixture(scope="module")
def scene_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("display") / "scene.toml"
    path.write_text(nephele.scene_toml(preset="default", scene={"quality.light_volume_km": 0}))
    return str(path)


def test_display_gives_the_png_the_cli_writes(scene_file, tmp_path):
    Image = pytest.importorskip("PIL.Image")
    cli = cli_path()
    if not os.path.exists(cli):
        pytest.skip("no built nephele CLI at " + cli + " (set NEPHELE_CLI)")
    png, stats_json = str(tmp_path / "cli.png"), str(tmp_path / "stats.json")
    subprocess.run([cli, "render", "--scene", scene_file, "--width", str(WIDTH), "--height", str(HEIGHT),
                    "-q", "-o", png, "--stats-json", stats_json], check=True, capture_output=True)
    expected = np.asarray(Image.open(png).convert("RGBA"))
    cli_stats = json.load(open(stats_json))

    image, stats = nephele.render(toml=scene_file, width=WIDTH, height=HEIGHT, stats=True)
    assert image.shape == (HEIGHT, WIDTH, 4) and image.dtype == np.float32
    # The CLI's exposure, and the same statistics it reports.
    assert stats["ev100"] == pytest.approx(cli_stats["ev100"], abs=1e-3)
    assert stats["exposure"] == pytest.approx(1.0 / (1.2 * 2.0 ** stats["ev100"]), rel=1e-9)
    assert stats["tonemap"] == "aces"
    assert -4.0 <= stats["ev100"] <= 17.0  # the default auto exposure's limits
    assert 0.0 <= stats["sky_cover_fraction"] <= 1.0
    assert stats["sky_cover_oktas"] == cli_stats["sky_cover_oktas"]
    assert 0.0 <= stats["cloud_cover_fraction"] <= 1.0
    assert stats["mean_luminance"] > 1000.0  # a day sky, cd/m^2
    assert stats["sun_elevation_deg"] == pytest.approx(cli_stats["sun_elevation_deg"], abs=1e-6)
    assert (stats["width"], stats["height"]) == (WIDTH, HEIGHT)
    assert set(cli_stats) - {"image"} <= set(stats)
    assert "clouds" in stats["passes_ms"]

    shown = nephele.display(image, ev100=stats["ev100"], tonemap=stats["tonemap"])
    assert shown.shape == (HEIGHT, WIDTH, 4) and shown.dtype == np.uint8
    assert np.all(shown[..., 3] == 255)
    difference = np.abs(shown.astype(int) - expected.astype(int))
    assert difference.max() <= 1, "largest difference %d at %s" % (
        difference.max(), np.unravel_index(difference.argmax(), difference.shape))
    # RGB alone reads as RGBA with alpha 1; another tone map gives another image.
    assert np.array_equal(nephele.display(image[..., :3], ev100=stats["ev100"]), shown)
    assert not np.array_equal(nephele.display(image, ev100=stats["ev100"], tonemap="reinhard"), shown)
    # Without an EV100 the image is metered (about the same EV100): brighter than 5 stops above.
    metered = nephele.display(image)
    assert metered.mean() > nephele.display(image, ev100=stats["ev100"] + 5).mean()


def test_layers_come_with_their_statistics_too():
    out, stats = nephele.render(width=16, height=12, layers=True, stats=True,
                                scene={"quality.light_volume_km": 0})
    assert set(out) == {"image", "sky", "clouds", "clouds_depth_m"}
    assert 0.0 <= stats["sky_cover_fraction"] <= 1.0
    assert -4.0 <= stats["ev100"] <= 17.0


def test_bad_display_arguments_get_one_line():
    image = np.full((4, 6, 4), 1000.0, np.float32)
    with pytest.raises(nephele.InputError, match=r'tonemap "filmic": unknown \(allowed: aces, agx'):
        nephele.display(image, tonemap="filmic")
    with pytest.raises(nephele.InputError, match=r"ev100 = 99: must be a number in \[-20, 30\]"):
        nephele.display(image, ev100=99)
    with pytest.raises(nephele.InputError, match=r"ev100 = 'bright': must be a number"):
        nephele.display(image, ev100="bright")
    with pytest.raises(nephele.InputError, match=r"image: shape \(4, 6\); a \(height, width, 3 or 4\) array"):
        nephele.display(np.zeros((4, 6)))
    assert nephele.display(image, ev100=np.float32(10.0)).shape == (4, 6, 4)
