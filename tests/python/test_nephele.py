"""The Python module `nephele` (python/nephele_module.cpp), run by the test suite with Debian's
python3 and pytest against the module in the build folder (PYTHONPATH)."""
import numpy as np
import pytest

import nephele


def luminance(image):
    return float(np.mean(0.2126 * image[..., 0] + 0.7152 * image[..., 1] + 0.0722 * image[..., 2]))


def test_renders_a_preset_into_an_hdr_array():
    image = nephele.render(preset="default", width=32, height=20)
    assert image.shape == (20, 32, 4)
    assert image.dtype == np.float32
    assert np.all(np.isfinite(image))
    assert np.all(image[..., 3] == 1.0)
    assert luminance(image) > 1000.0  # a day sky, cd/m^2


def test_a_dict_over_the_preset_changes_the_scene():
    clear = nephele.render(width=24, height=16, scene={"clouds": {"coverage": 0.0}})
    overcast = nephele.render(width=24, height=16, scene={"clouds.coverage": 1.0, "clouds.type": 0.0})
    # Looking up at a deck from below: the upper half of the image is grey cloud, not blue sky.
    blue = lambda im: float(np.mean(im[:8, :, 2] / np.maximum(im[:8, :, 0], 1e-6)))
    assert blue(clear) > 1.3 * blue(overcast)
    toml = nephele.scene_toml(scene={"sun": {"illuminance_lux": 100000.0}, "camera.fov_deg": 50})
    assert "illuminance_lux = 1e+05" in toml
    assert "fov_deg = 50.0" in toml


def test_layers_compose_into_the_image():
    out = nephele.render(width=24, height=16, layers=True)
    assert set(out) == {"image", "sky", "clouds", "clouds_depth_m"}
    sky, clouds = out["sky"], out["clouds"]
    over = clouds[..., :3] + (1.0 - clouds[..., 3:4]) * sky[..., :3]
    assert np.allclose(over, out["image"][..., :3], rtol=1e-3, atol=1e-2)
    assert out["clouds_depth_m"].shape == (16, 24, 1)


def test_bad_input_raises_input_error_with_nephele_s_message():
    with pytest.raises(nephele.InputError, match=r"clouds.coverage = 1.5: must be in \[0, 1\]"):
        nephele.render(width=8, height=8, scene={"clouds": {"coverage": 1.5}})
    with pytest.raises(nephele.InputError, match="unknown preset"):
        nephele.render(preset="no-such-sky")
    with pytest.raises(ValueError):  # InputError is a ValueError
        nephele.render(width=8, height=8, scene={"clouds.no_such_key": 1})
    assert "mountains" in nephele.presets()


def test_cloud_queries_from_the_cpu():
    # Straight up through an overcast deck (900 to 4500 m): cloud inside, none below or above.
    column = np.array([[0.0, 0.0, z] for z in (10.0, 2000.0, 2700.0, 6000.0)])
    density = nephele.cloud_density(column, preset="overcast")
    assert density.shape == (4,) and density.dtype == np.float32
    assert density[0] == 0.0 and density[3] == 0.0
    assert density[1] > 0.0 or density[2] > 0.0
    depth = nephele.optical_depth(column[:1], column[3:], preset="overcast")
    assert depth[0] > 5.0
    assert nephele.optical_depth(column[:1], column[3:], preset="clear")[0] == 0.0
    with pytest.raises(nephele.InputError, match="positions"):
        nephele.cloud_density(np.zeros((2, 2)))


def test_scene_parameters_give_each_key_its_range_unit_and_default():
    params = {p["key"]: p for p in nephele.scene_parameters()}
    coverage = params["clouds.coverage"]
    assert (coverage["min"], coverage["max"], coverage["allowed"]) == (0.0, 1.0, "[0, 1]")
    assert params["clouds.bottom_altitude_m"]["unit"] == "m"
    assert params["clouds.weather_evolution_s"]["off"] == 0.0
    assert params["atmosphere.model"]["allowed"] == ["hillaire", "preetham", "reference"]
    assert params["time"]["min"] is None


def test_rain_and_snow_from_python():
    params = {p["key"]: p for p in nephele.scene_parameters()}
    assert params["precipitation.rate_mm_per_h"]["unit"] == "mm/h"
    assert params["precipitation.kind"]["allowed"] == '"rain", "drizzle", "snow" or "sleet"'
    pixel_luminance = lambda im: im[..., :3] @ np.array([0.2126, 0.7152, 0.0722])
    deck = {"clouds.coverage": 0.9, "camera.view_dir": [0.0, 1.0, 0.1]}
    dry = nephele.render(width=24, height=16, scene=deck)
    snow = nephele.render(width=24, height=16, scene={**deck, "precipitation.kind": "snow",
                                                      "precipitation.rate_mm_per_h": 3.0})
    # Heavy snow, 400 m of visibility: the deck and the ground behind a grey veil.
    assert np.std(pixel_luminance(snow)) < 0.5 * np.std(pixel_luminance(dry))
