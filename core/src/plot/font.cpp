#include "plot/font.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>

#include <stb_truetype.h>   // libstb exports the implementation: no STB_TRUETYPE_IMPLEMENTATION here

#include "impactlab/plot.hpp"

namespace impactlab::plot {
namespace {

struct FontFile {
    std::string path;
    std::vector<unsigned char> data;
    stbtt_fontinfo info{};
};

bool read_file(const std::string& path, std::vector<unsigned char>& out) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return false;
    out.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    return !out.empty();
}

std::unique_ptr<FontFile> load_font(const std::vector<std::string>& candidates) {
    for (const auto& path : candidates) {
        auto font = std::make_unique<FontFile>();
        if (!read_file(path, font->data)) continue;
        const int offset = stbtt_GetFontOffsetForIndex(font->data.data(), 0);
        if (offset < 0 || stbtt_InitFont(&font->info, font->data.data(), offset) == 0) continue;
        font->path = path;
        return font;
    }
    if (candidates.empty())
        throw std::runtime_error("impactlab::plot: no font was handed in (the program calls plot::set_font_files)");
    std::string msg = "impactlab::plot: no usable TrueType font found; tried:";
    for (const auto& path : candidates) msg += " " + path;
    throw std::runtime_error(msg);
}

// The files the program handed in, and the font once loaded. The loaded font is never replaced: the glyph
// cache and every GlyphSet point into it. Text is drawn from many threads (scan tiles), so the loaded
// font is published through an atomic and read without the lock.
std::mutex g_font_mutex;
std::vector<std::string> g_font_files;
std::unique_ptr<const FontFile> g_font;
std::atomic<const FontFile*> g_font_loaded{nullptr};

const FontFile& font_file() {
    if (const FontFile* f = g_font_loaded.load(std::memory_order_acquire)) return *f;
    const std::lock_guard<std::mutex> lock(g_font_mutex);
    if (!g_font) {   // a failed load leaves nothing behind, so a later call tries again
        g_font = load_font(g_font_files);
        g_font_loaded.store(g_font.get(), std::memory_order_release);
    }
    return *g_font;
}

}  // namespace

void set_font_files(std::vector<std::string> candidates) {
    const std::lock_guard<std::mutex> lock(g_font_mutex);
    if (!g_font) g_font_files = std::move(candidates);
}

const std::string& font_path() { return font_file().path; }

std::string first_usable_font(const std::vector<std::string>& candidates) { return load_font(candidates)->path; }

