// A 5 x 9 pixel bitmap font (7 above the baseline, 2 for descenders) for the labels of the pictures the verifier writes
// (digits, lower-case letters and the
// signs numbers and units need). Private to src/verify.
#pragma once

namespace rosmill::core::verify {

constexpr int kGlyphWidth = 5, kGlyphHeight = 9;

// Nine rows of five '#' (ink) or '.' for the character, top row first; null for a character without a glyph
// (drawn as a space). Upper-case letters use the lower-case glyphs.
const char* glyph_rows(char c);

}  // namespace rosmill::core::verify
