"""The recognition sheet: one numbered, otherwise unlabelled close-up per category, and a
key whose tiles are the same photographs with the category written under the number."""

from __future__ import annotations

import cv2
import numpy as np

from instructmove_ms.assets import load_snapshot
from instructmove_ms.assets.catalog import plain as snap_plain
from instructmove_ms.assets.sheet import TILE, photograph, recognition_sheet
from instructmove_ms.assets.snapshot import DEFAULT_SNAPSHOT
from instructmove_ms.cli import main

CATEGORIES = ("canned_coke", "apple", "alarm_clock")
KEY_BAND = 40  # pixels at a tile's top where the number and the key's name are written


def test_one_unlabelled_close_up_per_category_and_its_key(tmp_path):
    catalog = load_snapshot()
    instances = [i for i in catalog.instances if i.category in CATEGORIES]
    assert len(instances) > len(CATEGORIES)  # several instances each: one is shown
    sheet_path, key_path = recognition_sheet(instances, tmp_path, columns=2)
    sheet, key = cv2.imread(str(sheet_path)), cv2.imread(str(key_path))
    assert sheet.shape == key.shape == (2 * TILE, 2 * TILE, 3)  # three tiles, two a row
    assert (sheet[TILE:, TILE:] == 255).all() and (key[TILE:, TILE:] == 255).all()
    # each category's first instance, in the order of the identity hashes (not the names)
    first: dict = {}
    for inst in instances:
        first.setdefault(inst.category, inst)
    shown = photograph(sorted(first.values(), key=lambda inst: inst.uuid))
    cells = [(r, c) for r in range(2) for c in range(2)][: len(CATEGORIES)]
    for (r, c), photo in zip(cells, shown, strict=True):
        cell = (slice(r * TILE, (r + 1) * TILE), slice(c * TILE, (c + 1) * TILE))
        plain, keyed = sheet[cell], key[cell]
        assert plain.std() > 5, "a photograph, not a blank"
        below = photo[KEY_BAND:, :, ::-1].astype(int)  # RGB -> the PNG's BGR
        assert np.abs(plain[KEY_BAND:].astype(int) - below).mean() < 2, "another object"
        # the same photograph below the text band; the key writes more in the band
        np.testing.assert_array_equal(plain[KEY_BAND:], keyed[KEY_BAND:])
        written = (plain[:KEY_BAND] != keyed[:KEY_BAND]).any(axis=2).sum()
        assert written > 50, "the key names the category"


def test_the_cli_writes_the_recognition_sheet_for_the_categories_asked(tmp_path, capsys):
    """By default it photographs the default snapshot (``recognisable``, which wears prints):
    the cola can with its print, not the plain one."""
    out = tmp_path / "recognition"
    assert main(["assets", "sheet", "--category", "canned_coke", "--recognition", str(out)]) == 0
    written = capsys.readouterr().out.split()
    assert written == [str(out / "recognition.png"), str(out / "recognition_key.png")]
    sheet = cv2.imread(written[0])
    assert sheet.shape == (TILE, 10 * TILE, 3)  # one category: one tile and nine blanks
    assert (sheet[:, TILE:] == 255).all()
    tile = sheet[KEY_BAND:, :TILE, ::-1].astype(int)
    printed = load_snapshot(DEFAULT_SNAPSHOT).of_category("canned_coke")[0]
    plain = snap_plain(printed)
    seen = [
        np.abs(tile - photograph([i])[0][KEY_BAND:].astype(int)).mean() for i in (printed, plain)
    ]
    assert seen[0] < 2 < seen[1], seen
