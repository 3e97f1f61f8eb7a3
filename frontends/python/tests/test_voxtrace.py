"""The Python package against the CLI, byte for byte, and its refusals.

The CLI comparisons need ``VOXTRACE_BIN`` (the ``voxtrace`` binary, as CI
sets it) and are skipped without it; the shared models under
``../shared/scenes/vox`` are skipped, with a notice, where absent.
"""

import os
import subprocess
import threading
from pathlib import Path

import numpy as np
import pytest

import voxtrace
from voxtrace.testing import assert_golden

ROOT = Path(__file__).resolve().parents[3]
CLI = os.environ.get("VOXTRACE_BIN")
needs_cli = pytest.mark.skipif(not CLI, reason="VOXTRACE_BIN is not set")


def cli_rgb(tmp_path, args, width, height):
    """The RGB bytes the CLI writes for ``args`` at ``width`` x ``height``."""
    out = tmp_path / "cli.ppm"
    size = ["--width", str(width), "--height", str(height)]
    subprocess.run([CLI, *args, *size, "--format", "ppm", "--out", str(out)], check=True,
                   capture_output=True)
    return out.read_bytes()[-width * height * 3:]


@needs_cli
@pytest.mark.parametrize("threads", [1, 0])
def test_the_terrain_is_the_clis_bytes(tmp_path, threads):
    image = voxtrace.render_terrain(seed=1, size=100, width=320, height=180,
                                    position=(90, 90, 90), lookat=(0, 0, 0), shadows=True,
                                    ao=4, threads=threads)
    args = ["--seed", "1", "--size", "100", "--position", "90,90,90", "--lookat", "0,0,0",
            "--shadows", "--ao", "4"]
    assert image[..., :3].tobytes() == cli_rgb(tmp_path, args, 320, 180)
    # The default view: the paper's camera.
    default = voxtrace.render_terrain(seed=3, size=60, width=160, height=90)
    assert default[..., :3].tobytes() == cli_rgb(tmp_path, ["--seed", "3", "--size", "60"], 160, 90)


@needs_cli
def test_a_vox_file_is_the_clis_bytes(tmp_path):
    model = ROOT / "docs" / "terrain.vox"
    image = voxtrace.render_vox(model, width=160, height=90)
    assert image[..., :3].tobytes() == cli_rgb(tmp_path, ["--vox", str(model)], 160, 90)
    draft = voxtrace.render_vox(model, width=160, height=90, quality="draft", fog=True,
                                position=(60, 80, 60), lookat=(0, 40, 0), fov=40)
    args = ["--vox", str(model), "--quality", "draft", "--fog", "--position", "60,80,60",
            "--lookat", "0,40,0", "--fov", "40"]
    assert draft[..., :3].tobytes() == cli_rgb(tmp_path, args, 160, 90)


@needs_cli
@pytest.mark.parametrize("keywords, flags", [
    ({"orbit": (200, 20)}, ["--orbit", "200,20"]),
    ({"orbit": (30, 45, 90), "fov": 35}, ["--orbit", "30,45,90", "--fov", "35"]),
    ({"view": "iso"}, ["--view", "iso"]),
    ({"view": "top", "lookat": (0, 40, 0)}, ["--view", "top", "--lookat", "0,40,0"]),
])
def test_orbits_and_views_are_the_clis(tmp_path, keywords, flags):
    model = ROOT / "docs" / "terrain.vox"
    image = voxtrace.render_vox(model, width=160, height=90, quality="draft", **keywords)
    args = ["--vox", str(model), "--quality", "draft", *flags]
    assert image[..., :3].tobytes() == cli_rgb(tmp_path, args, 160, 90)


@needs_cli
@pytest.mark.parametrize("name", ["chr_riotcop.vox", "O1-COLORED.vox"])
def test_a_shared_model_is_the_clis_bytes(tmp_path, name):
    model = ROOT.parent / "shared" / "scenes" / "vox" / name
    if not model.exists():
        pytest.skip(f"notice: {model} is absent")
    image = voxtrace.render_vox(model, width=96, height=54, spp=2)
    args = ["--vox", str(model), "--spp", "2"]
    assert image[..., :3].tobytes() == cli_rgb(tmp_path, args, 96, 54)


def test_a_generated_volume_shows_its_palette():
    volume = np.zeros((12, 6, 10), dtype=np.uint8)
    volume[:, 0, :] = 1  # a floor
    volume[4:7, 1:5, 3:6] = 2  # a block on it
    palette = np.zeros((256, 3), dtype=np.uint8)
    palette[1] = (200, 0, 0)
    palette[2] = (0, 0, 200)
    image = voxtrace.render(volume, palette, width=120, height=80)
    one = voxtrace.render(volume, palette, width=120, height=80, threads=1)
    assert np.array_equal(image, one)
    sky = image[0, 0]
    model = image[np.any(image != sky, axis=2)]
    assert len(model) > 1000
    # Every pixel of the volume is a shade of red or blue.
    reds = (model[:, 1] == 0) & (model[:, 2] == 0) & (model[:, 0] > 0)
    blues = (model[:, 0] == 0) & (model[:, 1] == 0) & (model[:, 2] > 0)
    assert np.all(reds | blues) and reds.any() and blues.any()
    # Index order: x is the first axis. Moving the block moves the picture.
    moved = np.zeros_like(volume)
    moved[:, 0, :] = 1
    moved[7:10, 1:5, 3:6] = 2
    assert not np.array_equal(voxtrace.render(moved, palette, width=120, height=80), image)


