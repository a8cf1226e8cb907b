"""Volumes from numpy without a copy, their round trips, and their errors."""
import gc
import weakref

import numpy as np
import pytest

import penumbra
from conftest import blob, small_scene

VOXEL_TYPES = [np.uint8, np.int8, np.uint16, np.int16, np.uint32, np.int32, np.float32, np.float64]


@pytest.mark.parametrize("dtype", VOXEL_TYPES)
def test_every_voxel_type_wraps_without_a_copy_and_round_trips(dtype):
    array = blob((6, 5, 4), dtype)
    volume = penumbra.Volume(array, spacing=(0.5, 1.0, 2.0))
    assert volume.shares_memory
    assert volume.dims == (4, 5, 6)  # (x, y, z) of an array[z, y, x]
    assert volume.shape == array.shape
    assert volume.dtype == array.dtype
    out = volume.to_numpy()
    assert out.dtype == array.dtype and out.shape == array.shape
    assert np.shares_memory(out, array)
    assert np.array_equal(out, array)
    assert volume.value_range() == (pytest.approx(float(array.min())), pytest.approx(float(array.max())))
    # The box: voxel centres spaced (0.5, 1, 2), centred at the origin.
    lower, upper = volume.bounds
    assert upper == pytest.approx((0.75, 2.0, 5.0)) and lower == pytest.approx((-0.75, -2.0, -5.0))


def test_the_volume_keeps_the_array_alive():
    array = blob()
    alive = weakref.ref(array)
    volume = penumbra.Volume(array)
    expected = array.copy()
    del array
    gc.collect()
    assert alive() is not None
    assert np.array_equal(volume.to_numpy(), expected)
    view = volume.to_numpy()
    del volume
    gc.collect()
    assert alive() is not None  # the view keeps the volume, which keeps the array
    del view
    gc.collect()
    assert alive() is None


def test_a_scene_keeps_the_volume_alive_and_renders_the_array():
    array = blob()
    alive = weakref.ref(array)
    scene = small_scene(volume=array)
    del array
    gc.collect()
    assert alive() is not None
    image = penumbra.Renderer(scene, "emission-absorption").render()
    assert image[..., 3].max() > 0.1


def test_layouts_that_cannot_be_wrapped_are_copied_or_refused():
    array = blob((8, 8, 8))
    for other in (array[:, :, ::2], np.asfortranarray(array), array.astype(">f4")):
        volume = penumbra.Volume(other)
        assert not np.shares_memory(volume.to_numpy(), other)
        assert np.array_equal(volume.to_numpy(), other)
        with pytest.raises(ValueError, match="copy"):
            penumbra.Volume(other, copy=False)
    copied = penumbra.Volume(array, copy=True)
    assert not np.shares_memory(copied.to_numpy(), array)


def test_bad_arrays_raise_value_errors_naming_the_problem():
    with pytest.raises(ValueError, match="int64"):
        penumbra.Volume(np.zeros((4, 4, 4), dtype=np.int64))
    with pytest.raises(ValueError, match="3D"):
        penumbra.Volume(np.zeros((4, 4)))
    with pytest.raises(ValueError, match="dimensions must be positive"):
        penumbra.Volume(np.zeros((0, 4, 4), dtype=np.uint8))
    with pytest.raises(penumbra.ParameterError) as error:
        penumbra.Volume(blob(), spacing=(1, 0, 1))
    assert error.value.name == "spacing"
    with pytest.raises(ValueError, match="3 numbers"):
        penumbra.Volume(blob(), spacing=(1, 1))


def test_views_are_read_only_and_modified_refreshes_the_range():
    array = blob()
    volume = penumbra.Volume(array)
    with pytest.raises(ValueError):
        volume.to_numpy()[0, 0, 0] = 5
    highest = volume.value_range()[1]
    array[0, 0, 0] = 7.0
    assert volume.value_range()[1] == highest  # cached
    volume.modified()
    assert volume.value_range()[1] == pytest.approx(7.0)


def test_a_4d_array_is_a_time_series():
    series = np.stack([blob(), 0.5 * blob()])
    volume = penumbra.Volume(series)
    assert volume.frames == 2 and volume.shape == series.shape and volume.dims == (16, 18, 20)
    assert np.shares_memory(volume.to_numpy(), series)
    assert np.array_equal(volume.to_numpy(frame=1), series[1])
    assert volume.value_range(1)[1] == pytest.approx(0.5 * volume.value_range(0)[1])
    first = penumbra.Renderer(small_scene(volume=volume, transfer_function={"points": [[0, 1, 1, 1, 0], [1, 1, 1, 1, 1]], "range": [0, 1]}), "emission-absorption")
    a = first.render()
    assert first.update(time_step=1) == ["data"]
    b = first.render()
    assert b[..., 3].sum() < a[..., 3].sum()  # the second frame is half as dense
    with pytest.raises(penumbra.SceneError):
        first.update(time_step=2)


def test_save_and_read_volume_round_trip(tmp_path):
    series = np.stack([blob(dtype=np.int16), blob(dtype=np.int16) // 2])
    for name in ("v.nrrd", "v.nhdr", "v.mha"):
        penumbra.Volume(series, spacing=(0.5, 0.75, 2.0), origin=(1, 2, 3)).save(tmp_path / name)
        back = penumbra.read_volume(tmp_path / name)
        assert back.frames == 2 and back.dtype == np.int16
        assert back.spacing == pytest.approx((0.5, 0.75, 2.0)) and back.origin == pytest.approx((1, 2, 3))
        assert np.array_equal(back.to_numpy(), series)
        assert not back.shares_memory
    single = penumbra.Volume(blob(dtype=np.uint8))
    single.save(tmp_path / "v.vti")
    read = penumbra.read_volume(tmp_path / "v.vti")
    assert np.array_equal(read.to_numpy(), single.to_numpy())
    assert np.shares_memory(read.to_numpy(), read.to_numpy())  # a view of the volume's own frame
    assert np.array_equal(np.asarray(read), single.to_numpy())
    with pytest.raises(ValueError, match="vti"):
        penumbra.Volume(series).save(tmp_path / "s.vti")
    with pytest.raises(ValueError, match=".nrrd"):
        single.save(tmp_path / "v.png")


def test_unreadable_volume_files_raise_os_errors(tmp_path):
    with pytest.raises(OSError) as error:
        penumbra.read_volume(tmp_path / "missing.nrrd")
    assert "missing.nrrd" in str(error.value) and error.value.filename.endswith("missing.nrrd")
    truncated = tmp_path / "truncated.nrrd"
    truncated.write_bytes(b"NRRD0004\ntype: uint8\ndimension: 3\nsizes: 64 64 64\nencoding: raw\n\nabc")
    with pytest.raises(OSError, match="truncated.nrrd"):
        penumbra.read_volume(truncated)
