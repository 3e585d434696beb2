// gzip (RFC 1952) over a small inflate (RFC 1951): canonical Huffman codes decoded bit by bit, in the
// manner of zlib's contrib/puff. Self-contained so that the core needs no zlib; fast enough for the
// data files (~30 MB/s). Every defect is a DataError naming the file.
#include <array>
#include <cstdint>
#include <cstring>
#include <string>

#include "impactlab/identify_data.hpp"

namespace impactlab::identify {

namespace {

struct Corrupt {
    const char* what;
};

struct Bits {
    const unsigned char* in;
    std::size_t n, pos;
    std::uint64_t buf = 0;
    int cnt = 0;

    int need(int k) {
        while (cnt < k) {
            if (pos >= n) throw Corrupt{"the compressed data end too early"};
            buf |= static_cast<std::uint64_t>(in[pos++]) << cnt;
            cnt += 8;
        }
        const int v = static_cast<int>(buf & ((std::uint64_t{1} << k) - 1));
        buf >>= k;
        cnt -= k;
        return v;
    }
    void align() {   // drop the bits left in the current byte
        buf = 0;
        cnt = 0;
    }
};

constexpr int kMaxBits = 15;

struct Huffman {
    std::array<short, kMaxBits + 1> count{};
    std::array<short, 320> symbol{};
};

// Canonical code from code lengths; returns > 0 for an incomplete code (allowed only for single codes).
int build(Huffman& h, const short* length, int n) {
    h.count.fill(0);
    for (int s = 0; s < n; ++s) ++h.count[static_cast<std::size_t>(length[s])];
    if (h.count[0] == n) return 0;
    int left = 1;
    for (int len = 1; len <= kMaxBits; ++len) {
        left <<= 1;
        left -= h.count[static_cast<std::size_t>(len)];
        if (left < 0) throw Corrupt{"an over-subscribed Huffman code"};
    }
    std::array<short, kMaxBits + 1> offs{};
    for (int len = 1; len < kMaxBits; ++len)
        offs[static_cast<std::size_t>(len + 1)] =
            static_cast<short>(offs[static_cast<std::size_t>(len)] + h.count[static_cast<std::size_t>(len)]);
    for (int s = 0; s < n; ++s)
        if (length[s] != 0) h.symbol[static_cast<std::size_t>(offs[static_cast<std::size_t>(length[s])]++)] = static_cast<short>(s);
    return left;
}

int decode(Bits& b, const Huffman& h) {
    int code = 0, first = 0, index = 0;
    for (int len = 1; len <= kMaxBits; ++len) {
        code |= b.need(1);
        const int count = h.count[static_cast<std::size_t>(len)];
        if (code - count < first) return h.symbol[static_cast<std::size_t>(index + (code - first))];
        index += count;
        first += count;
        first <<= 1;
        code <<= 1;
    }
    throw Corrupt{"an invalid Huffman code"};
}

constexpr short kLenBase[29] = {3, 4, 5, 6, 7, 8, 9, 10, 11, 13, 15, 17, 19, 23, 27, 31,
                                35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
constexpr short kLenExtra[29] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
constexpr short kDistBase[30] = {1, 2, 3, 4, 5, 7, 9, 13, 17, 25, 33, 49, 65, 97, 129,
                                 193, 257, 385, 513, 769, 1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
constexpr short kDistExtra[30] = {0, 0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 6, 6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13};

void codes(Bits& b, std::string& out, std::size_t start, const Huffman& lencode, const Huffman& distcode) {
    for (;;) {
        int sym = decode(b, lencode);
        if (sym < 256) {
            out.push_back(static_cast<char>(sym));
        } else if (sym == 256) {
            return;
        } else {
            sym -= 257;
            if (sym >= 29) throw Corrupt{"an invalid length code"};
            const int len = kLenBase[sym] + b.need(kLenExtra[sym]);
            const int ds = decode(b, distcode);
            if (ds >= 30) throw Corrupt{"an invalid distance code"};
            const std::size_t dist = static_cast<std::size_t>(kDistBase[ds] + b.need(kDistExtra[ds]));
            if (dist > out.size() - start) throw Corrupt{"a distance too far back"};
            std::size_t from = out.size() - dist;
            for (int i = 0; i < len; ++i) out.push_back(out[from++]);
        }
    }
}

void stored(Bits& b, std::string& out) {
    b.align();
    if (b.pos + 4 > b.n) throw Corrupt{"the compressed data end too early"};
    const unsigned len = b.in[b.pos] | (b.in[b.pos + 1] << 8);
    const unsigned nlen = b.in[b.pos + 2] | (b.in[b.pos + 3] << 8);
    b.pos += 4;
    if (len != (~nlen & 0xffffu)) throw Corrupt{"a stored block with a bad length"};
    if (b.pos + len > b.n) throw Corrupt{"the compressed data end too early"};
    out.append(reinterpret_cast<const char*>(b.in + b.pos), len);
    b.pos += len;
}

void fixed(Bits& b, std::string& out, std::size_t start) {
    static const auto tables = [] {
        std::pair<Huffman, Huffman> t;
        short lengths[288];
        for (int s = 0; s < 288; ++s) lengths[s] = s < 144 ? 8 : s < 256 ? 9 : s < 280 ? 7 : 8;
        build(t.first, lengths, 288);
        for (int s = 0; s < 30; ++s) lengths[s] = 5;
        build(t.second, lengths, 30);
        return t;
    }();
    codes(b, out, start, tables.first, tables.second);
}

void dynamic(Bits& b, std::string& out, std::size_t start) {
    static constexpr short order[19] = {16, 17, 18, 0, 8, 7, 9, 6, 10, 5, 11, 4, 12, 3, 13, 2, 14, 1, 15};
    const int nlen = b.need(5) + 257, ndist = b.need(5) + 1, ncode = b.need(4) + 4;
    if (nlen > 286 || ndist > 30) throw Corrupt{"bad code counts"};
    short lengths[320] = {};
    for (int i = 0; i < ncode; ++i) lengths[order[i]] = static_cast<short>(b.need(3));
    Huffman lencode, distcode;
    if (build(lencode, lengths, 19) != 0) throw Corrupt{"an incomplete code-length code"};
    int index = 0;
    while (index < nlen + ndist) {
        int sym = decode(b, lencode);
        if (sym < 16) {
            lengths[index++] = static_cast<short>(sym);
        } else {
            short len = 0;
            if (sym == 16) {
                if (index == 0) throw Corrupt{"a repeat with no previous length"};
                len = lengths[index - 1];
                sym = 3 + b.need(2);
            } else if (sym == 17) {
                sym = 3 + b.need(3);
            } else {
                sym = 11 + b.need(7);
            }
            if (index + sym > nlen + ndist) throw Corrupt{"too many code lengths"};
            while (sym--) lengths[index++] = len;
        }
    }
    if (lengths[256] == 0) throw Corrupt{"no end-of-block code"};
    const int err1 = build(lencode, lengths, nlen);
    if (err1 < 0 || (err1 > 0 && nlen - lencode.count[0] != 1)) throw Corrupt{"an incomplete literal/length code"};
    const int err2 = build(distcode, lengths + nlen, ndist);
    if (err2 < 0 || (err2 > 0 && ndist - distcode.count[0] != 1)) throw Corrupt{"an incomplete distance code"};
    codes(b, out, start, lencode, distcode);
}

std::uint32_t crc32(const unsigned char* p, std::size_t n) {
    static const auto table = [] {
        std::array<std::uint32_t, 256> t{};
        for (std::uint32_t i = 0; i < 256; ++i) {
            std::uint32_t c = i;
            for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xedb88320u ^ (c >> 1) : c >> 1;
            t[i] = c;
        }
        return t;
    }();
    std::uint32_t c = 0xffffffffu;
    for (std::size_t i = 0; i < n; ++i) c = table[(c ^ p[i]) & 0xff] ^ (c >> 8);
    return c ^ 0xffffffffu;
}

std::uint32_t le32(const unsigned char* p) {
    return static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) |
           (static_cast<std::uint32_t>(p[2]) << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
}

}  // namespace

bool is_gzip(std::string_view bytes) {
    return bytes.size() >= 2 && static_cast<unsigned char>(bytes[0]) == 0x1f && static_cast<unsigned char>(bytes[1]) == 0x8b;
}

std::string gunzip(std::string_view bytes, const std::string& source) {
    const auto* in = reinterpret_cast<const unsigned char*>(bytes.data());
    const std::size_t n = bytes.size();
    std::string out;
    out.reserve(n * 4);
    std::size_t pos = 0;
    try {
        do {
            if (n - pos < 18 || in[pos] != 0x1f || in[pos + 1] != 0x8b) throw Corrupt{"not a gzip member"};
            if (in[pos + 2] != 8) throw Corrupt{"an unknown compression method"};
            const int flags = in[pos + 3];
            pos += 10;
            if (flags & 4) {   // FEXTRA
                if (pos + 2 > n) throw Corrupt{"a truncated header"};
                pos += 2 + (in[pos] | (in[pos + 1] << 8));
            }
            for (int f : {8, 16})   // FNAME, FCOMMENT: zero-terminated
                if (flags & f) {
                    while (pos < n && in[pos] != 0) ++pos;
                    ++pos;
                }
            if (flags & 2) pos += 2;   // FHCRC
            if (pos >= n) throw Corrupt{"a truncated header"};
            const std::size_t start = out.size();
            Bits b{in, n, pos};
            int last = 0;
            do {
                last = b.need(1);
                const int type = b.need(2);
                if (type == 0) stored(b, out);
                else if (type == 1) fixed(b, out, start);
                else if (type == 2) dynamic(b, out, start);
                else throw Corrupt{"an invalid block type"};
            } while (!last);
            pos = b.pos;   // the trailer starts at the next whole byte
            if (pos + 8 > n) throw Corrupt{"a missing gzip trailer (truncated file)"};
            const std::uint32_t crc = le32(in + pos), size = le32(in + pos + 4);
            pos += 8;
            const auto* data = reinterpret_cast<const unsigned char*>(out.data() + start);
            if (crc32(data, out.size() - start) != crc) throw Corrupt{"a CRC mismatch (corrupt data)"};
            if (static_cast<std::uint32_t>(out.size() - start) != size) throw Corrupt{"a length mismatch"};
            while (pos < n && in[pos] == 0) ++pos;   // padding after the last member
        } while (pos < n);
    } catch (const Corrupt& c) {
        throw DataError(source + ": gzip: " + c.what);
    }
    return out;
}

std::string gzip_stored(std::string_view text) {
    std::string out = std::string("\x1f\x8b\x08\x00\x00\x00\x00\x00\x00\xff", 10);
    std::size_t pos = 0;
    do {
        const std::size_t len = std::min<std::size_t>(65535, text.size() - pos);
        const bool last = pos + len >= text.size();
        out.push_back(static_cast<char>(last ? 1 : 0));
        out.push_back(static_cast<char>(len & 0xff));
        out.push_back(static_cast<char>(len >> 8));
        out.push_back(static_cast<char>(~len & 0xff));
        out.push_back(static_cast<char>((~len >> 8) & 0xff));
        out.append(text.substr(pos, len));
        pos += len;
    } while (pos < text.size());
    const std::uint32_t crc = crc32(reinterpret_cast<const unsigned char*>(text.data()), text.size());
    const auto size = static_cast<std::uint32_t>(text.size());
    for (std::uint32_t v : {crc, size})
        for (int k = 0; k < 4; ++k) out.push_back(static_cast<char>((v >> (8 * k)) & 0xff));
    return out;
}

}  // namespace impactlab::identify
