#!/usr/bin/env python3
"""Advance widths of DejaVu Sans (font units, 2048 to the em) for the text-width estimate of
src/layout.rs.

Run: python3 scripts/font_widths.py [path/to/DejaVuSans.ttf]   (needs `pip install fonttools`)
and paste the printed table into `ASCII_WIDTHS` and `OTHER_WIDTHS`.
"""
import sys
from fontTools.ttLib import TTFont

path = sys.argv[1] if len(sys.argv) > 1 else "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"
font = TTFont(path)
cmap, hmtx, upm = font.getBestCmap(), font["hmtx"], font["head"].unitsPerEm
print("UNITS_PER_EM:", upm)
print("ASCII_WIDTHS:", ", ".join(str(hmtx[cmap[c]][0]) for c in range(32, 127)))
for ch in "νΣ′″→·≤−²³¹ξτλ…×ū—–“”‘’°±≈":
    print(f"('{ch}', {hmtx[cmap[ord(ch)]][0]}),")
