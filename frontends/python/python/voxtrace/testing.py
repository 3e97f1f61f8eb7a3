"""Golden-image tests for pytest: ``assert_golden(image, path)``."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Union

import numpy as np

from . import Image, _voxtrace


def _read_png(path: Path) -> np.ndarray:
    width, height, rgba = _voxtrace.decode_png(path.read_bytes())
    return np.frombuffer(rgba, dtype=np.uint8).reshape(height, width, 4)


def assert_golden(image: np.ndarray, path: Union[str, os.PathLike]) -> None:
    """Asserts that ``image`` is, pixel for pixel, the PNG at ``path``. With
    ``UPDATE_GOLDEN=1`` in the environment it writes ``image`` there
    instead. On a difference it writes ``failed/NAME.actual.png`` and
    ``failed/NAME.diff.png`` (differing pixels red on gray) beside the
    golden image and raises ``AssertionError`` naming them."""
    golden = Path(path)
    actual = np.asarray(image, dtype=np.uint8).view(Image)
    if os.environ.get("UPDATE_GOLDEN"):
        actual.save(golden)
        return
    if not golden.exists():
        raise AssertionError(f"{golden} does not exist: run with UPDATE_GOLDEN=1 to write it")
    expected = _read_png(golden)
    if expected.shape == actual.shape and np.array_equal(expected, actual):
        return
    failed = golden.parent / "failed"
    failed.mkdir(exist_ok=True)
    stem = golden.stem
    actual.save(failed / f"{stem}.actual.png")
    if expected.shape != actual.shape:
        raise AssertionError(
            f"{golden} is {expected.shape[1]}x{expected.shape[0]}, the image "
            f"{actual.shape[1]}x{actual.shape[0]}; actual image: {failed / (stem + '.actual.png')}"
        )
    differ = np.any(expected != actual, axis=2)
    largest = int(np.abs(expected.astype(int) - actual.astype(int)).max())
    diff = np.empty_like(actual)
    gray = (actual[..., :3].mean(axis=2) * 0.5).astype(np.uint8)
    diff[..., 0] = np.where(differ, 255, gray)
    diff[..., 1] = np.where(differ, 0, gray)
    diff[..., 2] = np.where(differ, 0, gray)
    diff[..., 3] = 255
    diff.view(Image).save(failed / f"{stem}.diff.png")
    raise AssertionError(
        f"{int(differ.sum())} of {differ.size} pixels differ from {golden} (largest channel "
        f"difference {largest}); actual image: {failed / (stem + '.actual.png')}, diff: "
        f"{failed / (stem + '.diff.png')}; run with UPDATE_GOLDEN=1 to accept"
    )
