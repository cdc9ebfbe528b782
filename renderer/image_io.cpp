#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <random>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

#include <zlib.h>

#include "rayview/texture_image.h"

namespace rayview::png_detail {
unsigned char* deflateForStb(unsigned char* data, int length, int* outLength, int quality);
}
// stb_image_write filters the rows and writes the PNG chunks; the deflate of the filtered rows is ours
// (zlib, in parallel parts): stb's own deflate took 50-130 ms for a 1024x768 image, half a render.
#define STBIW_ZLIB_COMPRESS rayview::png_detail::deflateForStb
// zlib's CRC (table-sliced) for the chunks instead of stb's byte-at-a-time loop.
#define STBIW_CRC32(buffer, length) static_cast<unsigned int>(crc32(0, buffer, static_cast<uInt>(length)))
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_WRITE_NO_STDIO
#include <stb_image_write.h>

#include "rayview/image.h"
#include "rayview/file_names.h"

namespace rayview {
namespace png_detail {
namespace {

thread_local const PngOptions* currentOptions = nullptr;

// Rows unfiltered (PNG filter type 0). stb's default tries all five filters on every row and keeps the one
// with the smallest sum of bytes, which cost 5-14 ms of a 1024x768 write; for rayview's images (flat shading,
// hard edges) followed by zlib's fastest level, unfiltered rows also came out smallest: car 276 066 bytes
// against 298 158, the anti-aliased textured scene 63 246 against 76 657 (docs/PERFORMANCE.md, "PNG writing").
// Set once, before any thread can encode.
[[maybe_unused]] const bool kRowsUnfiltered = (stbi_write_force_png_filter = 0, true);

constexpr std::size_t kWindow = 32768;         // deflate's window: each part may refer this far back
constexpr std::size_t kMinPartBytes = 1 << 18;  // smaller parts cost more in threads than they save

struct FreeBytes {
  void operator()(unsigned char* p) const { std::free(p); }
};

int partCount(std::size_t bytes, int threads) {
  if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const std::size_t byBytes = std::max<std::size_t>(1, bytes / kMinPartBytes);
  return static_cast<int>(std::min<std::size_t>({static_cast<std::size_t>(threads), byBytes, 64}));
}

}  // namespace

namespace {

// One part of the stream: its raw deflate output (malloc'd) and the Adler-32 of its input.
struct DeflatedPart {
  std::unique_ptr<unsigned char, FreeBytes> bytes;
  std::size_t size = 0;
  uLong adler = 0;
  bool failed = false;
};

// Deflates data[begin, end) as one part of a stream: primed with the 32 KiB before it, ended with a sync flush
// unless it is the last part.
void deflatePart(const unsigned char* data, std::size_t begin, std::size_t end, bool last, int level,
                 DeflatedPart& part) {
  z_stream s{};
  if (deflateInit2(&s, level, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY) != Z_OK) {
    part.failed = true;
    return;
  }
  if (begin > 0) {
    const std::size_t dictionary = std::min(begin, kWindow);
    deflateSetDictionary(&s, data + begin - dictionary, static_cast<uInt>(dictionary));
  }
  // Room for an eighth of the part first, doubled while deflate fills it: output is mostly a few hundred KB, and a
  // buffer of deflateBound's size would hold megabytes more at a 1920x1080 write.
  const std::size_t bound = deflateBound(&s, static_cast<uLong>(end - begin)) + 64;
  std::size_t capacity = std::min(bound, (end - begin) / 8 + 4096);
  part.bytes.reset(static_cast<unsigned char*>(std::malloc(capacity)));
  s.next_in = const_cast<unsigned char*>(data + begin);
  s.avail_in = static_cast<uInt>(end - begin);
  s.next_out = part.bytes.get();
  s.avail_out = static_cast<uInt>(capacity);
  bool ok = part.bytes != nullptr;
  while (ok) {
    const int result = deflate(&s, last ? Z_FINISH : Z_SYNC_FLUSH);
    if (last ? result == Z_STREAM_END : result == Z_OK && s.avail_in == 0 && s.avail_out != 0) break;
    // Only a full buffer is worth more room: doubled up to deflate's bound, which it never needs more than
    // (realloc keeps what is written).
    ok = result != Z_STREAM_ERROR && s.avail_out == 0 && capacity < bound;
    if (!ok) break;
    capacity = std::min(capacity * 2, bound);
    auto* grown = static_cast<unsigned char*>(std::realloc(part.bytes.get(), capacity));
    ok = grown != nullptr;
    if (!ok) break;
    static_cast<void>(part.bytes.release());
    part.bytes.reset(grown);
    s.next_out = grown + s.total_out;
    s.avail_out = static_cast<uInt>(capacity - s.total_out);
  }
  part.failed = !ok;
  part.size = s.total_out;
  deflateEnd(&s);
  part.adler = adler32(1L, data + begin, static_cast<uInt>(end - begin));
}

// The zlib stream: header, the parts in order, the combined Adler-32. Built in the first part's buffer, grown
// (realloc), each further part appended and freed: no second copy of the whole output beside the parts.
unsigned char* joinParts(std::vector<DeflatedPart>& parts, std::size_t bytes, int level, int* outLength) {
  const std::size_t count = parts.size();
  uLong adler = parts[0].adler;
  for (std::size_t k = 1; k < count; ++k) {
    const std::size_t partBytes = bytes * (k + 1) / count - bytes * k / count;
    adler = adler32_combine(adler, parts[k].adler, static_cast<z_off_t>(partBytes));
  }
  std::size_t total = 2 + 4;
  for (const DeflatedPart& part : parts) total += part.size;
  auto* stream = static_cast<unsigned char*>(std::realloc(parts[0].bytes.get(), total));
  if (!stream) return nullptr;
  static_cast<void>(parts[0].bytes.release());
  std::memmove(stream + 2, stream, parts[0].size);
  // CMF: deflate, 32 KiB window; FLG: its check bits, no dictionary, level hint.
  const unsigned cmf = 0x78, levelHint = level == 1 ? 0 : level < 6 ? 1 : level == 6 ? 2 : 3;
  unsigned flg = levelHint << 6;
  flg += 31 - (cmf * 256 + flg) % 31;
  stream[0] = static_cast<unsigned char>(cmf);
  stream[1] = static_cast<unsigned char>(flg);
  std::size_t at = 2 + parts[0].size;
  for (std::size_t k = 1; k < count; ++k) {
    std::memcpy(stream + at, parts[k].bytes.get(), parts[k].size);
    at += parts[k].size;
    parts[k].bytes.reset();
  }
  for (int shift = 24; shift >= 0; shift -= 8) stream[at++] = static_cast<unsigned char>(adler >> shift);
  *outLength = static_cast<int>(total);
  return stream;
}

}  // namespace

// A zlib stream of `data`, deflated in parts on their own threads (as pigz does): every part but the last
// ends with a sync flush, which leaves it byte-aligned after a non-final block, so the raw parts concatenate
// into one valid deflate stream; each part is primed with the 32 KiB before it, so matches still reach back
// across the seam. The Adler-32 of the whole is combined from the parts'. Returned in malloc'd memory, which
// stb_image_write frees.
unsigned char* deflateForStb(unsigned char* data, int length, int* outLength, int) {
  const PngOptions options = currentOptions ? *currentOptions : PngOptions{};
  const int level = std::clamp(options.level, 1, 9);
  const auto bytes = static_cast<std::size_t>(length);
  const int count = partCount(bytes, options.threads);
  std::vector<DeflatedPart> parts(static_cast<std::size_t>(count));
  auto work = [&](int k) {
    deflatePart(data, bytes * k / count, bytes * (k + 1) / count, k + 1 == count, level,
                parts[static_cast<std::size_t>(k)]);
  };
  std::vector<std::thread> threads;
  for (int k = 1; k < count; ++k) threads.emplace_back(work, k);
  work(0);
  for (std::thread& t : threads) t.join();
  for (const DeflatedPart& part : parts)
    if (part.failed) return nullptr;
  return joinParts(parts, bytes, level, outLength);
}

}  // namespace png_detail

namespace {


void appendBytes(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
}

std::string encodePpm(const Image& image) {
  std::string bytes = "P6\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n255\n";
  bytes.append(reinterpret_cast<const char*>(image.rgb.data()), image.rgb.size());
  return bytes;
}

}  // namespace


std::string encodePng(const Image& image, const PngOptions& options) {
  std::string bytes;
  png_detail::currentOptions = &options;
  const int ok = stbi_write_png_to_func(appendBytes, &bytes, image.width, image.height, 3, image.rgb.data(),
                                        image.width * 3);
  png_detail::currentOptions = nullptr;
  if (!ok) throw ImageIoError("cannot encode the PNG image");
  return bytes;
}

std::string encodeTexturePng(const Texture& texture) {
  if (texture.alpha.empty() && !texture.opaqueAlpha) {
    Image image(texture.width, texture.height);
    image.rgb = texture.rgb;
    return encodePng(image);
  }
  std::vector<std::uint8_t> rgba;
  const std::size_t pixels = texture.rgb.size() / 3;
  rgba.reserve(pixels * 4);
  for (std::size_t i = 0; i < pixels; ++i) {
    const std::uint8_t a = texture.alpha.empty() ? 255 : texture.alpha[i];  // opaqueAlpha: 255 everywhere
    rgba.insert(rgba.end(), {texture.rgb[i * 3], texture.rgb[i * 3 + 1], texture.rgb[i * 3 + 2], a});
  }
  std::string bytes;
  const PngOptions options;
  png_detail::currentOptions = &options;
  const int ok = stbi_write_png_to_func(appendBytes, &bytes, texture.width, texture.height, 4, rgba.data(),
                                        texture.width * 4);
  png_detail::currentOptions = nullptr;
  if (!ok) throw ImageIoError("cannot encode the PNG image");
  return bytes;
}

bool isSupportedImageExtension(const std::filesystem::path& path) {
  const std::string ext = lowerExtension(path);
  return ext == ".png" || ext == ".ppm";
}

void writeImageFile(const std::filesystem::path& path, const Image& image) {
  const std::string ext = lowerExtension(path);
  if (ext == ".png") writeFileAtomically(path, encodePng(image));
  else if (ext == ".ppm") writeFileAtomically(path, encodePpm(image));
  else throw ImageIoError("cannot write " + path.string() + ": the extension must be .png or .ppm");
}

void writeImageFile(const std::filesystem::path& path, Image&& image) {
  Image owned = std::move(image);
  const std::string ext = lowerExtension(path);
  if (ext != ".png" && ext != ".ppm")
    throw ImageIoError("cannot write " + path.string() + ": the extension must be .png or .ppm");
  const std::string bytes = ext == ".png" ? encodePng(owned) : encodePpm(owned);
  // The pixels are not needed while the file is written: their memory goes back before the write's.
  owned = Image();
  writeFileAtomically(path, bytes);
}

Image readImageFile(const std::filesystem::path& path, std::string_view role) {
  // As textures are read: never blocking on a FIFO, sizes checked first, the same decoders.
  std::string reason;
  std::optional<Texture> texture = detail::readTextureImage(path, reason, role);
  if (!texture) throw ImageIoError("cannot read " + path.string() + ": " + reason);
  Image image(texture->width, texture->height);
  image.rgb = std::move(texture->rgb);
  return image;
}

}  // namespace rayview
