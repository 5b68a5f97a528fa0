"""Reprints (revision 3): categories whose labels drew a wordmark (a row of letter-like
strokes, read as "Lnol" or "oluo") print what the product is instead, in words that read
upright and left to right from outside. A reprint (``reprint``, under the category's
``generator``) builds what the build it decorates builds and swaps each wordmark label
(``label``, ``sticker``, ``wave``) for the same layout printing the words
(``<layout>_words_<key>``, ``<layout>_around_<key>`` round a cylinder: same band, pictogram
and inks).

A box label whose largest face is its top (a band round a flat pack) is turned a quarter
about z, its half extents swapped to match (the same box), so its words are read from the
front (+x) like every printed top. Round a standing cylinder the words face the front by
their layout (``textures.FRONT``).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable

from ..design import Design, Traits
from ..parts import Part
from ..textures import LAYOUTS, WORDS, Texture
from ..vocab import COLORS
from .facing import top_to_front


def reprinted(part: Part, key: str) -> Part:
    """``part`` with its wordmark label printing the words of ``key`` (unchanged when it
    draws no wordmark)."""
    texture = part.texture
    if texture is None or texture.pattern not in LAYOUTS:
        return part
    kind = "around" if part.shape == "cylinder" else "words"
    words = Texture(f"{texture.pattern}_{kind}_{key}", _legible(texture, part.color), texture.motif)
    return top_to_front(dataclasses.replace(part, texture=words))


def _lightness(color: str) -> float:
    r, g, b = COLORS[color]
    return 0.2126 * r + 0.7152 * g + 0.0722 * b


def _apart(a: str, b: str) -> bool:
    """Whether words in colour ``a`` stand out on colour ``b`` (lighter or darker)."""
    return abs(_lightness(a) - _lightness(b)) >= 0.3


def _against(ground: str) -> str:
    """Black or white, whichever stands out more on ``ground``."""
    return "black" if _lightness(ground) > 0.5 else "white"


def _legible(texture: Texture, color: str) -> tuple[str, ...]:
    """The label's inks, where its words would vanish into what they are printed on (a
    wordmark in the label's own colour) the words in black or white instead."""
    inks = list(texture.inks)
    if texture.pattern == "label" and len(inks) == 1:  # the part's colour on the band
        if not _apart(color, inks[0]):
            inks.append(_against(inks[0]))  # then the words print in their own ink
    else:
        on_band = texture.pattern == "label"
        words, ground = (1, inks[0]) if on_band else (0, color)
        if not _apart(inks[words], ground):
            if words == len(inks) - 1:  # the pictogram's ink too (the last): it keeps it
                inks.insert(words, _against(ground))
            else:
                inks[words] = _against(ground)
    return tuple(inks)


def reprint(key: str) -> Callable[[Callable[[Design], Traits]], Callable[[Design], Traits]]:
    """Decorate a build: the returned build builds the same from the same draws, its
    wordmark labels printing the words of ``key`` (a key of ``textures.WORDS``). The build
    it reprints is its ``__wrapped__``."""

    def wrap(before: Callable[[Design], Traits]) -> Callable[[Design], Traits]:
        def build(d: Design) -> Traits:
            traits = before(d)
            d.parts[:] = [reprinted(p, key) for p in d.parts]
            return traits

        build.__name__ = build.__qualname__ = f"{before.__name__}_reprinted"
        build.__doc__ = (
            f"{before.__name__}, its labels printing {' '.join(WORDS[key])} where they drew "
            "a wordmark."
        )
        build.__module__ = before.__module__
        build.__wrapped__ = before
        return build

    return wrap