def test_a_256_cubed_random_volume_renders():
    rng = np.random.default_rng(7)
    volume = np.where(rng.random((256, 256, 256)) < 0.02, rng.integers(1, 256, (256, 256, 256)),
                      0).astype(np.uint8)
    image = voxtrace.render(volume, width=160, height=90)
    assert image.shape == (90, 160, 4) and image.dtype == np.uint8
    assert len(np.unique(image.reshape(-1, 4), axis=0)) > 100


@pytest.mark.parametrize("call, error, words", [
    (lambda: voxtrace.render(np.zeros((4, 4), np.uint8)), ValueError, "3-dimensional"),
    (lambda: voxtrace.render(np.zeros((4, 4, 4), np.float32)), TypeError, "uint8"),
    (lambda: voxtrace.render(np.ones((4, 4, 4), np.uint8), np.zeros((255, 3), np.uint8)),
     ValueError, "(256, 3)"),
    (lambda: voxtrace.render(np.ones((4, 4, 4), np.uint8), np.zeros((256, 3), np.int64)),
     TypeError, "uint8"),
    (lambda: voxtrace.render(np.zeros((0, 4, 4), np.uint8)), ValueError, "0x4x4"),
    (lambda: voxtrace.render_terrain(seed=1, size=20, width=32, height=18,
                                     position=(float("nan"), 1, 1), lookat=(0, 0, 0)),
     ValueError, ""),
    (lambda: voxtrace.render_terrain(seed=1, size=20, width=32, height=18,
                                     position=(5, 5, 5), lookat=(5, 5, 5)), ValueError, ""),
    (lambda: voxtrace.render_terrain(seed=1, size=0), ValueError, "size 0"),
    (lambda: voxtrace.render_terrain(seed=1, size=20, width=0, height=18), ValueError, ""),
    (lambda: voxtrace.render_terrain(seed=1, size=20, quality="best"), ValueError, "best"),
    (lambda: voxtrace.render_terrain(seed=1, size=20, backend="kd"), ValueError, "kd"),
    (lambda: voxtrace.render_terrain(seed=1, size=20, fov=30), ValueError, "position"),
    (lambda: voxtrace.render_vox("/nonexistent/model.vox"), FileNotFoundError, "model.vox"),
    (lambda: voxtrace.render_terrain(seed=1, size=20, view="side"), ValueError, "side"),
    (lambda: voxtrace.render_terrain(seed=1, size=20, view="iso", orbit=(0, 30)), ValueError,
     "one of"),
    (lambda: voxtrace.render_terrain(seed=1, size=20, orbit=(0,)), ValueError, "orbit"),
])
def test_bad_input_raises_the_right_exception(call, error, words):
    with pytest.raises(error) as raised:
        call()
    assert words in str(raised.value)


def test_a_damaged_vox_file_is_a_value_error(tmp_path):
    bad = tmp_path / "bad.vox"
    bad.write_bytes((ROOT / "docs" / "terrain.vox").read_bytes()[:40])
    with pytest.raises(ValueError):
        voxtrace.render_vox(bad, width=32, height=18)
    with pytest.raises(ValueError, match="frame"):
        voxtrace.render_vox(ROOT / "docs" / "terrain.vox", frame=3, width=32, height=18)


def test_two_python_threads_render_at_once():
    def frame(seed):
        return voxtrace.render_terrain(seed=seed, size=50, width=160, height=90, ao=2, spp=2)

    expected = {seed: frame(seed) for seed in (1, 2)}
    got = {}
    threads = [threading.Thread(target=lambda s=s: got.__setitem__(s, frame(s))) for s in (1, 2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert all(np.array_equal(got[s], expected[s]) for s in (1, 2))


def test_save_writes_a_png_and_golden_images_catch_a_pixel(tmp_path, monkeypatch):
    image = voxtrace.render_terrain(seed=2, size=30, width=64, height=36)
    assert image._repr_png_().startswith(b"\x89PNG\r\n\x1a\n")
    golden = tmp_path / "terrain.png"
    with pytest.raises(AssertionError, match="UPDATE_GOLDEN=1"):
        assert_golden(image, golden)
    monkeypatch.setenv("UPDATE_GOLDEN", "1")
    assert_golden(image, golden)
    monkeypatch.delenv("UPDATE_GOLDEN")
    assert oct(golden.stat().st_mode & 0o777) != oct(0o600)
    assert_golden(image, golden)
    changed = image.copy()
    changed[5, 7, 0] ^= 0xFF
    with pytest.raises(AssertionError, match="1 of 2304 pixels differ"):
        assert_golden(changed, golden)
    assert (tmp_path / "failed" / "terrain.actual.png").exists()
    assert (tmp_path / "failed" / "terrain.diff.png").exists()