namespace detail {

GlyphSet::GlyphSet(int pixel_size) : size_(pixel_size) {
    const stbtt_fontinfo* info = &font_file().info;
    scale_ = stbtt_ScaleForMappingEmToPixels(info, static_cast<float>(pixel_size));
    int asc = 0, desc = 0, gap = 0;
    stbtt_GetFontVMetrics(info, &asc, &desc, &gap);
    ascent_ = static_cast<float>(asc) * scale_;
    descent_ = static_cast<float>(desc) * scale_;

    ascii_.resize(128);
    const int question = stbtt_FindGlyphIndex(info, '?');
    for (int cp = 0; cp < 128; ++cp) {
        const int index = cp >= 32 && cp < 127 ? stbtt_FindGlyphIndex(info, cp) : 0;
        ascii_[static_cast<std::size_t>(cp)] = bake(index != 0 || cp == ' ' ? index : question);
    }
    cap_ = static_cast<float>(-ascii_[static_cast<std::size_t>('0')].phase[0].y0);
}

Glyph GlyphSet::bake(int glyph_index) const {
    const stbtt_fontinfo* info = &font_file().info;
    Glyph g;
    g.index = glyph_index;
    int adv = 0, lsb = 0;
    stbtt_GetGlyphHMetrics(info, glyph_index, &adv, &lsb);
    g.advance = static_cast<float>(adv) * scale_;
    for (int p = 0; p < kSubpixel; ++p) {
        const float shift = static_cast<float>(p) / kSubpixel;
        GlyphBitmap& b = g.phase[static_cast<std::size_t>(p)];
        int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
        stbtt_GetGlyphBitmapBoxSubpixel(info, glyph_index, scale_, scale_, shift, 0.0f, &x0, &y0, &x1, &y1);
        b.x0 = x0;
        b.y0 = y0;
        b.w = std::max(0, x1 - x0);
        b.h = std::max(0, y1 - y0);
        b.alpha.assign(static_cast<std::size_t>(b.w) * static_cast<std::size_t>(b.h), 0);
        if (b.w > 0 && b.h > 0)
            stbtt_MakeGlyphBitmapSubpixel(info, b.alpha.data(), b.w, b.h, b.w, scale_, scale_, shift, 0.0f, glyph_index);
    }
    return g;
}

const Glyph& GlyphSet::glyph(char32_t codepoint) const {
    if (codepoint < 128) return ascii_[codepoint];
    const std::lock_guard<std::mutex> lock(mutex_);
    auto it = others_.find(codepoint);
    if (it == others_.end()) {
        const int index = codepoint <= 0x10FFFF ? stbtt_FindGlyphIndex(&font_file().info, static_cast<int>(codepoint)) : 0;
        it = others_.emplace(codepoint, index != 0 ? std::make_unique<const Glyph>(bake(index)) : nullptr).first;
    }
    return it->second ? *it->second : ascii_[static_cast<std::size_t>('?')];
}

float GlyphSet::kern(const Glyph& left, const Glyph& right) const {
    return static_cast<float>(stbtt_GetGlyphKernAdvance(&font_file().info, left.index, right.index)) * scale_;
}

const GlyphSet& glyphs(int pixel_size) {
    static std::mutex mutex;
    static std::map<int, std::unique_ptr<const GlyphSet>> cache;
    const std::lock_guard<std::mutex> lock(mutex);
    auto& slot = cache[pixel_size];
    if (!slot) {
        try {
            slot = std::make_unique<const GlyphSet>(pixel_size);
        } catch (...) {
            cache.erase(pixel_size);
            throw;
        }
    }
    return *slot;
}

std::u32string decode_utf8(std::string_view text) {
    std::u32string out;
    out.reserve(text.size());
    std::size_t i = 0;
    while (i < text.size()) {
        const auto c = static_cast<unsigned char>(text[i]);
        int len = 0;
        char32_t cp = 0;
        if (c < 0x80) { len = 1; cp = c; }
        else if ((c & 0xE0) == 0xC0) { len = 2; cp = c & 0x1Fu; }
        else if ((c & 0xF0) == 0xE0) { len = 3; cp = c & 0x0Fu; }
        else if ((c & 0xF8) == 0xF0) { len = 4; cp = c & 0x07u; }
        bool ok = len > 0 && i + static_cast<std::size_t>(len) <= text.size();
        for (int k = 1; ok && k < len; ++k) {
            const auto cc = static_cast<unsigned char>(text[i + static_cast<std::size_t>(k)]);
            if ((cc & 0xC0) != 0x80) ok = false;
            cp = (cp << 6) | (cc & 0x3Fu);
        }
        if (!ok) { out.push_back(0xFFFD); ++i; continue; }
        out.push_back(cp);
        i += static_cast<std::size_t>(len);
    }
    return out;
}

namespace {

struct Placed {
    const GlyphBitmap* bitmap;
    int x;   // pen column (integer part); the bitmap starts at x + bitmap->x0
};

// Lays out the glyphs of one line; returns the pen advance.
float place(const GlyphSet& gs, const std::u32string& text, std::vector<Placed>* out) {
    float pen = 0;
    const Glyph* prev = nullptr;
    for (char32_t cp : text) {
        const Glyph& g = gs.glyph(cp);
        if (prev != nullptr) pen += gs.kern(*prev, g);
        int ipen = static_cast<int>(std::floor(pen));
        int phase = static_cast<int>(std::lround((pen - static_cast<float>(ipen)) * kSubpixel));
        if (phase == kSubpixel) { ++ipen; phase = 0; }
        if (out != nullptr) out->push_back({&g.phase[static_cast<std::size_t>(phase)], ipen});
        pen += g.advance;
        prev = &g;
    }
    return pen;
}

}  // namespace

float text_width(std::string_view utf8, int pixel_size) {
    return place(glyphs(pixel_size), decode_utf8(utf8), nullptr);
}

TextMask rasterize(std::string_view utf8, int pixel_size) {
    const GlyphSet& gs = glyphs(pixel_size);
    std::vector<Placed> placed;
    const std::u32string text = decode_utf8(utf8);
    placed.reserve(text.size());
    TextMask m;
    m.advance = place(gs, text, &placed);
    m.ascent = gs.ascent();
    m.descent = gs.descent();
    m.cap_height = gs.cap_height();

    // Extent: the logical box (pen travel x ascent..descent), grown to hold any overhanging ink.
    int xmin = 0, xmax = static_cast<int>(std::ceil(m.advance));
    int ymin = -static_cast<int>(std::ceil(gs.ascent())), ymax = static_cast<int>(std::ceil(-gs.descent()));
    for (const auto& p : placed) {
        if (p.bitmap->w == 0) continue;
        xmin = std::min(xmin, p.x + p.bitmap->x0);
        xmax = std::max(xmax, p.x + p.bitmap->x0 + p.bitmap->w);
        ymin = std::min(ymin, p.bitmap->y0);
        ymax = std::max(ymax, p.bitmap->y0 + p.bitmap->h);
    }
    m.w = xmax - xmin;
    m.h = ymax - ymin;
    m.origin_x = -xmin;
    m.baseline = -ymin;
    m.alpha.assign(static_cast<std::size_t>(m.w) * static_cast<std::size_t>(m.h), 0);
    for (const auto& p : placed) {
        const GlyphBitmap& b = *p.bitmap;
        const int ox = m.origin_x + p.x + b.x0, oy = m.baseline + b.y0;
        for (int r = 0; r < b.h; ++r) {
            std::uint8_t* dst = &m.alpha[static_cast<std::size_t>((oy + r) * m.w + ox)];
            const std::uint8_t* src = &b.alpha[static_cast<std::size_t>(r * b.w)];
            for (int c = 0; c < b.w; ++c) dst[c] = static_cast<std::uint8_t>(std::min(255, dst[c] + src[c]));
        }
    }
    return m;
}

}  // namespace detail
}  // namespace impactlab::plot
