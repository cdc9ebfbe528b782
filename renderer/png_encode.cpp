// PNG files from 8-bit pixels: the signature, IHDR, one IDAT holding the zlib stream, IEND. The rows go
// unfiltered (filter type 0): for rayview's images (flat shading, hard edges) followed by a fast deflate they came
// out smallest of the five filters, and choosing a filter per row cost 5-14 ms of a 1024x768 write
// (docs/PERFORMANCE.md, "PNG writing"). The stream is deflated in parallel parts, as pigz does: every part but the
// last ends with a sync flush, which leaves it byte-aligned after a non-final block, so the parts concatenate into
// one deflate stream; each is primed with the 32 KiB before it, so matches still reach back across the seam. Each
// part reads its rows a few at a time into a small buffer with their filter bytes: the filtered image is never
// held whole (in a fresh process its pages' first touches cost more than the deflate).

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <new>
#include <string>
#include <thread>
#include <vector>

#include <isa-l/igzip_lib.h>
#include <zlib.h>

#include "rayview/image.h"
#include "rayview/own_pages.h"
#include "rayview/texture_image.h"

namespace rayview {
namespace {

constexpr std::size_t kWindow = 32768;          // deflate's window: each part may refer this far back
constexpr std::size_t kMinPartBytes = 1 << 18;  // smaller parts cost more in threads than they save
constexpr std::size_t kChunkBytes = 1 << 16;    // rows handed to the deflate at a time

// The image's filtered stream: each row its filter byte (0) and its pixels.
struct Rows {
  const std::uint8_t* pixels;
  std::size_t rowBytes;  // without the filter byte
  int height;

  std::size_t stride() const { return rowBytes + 1; }
  std::size_t bytes() const { return stride() * static_cast<std::size_t>(height); }
  // Copies the stream's bytes [from, to) to out.
  void copy(std::size_t from, std::size_t to, std::uint8_t* out) const {
    while (from < to) {
      const std::size_t row = from / stride(), at = from % stride();
      const std::size_t n = std::min(to - from, stride() - at);
      if (at == 0) {
        *out = 0;
        if (n > 1) std::memcpy(out + 1, pixels + row * rowBytes, n - 1);
      } else {
        std::memcpy(out, pixels + row * rowBytes + (at - 1), n);
      }
      out += n;
      from += n;
    }
  }
};

// A part's deflated bytes (malloc'd, grown as the deflate fills them) and the Adler-32 of its input.
struct DeflatedPart {
  struct Free {
    void operator()(unsigned char* p) const { std::free(p); }
  };
  std::unique_ptr<unsigned char, Free> bytes;
  std::size_t capacity = 0, size = 0;
  uLong adler = 1;
  bool failed = false;

  // Room for an eighth of the part first, doubled whenever the deflate fills it: output is mostly a few hundred KB,
  // and room for the worst case would hold megabytes more at a 1920x1080 write (realloc keeps what is written).
  bool grow(std::size_t partBytes) {
    const std::size_t wanted = capacity == 0 ? partBytes / 8 + 4096 : capacity * 2;
    auto* grown = static_cast<unsigned char*>(std::realloc(bytes.get(), wanted));
    if (!grown) return false;
    static_cast<void>(bytes.release());
    bytes.reset(grown);
    capacity = wanted;
    return true;
  }
};

// One library's deflate of a part, fed a chunk at a time: deflate(chunk, n, end) consumes the chunk, and with `end`
// finishes the part (a sync flush, or the final block when `last`); it returns false on failure. adler(a, chunk, n)
// is the same library's Adler-32 of the chunk, continued from a.
class ZlibPart {
 public:
  ZlibPart(int level, bool last, DeflatedPart& part) : last_(last), part_(part) {
    ok_ = deflateInit2(&s_, level, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY) == Z_OK;
  }
  ~ZlibPart() {
    if (ok_) deflateEnd(&s_);
  }
  ZlibPart(const ZlibPart&) = delete;
  ZlibPart& operator=(const ZlibPart&) = delete;

