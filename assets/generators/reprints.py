"""Revision 3 reprints: categories whose labels drew a wordmark (a row of letter-like
strokes, read as "Lnol" or "oluo") print what the product is instead, in words that read
upright and left to right from outside. Each reprint builds what the category's previous
build builds and swaps each wordmark label (``label``, ``sticker``, ``wave``) for the same
layout printing the words (``<layout>_words_<key>``, ``<layout>_around_<key>`` round a
cylinder: same band, pictogram and inks).

A box label whose largest face is its top (a band round a flat pack) is turned a quarter
about z, its half extents swapped to match (the same box), so its words are read from the
front (+x) like every printed top. Round a standing cylinder the words face the front by
their layout (``textures.FRONT``).
"""

from __future__ import annotations

import dataclasses

from ..design import Design, Traits
from ..parts import Part
from ..textures import LAYOUTS, WORDS, Texture
from ..vocab import COLORS
from . import food, groceries  # noqa: F401  (the builds reprinted: registered first)
from .facing import top_to_front
from .registry import REVISIONS, revised

#: Category -> the words its labels print (a key of ``textures.WORDS``).
REPRINTS = {
    "canned_coke": "cola",
    "chewing_gum": "gum",
    "chocolate": "chocolate",
    "juice": "juice",
    "milk_carton": "milk",
    "potato_chips": "chips",
}


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


def _reprint(category: str, key: str) -> None:
    before = REVISIONS[category][max(REVISIONS[category])]

    def build(d: Design) -> Traits:
        traits = before.build(d)
        d.parts[:] = [reprinted(p, key) for p in d.parts]
        return traits

    build.__name__ = f"{category}_3"
    build.__doc__ = (
        f"Revision 3: revision {before.revision}'s {category.replace('_', ' ')}, its labels "
        f"printing {' '.join(WORDS[key])} where they drew a wordmark."
    )
    revised(category, 3)(build)


for _category, _key in REPRINTS.items():
    _reprint(_category, _key)
