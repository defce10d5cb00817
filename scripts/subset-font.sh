#!/usr/bin/env bash
# Makes the font that the PNG figures embed: DejaVu Sans cut down to the characters the
# figures use, so the repository carries about 30 kB instead of the 750 kB of the full font.
#
# Usage: scripts/subset-font.sh [SOURCE_TTF]
#   SOURCE_TTF defaults to the system copy /usr/share/fonts/truetype/dejavu/DejaVuSans.ttf
#   (Debian package fonts-dejavu-core, DejaVu 2.37). Needs fonttools' pyftsubset
#   (`pip install fonttools`). Writes crates/hemicontact/assets/fonts/DejaVuSans-subset.ttf.
#
# Characters kept: printable ASCII; Latin-1 signs (° ± ² ³ · × µ ¹ and the no-break space);
# Greek capitals and small letters; superscript and subscript digits and signs (⁰ ⁴–⁹ ⁺ ⁻,
# ₀–₉); dashes, thin space, ‖ ′ … ; arrows ← ↑ → ↓; mathematical signs ∂ ∇ − √ ∞ ≈ ≤ ≥.
# Glyph outlines only: hinting and layout tables (kerning, ligatures) are dropped, since
# the renderer draws one glyph per character at its advance width.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
src="${1:-/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf}"
out="$here/crates/hemicontact/assets/fonts/DejaVuSans-subset.ttf"
pyftsubset "$src" \
    --output-file="$out" \
    --unicodes="U+0020-007E,U+00A0,U+00B0,U+00B1,U+00B2,U+00B3,U+00B5,U+00B7,U+00B9,U+00D7,\
U+0391-03A1,U+03A3-03A9,U+03B1-03C9,U+2009,U+2013,U+2014,U+2016,U+2026,U+2032,\
U+2070,U+2074-207B,U+2080-2089,U+2190-2193,U+2202,U+2207,U+2212,U+221A,U+221E,U+2248,\
U+2264,U+2265" \
    --layout-features='' \
    --no-hinting \
    --drop-tables+=GSUB,GPOS,GDEF,kern,FFTM \
    --name-IDs='*' \
    --name-languages='*' \
    --notdef-outline
echo "wrote $out ($(wc -c <"$out") bytes)"
