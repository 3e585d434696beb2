// Internal: text rasterisation with stb_truetype. Glyphs are baked once per pixel size (three horizontal
// sub-pixel phases each) into a process-wide cache; a baked GlyphSet is immutable and may be shared by
// threads.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace impactlab::plot::detail {

inline constexpr int kSubpixel = 3;   // horizontal sub-pixel phases baked per glyph

struct GlyphBitmap {
    int x0 = 0, y0 = 0, w = 0, h = 0;   // offset of the bitmap from the pen position on the baseline
    std::vector<std::uint8_t> alpha;    // w * h coverage values
};

struct Glyph {
    int index = 0;                      // glyph index in the font (for kerning)
    float advance = 0;                  // in px
    std::array<GlyphBitmap, kSubpixel> phase;
};

class GlyphSet {
public:
    explicit GlyphSet(int pixel_size);
    int pixel_size() const { return size_; }
    float ascent() const { return ascent_; }     // > 0, px above the baseline
    float descent() const { return descent_; }   // < 0, px below the baseline
    float cap_height() const { return cap_; }    // height of the digits above the baseline
    // ASCII is baked up front, any other codepoint on first use; one the font lacks shows as '?'.
    // The reference stays valid as long as the set.
    const Glyph& glyph(char32_t codepoint) const;
    float kern(const Glyph& left, const Glyph& right) const;

private:
    Glyph bake(int glyph_index) const;

    int size_;
    float scale_ = 0, ascent_ = 0, descent_ = 0, cap_ = 0;
    std::vector<Glyph> ascii_;                     // indexed by codepoint, 0..127
    mutable std::mutex mutex_;                     // guards others_
    mutable std::unordered_map<char32_t, std::unique_ptr<const Glyph>> others_;   // nullptr: not in the font
};

// The glyphs of one size, baked on first use (thread-safe). Throws std::runtime_error without a font.
const GlyphSet& glyphs(int pixel_size);

// Decodes UTF-8 (invalid bytes become U+FFFD).
std::u32string decode_utf8(std::string_view text);

// Text rendered into a coverage mask. The pen starts at column origin_x on row `baseline`.
struct TextMask {
    int w = 0, h = 0;
    int origin_x = 0, baseline = 0;
    float advance = 0;                  // pen travel in px (the text's logical width)
    float ascent = 0, descent = 0, cap_height = 0;
    std::vector<std::uint8_t> alpha;    // w * h
};

TextMask rasterize(std::string_view utf8, int pixel_size);
float text_width(std::string_view utf8, int pixel_size);

}  // namespace impactlab::plot::detail