  bool prime(const std::uint8_t* dictionary, std::size_t n) {
    return ok_ && deflateSetDictionary(&s_, dictionary, static_cast<uInt>(n)) == Z_OK;
  }
  static uLong adler(uLong a, const std::uint8_t* chunk, std::size_t n) {
    return adler32(a, chunk, static_cast<uInt>(n));
  }
  bool deflate(const std::uint8_t* chunk, std::size_t n, bool end, std::size_t partBytes) {
    if (!ok_) return false;
    s_.next_in = const_cast<std::uint8_t*>(chunk);
    s_.avail_in = static_cast<uInt>(n);
    const int flush = !end ? Z_NO_FLUSH : last_ ? Z_FINISH : Z_SYNC_FLUSH;
    for (;;) {
      s_.next_out = part_.bytes.get() + s_.total_out;
      s_.avail_out = static_cast<uInt>(part_.capacity - s_.total_out);
      const int result = ::deflate(&s_, flush);
      part_.size = s_.total_out;
      if (result == Z_STREAM_ERROR) return false;
      const bool done = flush == Z_FINISH ? result == Z_STREAM_END : s_.avail_in == 0 && s_.avail_out != 0;
      if (done) return true;
      if (s_.avail_out == 0 && !part_.grow(partBytes)) return false;
    }
  }

 private:
  z_stream s_{};
  bool ok_ = false;
  bool last_;
  DeflatedPart& part_;
};

// What a part's deflate works in, besides its output: ISA-L's stream state (~80 KB) and level buffer (~280 KB, left
// unfilled: ISA-L writes before it reads), and the chunk of rows it is fed. Every part's in one block, on pages of its
// own from kOwnPagesMinBytes (two parts and more): on the heap, each part's were fresh pages, whose first touches cost
// more than the deflate of a small image (bunny's 512x512: ~65 faults, 0.7 ms). The mapping is kept for the next
// write of as many parts (rayview/own_pages.h).
struct PartScratch {
  isal_zstream stream;
  std::uint8_t level[ISAL_DEF_LVL1_DEFAULT];
  std::uint8_t chunk[kChunkBytes];
};

// ISA-L's level 1: the fastest deflate measured here, files 1-6 % larger than zlib's level 1 (docs/PERFORMANCE.md,
// "PNG writing").
class IsalPart {
 public:
  IsalPart(bool last, DeflatedPart& part, PartScratch& scratch) : stream_(&scratch.stream), last_(last), part_(part) {
    std::memset(stream_, 0, sizeof *stream_);  // as value-initialised
    isal_deflate_init(stream_);
    stream_->level = 1;
    stream_->level_buf = scratch.level;
    stream_->level_buf_size = ISAL_DEF_LVL1_DEFAULT;
  }

  bool prime(const std::uint8_t* dictionary, std::size_t n) {
    return isal_deflate_set_dict(stream_, const_cast<std::uint8_t*>(dictionary),
                                 static_cast<std::uint32_t>(n)) == COMP_OK;
  }
  static uLong adler(uLong a, const std::uint8_t* chunk, std::size_t n) {
    return isal_adler32(static_cast<std::uint32_t>(a), chunk, n);  // vectorised; zlib's is a byte loop
  }
  bool deflate(const std::uint8_t* chunk, std::size_t n, bool end, std::size_t partBytes) {
    isal_zstream& s = *stream_;
    s.next_in = const_cast<std::uint8_t*>(chunk);
    s.avail_in = static_cast<std::uint32_t>(n);
    s.flush = end && !last_ ? SYNC_FLUSH : NO_FLUSH;
    s.end_of_stream = end && last_ ? 1 : 0;
    for (;;) {
      s.next_out = part_.bytes.get() + s.total_out;
      s.avail_out = static_cast<std::uint32_t>(part_.capacity - s.total_out);
      const std::uint32_t written = s.total_out, left = s.avail_in;
      if (isal_deflate(&s) != COMP_OK) return false;
      part_.size = s.total_out;
      // Done as igzip_lib.h says: all input taken and, at the part's end, the final block written, or the flush's
      // block out (room left over, or a new block next).
      const bool flushed = s.avail_out != 0 || s.internal_state.state == ZSTATE_NEW_HDR;
      if (s.avail_in == 0 && (!end || (last_ ? s.internal_state.state == ZSTATE_END : flushed))) return true;
      if (s.avail_out == 0) {
        if (!part_.grow(partBytes)) return false;
      } else if (s.total_out == written && s.avail_in == left) {
        return false;  // no progress with room to spare
      }
    }
  }

