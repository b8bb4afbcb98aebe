"""The layout every figure of `asperity.plots` shares.

Figures are made with matplotlib's constrained layout (`subplots`): it makes room
for colour bars, suptitles, tick and axis labels at every draw, so none is clipped
or covered.  It makes room for a title's height but not for its width, so `fit`
narrows every axes title wider than its axes and a suptitle wider than the figure:
a slightly smaller font where that is enough, else the text wrapped at word
boundaries (the text is measured once, after a draw without rendering).
"""

from __future__ import annotations

import textwrap

import matplotlib.pyplot as plt

__all__ = ["subplots", "fit"]


def subplots(nrows: int = 1, ncols: int = 1, **kwargs):
    """`matplotlib.pyplot.subplots` with ``layout="constrained"``."""
    kwargs.setdefault("layout", "constrained")
    return plt.subplots(nrows, ncols, **kwargs)


def _wrap(text, width: float, renderer, shrink: float = 0.85) -> None:
    """Make `text` (a matplotlib Text) at most `width` pixels wide: a font down to
    `shrink` times its size if that is enough (the words stay as they are), else
    each line too long wrapped at word boundaries to the share of characters
    `width` leaves of the widest."""
    if not text.get_visible() or not text.get_text():
        return
    extent = text.get_window_extent(renderer)
    if extent.width <= width:
        return
    if extent.width * shrink <= width:
        text.set_fontsize(text.get_fontsize() * width / extent.width * 0.98)
        return
    lines = text.get_text().split("\n")
    chars = max(12, int(max(map(len, lines)) * width / extent.width * 0.95))
    text.set_text("\n".join(textwrap.fill(line, chars) if len(line) > chars else line
                             for line in lines))


def fit(fig: plt.Figure) -> plt.Figure:
    """Fit each visible axes title to its axes' width and the suptitle to the figure's
    width (`_wrap`), after a draw that runs the layout; the constrained layout gives
    the changed titles their room at the next draw."""
    fig.draw_without_rendering()
    renderer = fig.canvas.get_renderer()
    for ax in fig.axes:
        if ax.get_visible():
            _wrap(ax.title, ax.get_window_extent(renderer).width, renderer)
    if fig._suptitle is not None:
        _wrap(fig._suptitle, 0.98 * fig.bbox.width, renderer)
    return fig
