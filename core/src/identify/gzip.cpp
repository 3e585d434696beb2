// gzip (RFC 1952) through zlib: streaming inflate with a cap on the decompressed size (a gzip bomb is
// refused before it fills the memory), and deflate for what synth writes. Every defect is a DataError
// naming the file.
#define ZLIB_CONST
#include <zlib.h>

#include <algorithm>
#include <climits>
#include <cstddef>
#include <new>
#include <string>

#include "impactlab/identify_data.hpp"
#include "impactlab/input_file.hpp"

namespace impactlab::identify {

namespace {

constexpr std::size_t kChunk = std::size_t{1} << 18;   // output produced per inflate/deflate call
constexpr std::size_t kMaxAvail = UINT_MAX;             // z_stream counts in uInt

struct Inflater {
    z_stream zs{};
    Inflater() {
        const int rc = inflateInit2(&zs, 16 + MAX_WBITS);   // 16: a gzip wrapper, header and CRC checked
        if (rc == Z_MEM_ERROR) throw std::bad_alloc();
        if (rc != Z_OK) throw std::runtime_error("zlib inflateInit2 failed");
    }
    ~Inflater() { inflateEnd(&zs); }
    Inflater(const Inflater&) = delete;
    Inflater& operator=(const Inflater&) = delete;
};

struct Deflater {
    z_stream zs{};
    Deflater() {
        const int rc = deflateInit2(&zs, 6, Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY);
        if (rc == Z_MEM_ERROR) throw std::bad_alloc();
        if (rc != Z_OK) throw std::runtime_error("zlib deflateInit2 failed");
    }
    ~Deflater() { deflateEnd(&zs); }
    Deflater(const Deflater&) = delete;
    Deflater& operator=(const Deflater&) = delete;
};

}  // namespace

bool is_gzip(std::string_view bytes) {
    return bytes.size() >= 2 && static_cast<unsigned char>(bytes[0]) == 0x1f && static_cast<unsigned char>(bytes[1]) == 0x8b;
}

namespace {

// Inflates every member of `bytes` (concatenated gzip, zero padding after the last allowed), handing each
// piece of output to `sink(data, n)`; a defect throws DataError naming `source`.
template <class Sink>
void inflate_members(std::string_view bytes, const std::string& source, Sink&& sink) {
    const auto corrupt = [&](const std::string& what) { return DataError(source + ": corrupt gzip data: " + what); };
    const auto* in = reinterpret_cast<const Bytef*>(bytes.data());
    std::size_t in_left = bytes.size();
    Inflater z;
    z.zs.next_in = in;
    z.zs.avail_in = 0;
    std::string chunk(kChunk, '\0');
    for (;;) {
        if (z.zs.avail_in == 0 && in_left > 0) {   // feed the input in pieces z_stream can count
            const auto take = static_cast<uInt>(std::min(in_left, kMaxAvail));
            z.zs.avail_in = take;
            in_left -= take;
        }
        z.zs.next_out = reinterpret_cast<Bytef*>(chunk.data());
        z.zs.avail_out = static_cast<uInt>(kChunk);
        const int rc = inflate(&z.zs, Z_NO_FLUSH);
        sink(chunk.data(), kChunk - z.zs.avail_out);
        if (rc == Z_STREAM_END) {   // one member done: another may follow (concatenated gzip)
            while (z.zs.avail_in > 0 || in_left > 0) {   // zero padding after the last member is allowed
                if (z.zs.avail_in == 0) {
                    const auto take = static_cast<uInt>(std::min(in_left, kMaxAvail));
                    z.zs.avail_in = take;
                    in_left -= take;
                }
                if (*z.zs.next_in != 0) break;
                ++z.zs.next_in;
                --z.zs.avail_in;
            }
            if (z.zs.avail_in == 0 && in_left == 0) break;
            if (inflateReset(&z.zs) != Z_OK) throw corrupt("inflateReset failed");
            continue;
        }
        if (rc == Z_MEM_ERROR) throw std::bad_alloc();
        if (rc == Z_NEED_DICT || rc == Z_DATA_ERROR || rc == Z_STREAM_ERROR)
            throw corrupt(z.zs.msg != nullptr ? z.zs.msg : "invalid data");
        // Z_OK or Z_BUF_ERROR: progress, or none possible without more input.
        if (z.zs.avail_in == 0 && in_left == 0 && z.zs.avail_out != 0)
            throw corrupt("unexpected end of data (truncated file)");
    }
}

}  // namespace

std::string gunzip(std::string_view bytes, const std::string& source, std::size_t max_bytes) {
    // Inflated twice: once counting, so that a bomb is refused before anything is held and the memory
    // never exceeds the cap (a growing buffer would need one and a half times it), then into a buffer of
    // exactly that size. Inflating runs at hundreds of MB/s: the second pass costs little.
    std::size_t total = 0;
    inflate_members(bytes, source, [&](const char*, std::size_t n) {
        if (n > max_bytes - total)
            throw DataError(source + ": decompressed data exceed " + size_text(max_bytes) + " (a gzip bomb?)");
        total += n;
    });
    std::string out;
    out.reserve(total);
    inflate_members(bytes, source, [&](const char* data, std::size_t n) { out.append(data, n); });
    return out;
}

std::string gzip_stored(std::string_view text) {
    Deflater z;
    const auto* in = reinterpret_cast<const Bytef*>(text.data());
    std::size_t in_left = text.size();
    z.zs.next_in = in;
    z.zs.avail_in = 0;
    std::string out;
    std::size_t produced = 0;
    int rc = Z_OK;
    while (rc != Z_STREAM_END) {
        if (z.zs.avail_in == 0 && in_left > 0) {
            const auto take = static_cast<uInt>(std::min(in_left, kMaxAvail));
            z.zs.avail_in = take;
            in_left -= take;
        }
        out.resize(produced + kChunk);
        z.zs.next_out = reinterpret_cast<Bytef*>(&out[produced]);
        z.zs.avail_out = static_cast<uInt>(kChunk);
        rc = deflate(&z.zs, in_left == 0 ? Z_FINISH : Z_NO_FLUSH);
        produced += kChunk - z.zs.avail_out;
        if (rc == Z_STREAM_ERROR) throw std::runtime_error("zlib deflate failed");
    }
    out.resize(produced);
    return out;
}

}  // namespace impactlab::identify