 private:
  isal_zstream* stream_;
  bool last_;
  DeflatedPart& part_;
};

// The stream's bytes [begin, end) as one part: primed with the 32 KiB before it, fed a chunk at a time.
template <class Deflater>
void deflatePart(const Rows& rows, std::size_t begin, std::size_t end, Deflater& deflater, std::uint8_t* chunk,
                 DeflatedPart& part) {
  const std::size_t partBytes = end - begin;
  if (!part.grow(partBytes)) return static_cast<void>(part.failed = true);
  if (begin > 0) {
    const std::size_t dictionary = std::min(begin, kWindow);
    rows.copy(begin - dictionary, begin, chunk);
    if (!deflater.prime(chunk, dictionary)) return static_cast<void>(part.failed = true);
  }
  std::size_t at = begin;
  do {  // at least once: an empty part still ends its stream
    const std::size_t n = std::min(end - at, kChunkBytes);
    rows.copy(at, at + n, chunk);
    part.adler = Deflater::adler(part.adler, chunk, n);
    at += n;
    if (!deflater.deflate(chunk, n, at == end, partBytes)) return static_cast<void>(part.failed = true);
  } while (at < end);
}

int partCount(std::size_t bytes, int threads) {
  if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const std::size_t byBytes = std::max<std::size_t>(1, bytes / kMinPartBytes);
  return static_cast<int>(std::min<std::size_t>({static_cast<std::size_t>(threads), byBytes, 64}));
}

// The parts of the zlib stream's deflate data at `level` (1-9), deflated on their own threads; empty when any failed.
std::vector<DeflatedPart> deflateParts(const Rows& rows, int level, int threadCount) {
  const std::size_t bytes = rows.bytes();
  const int count = partCount(bytes, threadCount);
  std::vector<DeflatedPart> parts(static_cast<std::size_t>(count));
  OwnPagesArray<PartScratch, OwnPages::RoundedUp> scratch(static_cast<std::size_t>(count));
  auto work = [&](int k) {
    const std::size_t begin = bytes * k / count, end = bytes * (k + 1) / count;
    const bool last = k + 1 == count;
    DeflatedPart& part = parts[static_cast<std::size_t>(k)];
    PartScratch& own = scratch[static_cast<std::size_t>(k)];
    if (level == 1) {
      IsalPart deflater(last, part, own);
      deflatePart(rows, begin, end, deflater, own.chunk, part);
    } else {
      ZlibPart deflater(level, last, part);
      deflatePart(rows, begin, end, deflater, own.chunk, part);
    }
  };
  std::vector<std::thread> threads;
  for (int k = 1; k < count; ++k) threads.emplace_back(work, k);
  work(0);
  for (std::thread& t : threads) t.join();
  for (const DeflatedPart& part : parts)
    if (part.failed) return {};
  return parts;
}

void appendBigEndian(std::string& out, std::uint32_t value) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<char>((value >> shift) & 0xFF));
}

std::uint32_t crcOf(std::uint32_t crc, const void* data, std::size_t n) {
  return static_cast<std::uint32_t>(crc32(crc, static_cast<const Bytef*>(data), static_cast<uInt>(n)));
}

// A chunk whose data is in `data`: its length, type, data and CRC.
void appendChunk(std::string& out, const char type[4], const std::string& data) {
  appendBigEndian(out, static_cast<std::uint32_t>(data.size()));
  out.append(type, 4);
  out += data;
  appendBigEndian(out, crcOf(crcOf(0, type, 4), data.data(), data.size()));
}

