"""compare() against a reference and the image metrics on arrays."""
import math

import numpy as np
import pytest

import penumbra
from conftest import small_scene


def test_compare_returns_the_report_and_the_images():
    scene = small_scene(size=(24, 20))
    result = penumbra.compare(scene, ["phong", "shadow-rays"], params={"pathtrace": {"spp": 16, "min_spp": 8}},
                              frames=1)
    assert result["image"] == [24, 20] and result["reference"]["technique"] == "pathtrace"
    assert result["reference"]["params"]["spp"] == 16 and result["reference"]["paths"] == 24 * 20 * 16
    assert [t["technique"] for t in result["techniques"]] == ["phong", "shadow-rays"]
    reference = result["images"]["reference"]
    for entry in result["techniques"]:
        image = result["images"][entry["technique"]]
        assert image.shape == (20, 24, 4)
        assert entry["rmse"] == pytest.approx(penumbra.rmse(image, reference), rel=1e-5)
        assert entry["ssim"] == pytest.approx(penumbra.ssim(image, reference), rel=1e-5)
        assert entry["mean_de"] == pytest.approx(float(result["delta_e"][entry["technique"]].mean()), rel=1e-4)
        assert entry["frame_ms"] > 0 and entry["aux_bytes"] >= 0
    errors = {t["technique"]: t["mean_de"] for t in result["techniques"]}
    assert errors["shadow-rays"] < errors["phong"]  # pathtrace in single mode converges to shadow-rays
    assert result["reference_noise_de"].shape == (20, 24)
    assert result["reference_standard_error"].shape == (20, 24, 4)


def test_compare_against_a_stored_image_and_bad_requests():
    scene = small_scene(size=(16, 12))
    stored = penumbra.Renderer(scene, "shadow-rays").render()
    result = penumbra.compare(scene, "shadow-rays", reference_image=stored, frames=1)
    assert result["techniques"][0]["rmse"] == 0.0 and result["techniques"][0]["psnr"] is None  # inf is null in JSON
    assert "technique" not in result["reference"]
    with pytest.raises(ValueError, match="16x12"):
        penumbra.compare(scene, "phong", reference_image=stored[:8])
    with pytest.raises(penumbra.ParameterError, match="teapot"):
        penumbra.compare(scene, ["teapot"])
    with pytest.raises(penumbra.ParameterError, match="no_such"):
        penumbra.compare(scene, ["phong"], params={"no_such": 1})
    with pytest.raises(ValueError, match="frames"):
        penumbra.compare(scene, ["phong"], frames=0)


def test_metrics_on_arrays_agree_with_their_definitions():
    rng = np.random.default_rng(1)
    reference = rng.uniform(0.1, 0.8, (12, 14, 3)).astype(np.float32)
    shifted = reference + 0.1
    assert penumbra.rmse(shifted, reference) == pytest.approx(0.1, rel=1e-5)
    assert penumbra.psnr(shifted, reference) == pytest.approx(20.0, rel=1e-4)  # 10 log10(1 / 0.01)
    assert penumbra.psnr(reference, reference) == math.inf
    assert penumbra.ssim(reference, reference) == 1.0
    assert penumbra.ssim(shifted, reference) < 1.0
    de = penumbra.delta_e_2000(reference, reference)
    assert de.shape == (12, 14) and de.max() == 0.0
    # Black against mid grey (linear 0.2140 = sRGB 0.5, L* 53.39), a pure lightness difference:
    # dE00 = dL / S_L with S_L = 1 + 0.015 (Lm - 50)^2 / sqrt(20 + (Lm - 50)^2), Lm = 26.70: 53.39 / 1.3432.
    black, grey = np.zeros((1, 1, 3)), np.full((1, 1, 3), 0.21404114)
    assert penumbra.delta_e_2000(black, grey)[0, 0] == pytest.approx(39.75, abs=0.02)
    all_metrics = penumbra.compare_images(shifted, reference)
    assert all_metrics["rmse"] == pytest.approx(0.1, rel=1e-5) and all_metrics["mae"] == pytest.approx(0.1, rel=1e-5)
    with pytest.raises(ValueError, match="14x12 image with a 14x6"):
        penumbra.rmse(reference, reference[:6])
    with pytest.raises(ValueError, match="shape"):
        penumbra.rmse(reference[..., 0], reference[..., 0])


def test_images_read_and_write_like_the_cli(tmp_path):
    image = penumbra.Renderer(small_scene(size=(10, 8)), "phong").render()
    penumbra.write_image(tmp_path / "i.exr", image)
    assert np.array_equal(penumbra.read_image(tmp_path / "i.exr"), image)
    penumbra.write_image(tmp_path / "i.png", image)
    assert (tmp_path / "i.png").read_bytes() == image._repr_png_()
    with pytest.raises(ValueError, match=".png or .exr"):
        penumbra.write_image(tmp_path / "i.jpg", image)
    with pytest.raises(OSError):
        penumbra.read_image(tmp_path / "missing.exr")
