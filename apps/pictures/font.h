// apps/pictures/font.h — a tiny built-in 5x7 bitmap font (our own glyphs) for numbers, labels and
// titles in rendered images: digits, A-Z, a-z, space and . , - + : ( ) / = _ % ! ? * [ ] < > ' | ^.
// Glyphs are 5 x 7 units and advance 6 units; `scale` multiplies units into pixels. The
// descender letters g, p, q, y are drawn 2 units lower (their last two rows below the line).
#pragma once

#include <array>
#include <string>

#include "polydec/apps/pictures/image.h"

namespace polydec {

// The 7 rows (top first) of 5 columns of a glyph, '#' = ink, '.' = paper. Characters without a
// glyph are drawn as '?'.
const std::array<const char*, 7>& glyph(char c);
// Whether c is drawn 2 units lower (g, p, q, y).
bool is_descender(char c);
// Whether the font has a glyph of its own for c.
bool has_glyph(char c);

constexpr int kGlyphWidth = 5, kGlyphHeight = 7, kGlyphAdvance = 6;

// Width and height in pixels of `text` drawn at `scale` (single line).
int text_width(const std::string& text, int scale);
inline int text_height(int scale) { return kGlyphHeight * scale; }

// Draws `text` with its top-left corner at pixel (x, y).
void draw_text(Image& img, int x, int y, const std::string& text, const Color& color, int scale);

}  // namespace polydec
