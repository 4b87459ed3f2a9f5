"""Browser tests' helpers: headless Chromium through playwright, a file:// page with its console errors and page
errors collected, screenshots as NumPy arrays, and how much two screenshots differ.

Chromium is Debian's (``/usr/bin/chromium``, found on PATH), not playwright's own download; WebGL runs on
SwiftShader (software), so 3-D plots draw on a machine without a GPU. A test calls `chromium_or_skip()` first
(or uses `open_page`, which calls it) and is skipped, with the reason, where Chromium or playwright is missing.

Usage::

    from browser import open_page, screenshot, wait_for_plotly

    def test_page(tmp_path):
        with open_page(tmp_path / "page.html") as (page, errors):
            wait_for_plotly(page)
            image = screenshot(page)
        assert errors == []
"""

from __future__ import annotations

import io
import os
import shutil
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np
import pytest

CHROMIUM_ARGS = ["--no-sandbox", "--use-gl=angle", "--use-angle=swiftshader", "--enable-unsafe-swiftshader"]
"""Chromium's flags: no sandbox (containers), WebGL through ANGLE on SwiftShader (no GPU needed)."""


def chromium_or_skip() -> str:
    """The path of the Chromium executable; skips the test (pytest.skip, with the reason) when Chromium is not
    on PATH or playwright is not installed."""
    executable = shutil.which("chromium") or shutil.which("chromium-browser")
    if executable is None:
        pytest.skip(
            "browser test: no Chromium on PATH (install Debian's chromium, e.g. apt-get install chromium)"
        )
    try:
        import playwright.sync_api  # noqa: F401
    except ImportError:
        pytest.skip(
            "browser test: playwright is not installed (pip install playwright; its browsers are not needed)"
        )
    return executable


@contextmanager
def open_page(
    path: str | os.PathLike[str], *, width: int = 1280, height: int = 800, timeout: float = 30.0
) -> Iterator[tuple[Any, list[str]]]:
    """Opens the local file `path` (file://) in a fresh headless Chromium with a `width` × `height` viewport and
    yields ``(page, errors)``: the playwright Page, and the console errors (``"console: …"``) and uncaught page
    errors (``"page error: …"``) seen so far (the list grows while the page lives). Closes the browser after.
    Skips the test without Chromium or playwright."""
    executable = chromium_or_skip()
    from playwright.sync_api import sync_playwright

    errors: list[str] = []
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path=executable, args=CHROMIUM_ARGS)
        try:
            page = browser.new_page(viewport={"width": width, "height": height})
            page.set_default_timeout(timeout * 1e3)
            page.on("console", lambda message: _console(message, errors))
            page.on("pageerror", lambda error: errors.append(f"page error: {error}"))
            page.goto(Path(path).resolve().as_uri(), wait_until="load")
            yield page, errors
        finally:
            browser.close()


def _console(message: Any, errors: list[str]) -> None:
    if message.type == "error":
        errors.append(f"console: {message.text}")


def wait_for_plotly(page: Any, selector: str = ".js-plotly-plot", timeout: float = 30.0) -> None:
    """Waits until plotly.js is loaded (``window.Plotly``) and has drawn the plot `selector`: its layout is
    computed and, for a 3-D scene, its WebGL canvas exists; then two animation frames more."""
    page.wait_for_function(
        """(selector) => {
            const gd = document.querySelector(selector);
            if (!window.Plotly || !gd || !gd._fullLayout) return false;
            const scenes = Object.keys(gd._fullLayout).filter((k) => /^scene\\d*$/.test(k));
            return scenes.every((k) => gd._fullLayout[k]._scene && gd.querySelector(".gl-container canvas"));
        }""",
        arg=selector,
        timeout=timeout * 1e3,
    )
    frames(page, 2)


def frames(page: Any, count: int = 2) -> None:
    """Waits for `count` animation frames of the page (what was changed is then painted)."""
    page.evaluate(
        """(count) => new Promise((resolve) => {
            const step = (left) => left === 0 ? resolve() : requestAnimationFrame(() => step(left - 1));
            step(count);
        })""",
        count,
    )


def screenshot(page: Any, selector: str | None = None) -> np.ndarray:
    """A screenshot (height, width, 3) uint8 RGB of the page's viewport, or of the element `selector`."""
    from PIL import Image

    png = page.locator(selector).first.screenshot() if selector else page.screenshot()
    return np.asarray(Image.open(io.BytesIO(png)).convert("RGB"))


def settled_screenshot(
    page: Any, selector: str | None = None, timeout: float = 10.0, interval: float = 0.2
) -> np.ndarray:
    """A screenshot once the picture has stopped changing: two in a row, `interval` s apart, identical (or the
    last at `timeout` s)."""
    last = screenshot(page, selector)
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        time.sleep(interval)
        image = screenshot(page, selector)
        if image.shape == last.shape and np.array_equal(image, last):
            return image
        last = image
    return last


def changed_fraction(a: np.ndarray, b: np.ndarray, tolerance: int = 8) -> float:
    """The fraction of pixels whose colour differs by more than `tolerance` (of 255) in some channel between two
    screenshots of the same size."""
    if a.shape != b.shape:
        raise ValueError(f"screenshots of different sizes: {a.shape} and {b.shape}")
    difference = np.abs(a.astype(np.int16) - b.astype(np.int16)).max(axis=-1)
    return float(np.mean(difference > tolerance))


def distinct_colours(image: np.ndarray) -> int:
    """The number of distinct RGB colours of a screenshot."""
    flat = image.reshape(-1, image.shape[-1]).astype(np.uint32)
    return int(np.unique((flat[:, 0] << 16) | (flat[:, 1] << 8) | flat[:, 2]).size)