// The file as its pieces: the headers up to the zlib stream's, each part's deflated bytes where the deflate left
// them, then the Adler-32, the CRC and IEND.
FileBytes encode(const std::uint8_t* pixels, int width, int height, int channels, const PngOptions& options) {
  const Rows rows{pixels, static_cast<std::size_t>(width) * static_cast<std::size_t>(channels), height};
  const int level = std::clamp(options.level, 1, 9);
  struct Pieces {
    std::string head, tail;
    std::vector<DeflatedPart> parts;
  };
  auto made = std::make_shared<Pieces>();
  made->parts = deflateParts(rows, level, options.threads);
  std::vector<DeflatedPart>& parts = made->parts;
  if (parts.empty()) throw ImageIoError("cannot encode the PNG image");
  uLong adler = parts[0].adler;
  std::size_t deflated = 0;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    deflated += parts[k].size;
    if (k == 0) continue;
    const std::size_t partBytes = rows.bytes() * (k + 1) / parts.size() - rows.bytes() * k / parts.size();
    adler = adler32_combine(adler, parts[k].adler, static_cast<z_off_t>(partBytes));
  }
  std::string header;
  appendBigEndian(header, static_cast<std::uint32_t>(width));
  appendBigEndian(header, static_cast<std::uint32_t>(height));
  // Bit depth 8; colour type 2 (RGB) or 6 (RGBA); deflate; filters of method 0; not interlaced.
  header += {8, static_cast<char>(channels == 4 ? 6 : 2), 0, 0, 0};

  std::string& head = made->head;
  head = "\x89PNG\r\n\x1a\n";
  appendChunk(head, "IHDR", header);
  appendBigEndian(head, static_cast<std::uint32_t>(2 + deflated + 4));
  const std::size_t typeAt = head.size();
  head += "IDAT";
  // CMF: deflate, 32 KiB window; FLG: its check bits, no dictionary, level hint.
  const unsigned cmf = 0x78, levelHint = level == 1 ? 0 : level < 6 ? 1 : level == 6 ? 2 : 3;
  unsigned flg = levelHint << 6;
  flg += 31 - (cmf * 256 + flg) % 31;
  head += {static_cast<char>(cmf), static_cast<char>(flg)};
  std::uint32_t crc = crcOf(0, head.data() + typeAt, head.size() - typeAt);
  for (const DeflatedPart& part : parts) crc = crcOf(crc, part.bytes.get(), part.size);
  std::string& tail = made->tail;
  appendBigEndian(tail, static_cast<std::uint32_t>(adler));
  crc = crcOf(crc, tail.data(), tail.size());
  appendBigEndian(tail, crc);
  appendChunk(tail, "IEND", std::string());

  FileBytes file;
  file.pieces.push_back(head);
  for (const DeflatedPart& part : parts)
    file.pieces.emplace_back(reinterpret_cast<const char*>(part.bytes.get()), part.size);
  file.pieces.push_back(tail);
  file.owner = std::move(made);
  return file;
}

}  // namespace

FileBytes encodePngFile(const Image& image, const PngOptions& options) {
  return encode(image.rgb.data(), image.width, image.height, 3, options);
}

std::string encodePng(const Image& image, const PngOptions& options) { return encodePngFile(image, options).joined(); }

std::string encodeTexturePng(const Texture& texture) {
  if (texture.alpha.empty() && !texture.opaqueAlpha)
    return encode(texture.rgb.data(), texture.width, texture.height, 3, {}).joined();
  std::vector<std::uint8_t> rgba;
  const std::size_t pixels = texture.rgb.size() / 3;
  rgba.reserve(pixels * 4);
  for (std::size_t i = 0; i < pixels; ++i) {
    const std::uint8_t a = texture.alpha.empty() ? 255 : texture.alpha[i];  // opaqueAlpha: 255 everywhere
    rgba.insert(rgba.end(), {texture.rgb[i * 3], texture.rgb[i * 3 + 1], texture.rgb[i * 3 + 2], a});
  }
  return encode(rgba.data(), texture.width, texture.height, 4, {}).joined();
}

}  // namespace rayview
