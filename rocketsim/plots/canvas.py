"""What every plot shares: matplotlib's pyplot on the non-interactive Agg backend, and a
finished figure written as a PNG file or kept as a :class:`Picture` a notebook shows."""

from __future__ import annotations

import io
from pathlib import Path


def pyplot():
    """``matplotlib.pyplot`` on the Agg backend (no display needed), imported on first use."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


class Picture:
    """A PNG picture; a notebook shows it inline, :meth:`save` writes it."""

    def __init__(self, png: bytes):
        self.png = png

    def _repr_png_(self) -> bytes:
        return self.png

    def save(self, path: str | Path) -> Path:
        Path(path).write_bytes(self.png)
        return Path(path)


def save(figure, out, **options) -> Path | Picture:
    """Write ``figure`` with ``savefig``'s ``options`` to ``out`` (a path or a binary file)
    and return it as a path, or with ``out`` None return it as a PNG :class:`Picture`;
    the figure is closed."""
    try:
        if out is None:
            png = io.BytesIO()
            figure.savefig(png, **{**options, "format": "png"})
            return Picture(png.getvalue())
        figure.savefig(out, **options)
        return Path(out) if isinstance(out, (str, Path)) else out
    finally:
        pyplot().close(figure)
