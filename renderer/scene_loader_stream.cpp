// The scene loader's big blocks read as a stream (scene_loader_internal.h, "the big blocks as a stream"): the
// first pass copies the file into the skeleton, leaving out each block's text; the second parses the blocks.

#include <algorithm>
#include <exception>
#include <system_error>
#include <thread>
#include <vector>

#include "rayview/file_read.h"
#include "rayview/own_pages.h"
#include "scene_loader_internal.h"

namespace rayview::scene_loading {

namespace {

// The pieces the file is read in: large enough that reading costs nothing, small enough not to matter.
constexpr std::size_t kPiece = std::size_t{1} << 20;
// A file whose piece would be under kOwnPagesMinBytes, on the heap, is read in pieces of this size instead: 16 pages
// to touch instead of one per 4 KiB of the file in each pass (a fresh page costs a fault, 11 us on a VM).
constexpr std::size_t kSmallPiece = std::size_t{1} << 16;
// What the skeleton is given at a time: a block's text after its opening tag is taken back out of it, so the
// skeleton never first holds (and touches) a whole piece of the text it leaves out.
constexpr std::size_t kSkeletonStep = std::size_t{1} << 16;

[[noreturn]] void abandon() { throw StreamAbandoned{}; }

// A piece's buffer, not zero-filled (the reads fill it), no larger than what it will hold: a small scene
// does not pay for a megabyte. A big one is on pages of its own, which the second pass's buffer takes over from
// the first's (rayview/own_pages.h); a small one is a small piece.
class Buffer {
 public:
  explicit Buffer(std::uint64_t wanted) : bytes_(pieceFor(wanted)) {}
  char* data() { return bytes_.data(); }
  char operator[](std::size_t i) const { return bytes_[i]; }
  std::size_t size() const { return bytes_.size(); }

 private:
  using Bytes = OwnPagesArray<char, OwnPages::RoundedUp>;
  static std::size_t pieceFor(std::uint64_t wanted) {
    const auto piece = static_cast<std::size_t>(std::clamp<std::uint64_t>(wanted, 16, kPiece));
    return OwnPagesAllocator<char, OwnPages::RoundedUp>::ownPages(piece) ? piece : std::min(piece, kSmallPiece);
  }
  Bytes bytes_;
};

bool isNameStart(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_' || c == ':' || static_cast<unsigned char>(c) >= 0x80;
}
bool isNameChar(char c) { return isNameStart(c) || (c >= '0' && c <= '9') || c == '-' || c == '.'; }

Tag blockTag(std::string_view name) {
  if (name.size() > 11) return Tag::Unknown;
  const std::string lower = toLower(name);
  if (lower == "vertexdata") return Tag::VertexData;
  if (lower == "texturedata") return Tag::TextureData;
  if (lower == "normaldata") return Tag::NormalData;
  if (lower == "faces") return Tag::Faces;
  return Tag::Unknown;
}

enum class Markup { Incomplete, Opening, Closing, Other };

// The first pass. The skeleton is scanned for markup as it grows; when the opening tag of a block ends, the
// bytes after it are taken back out of the skeleton and read as the block's text up to the next '<', which
// must begin a closing tag.
class SkeletonReader {
 public:
  SkeletonReader(const ReadAt& read, std::uint64_t size) : read_(read), size_(size) {}

  StreamedBlocks run() {
    std::string& s = out_.skeleton;
    Buffer buffer(size_ + 1);
    std::uint64_t offset = 0;  // of buffer[0] in the file
    std::size_t length = 0, pos = 0;
    bool inBlock = false, first = true;
    StreamedBlock block;
    std::size_t newlines = 0;
    while (true) {
      if (pos == length) {
        offset += length;
        const long got = read_(offset, buffer.data(), buffer.size());
        if (got < 0) abandon();
        length = static_cast<std::size_t>(got);
        pos = 0;
        if (length == 0) break;
        // What refuseWhatIsNotText would name.
        if (first && !detail::binaryFileKind(std::string_view(buffer.data(), std::min(length, detail::kFileStartBytes))).empty())
          abandon();
        first = false;
        if (std::memchr(buffer.data(), '\0', length)) abandon();
      }
      if (inBlock) {
        const char* from = buffer.data() + pos;
        const char* lt = static_cast<const char*>(std::memchr(from, '<', length - pos));
        const char* stop = lt ? lt : buffer.data() + length;
        newlines += static_cast<std::size_t>(std::count(from, stop, '\n'));
        pos = static_cast<std::size_t>(stop - buffer.data());
        if (!lt) continue;
        block.end = offset + pos;
        s.append(kStreamMarker);
        s.append(std::to_string(out_.blocks.size()));
        s.append(newlines, '\n');
        out_.blocks.push_back(std::move(block));
        inBlock = false;
        mustClose_ = true;
        scan_ = s.size();
      }
      const std::size_t appendedAt = s.size(), step = std::min(length - pos, kSkeletonStep);
      s.append(buffer.data() + pos, step);
      const std::size_t contentAt = scan();
      if (contentAt == std::string::npos) {
        pos += step;
        continue;
      }
      // The block's text starts right after its opening tag, which ended in the bytes just appended.
      pos += contentAt - appendedAt;
      s.resize(contentAt);
      block = StreamedBlock{};
      block.tag = pendingTag_;
      block.begin = offset + pos;
      block.line = lineAt(contentAt);
      newlines = 0;
      inBlock = true;
    }
    if (inBlock || mustClose_) abandon();  // the file ends inside a block: the ordinary reading says so
    // A marker the file itself spells out would be read as one of ours.
    std::size_t markers = 0;
    for (std::size_t at = s.find(kStreamMarker); at != std::string::npos; at = s.find(kStreamMarker, at + 1)) ++markers;
    if (markers != out_.blocks.size()) abandon();
    return std::move(out_);
  }

 private:
  // Scans the skeleton's complete markup from scan_. Returns the offset just after the opening tag of a block
  // (the block's text starts there), or npos once the markup left is incomplete or there is none.
  std::size_t scan() {
    const std::string& s = out_.skeleton;
    while (true) {
      const void* hit = scan_ < s.size() ? std::memchr(s.data() + scan_, '<', s.size() - scan_) : nullptr;
      if (!hit) {
        scan_ = s.size();
        return std::string::npos;
      }
      const std::size_t i = static_cast<std::size_t>(static_cast<const char*>(hit) - s.data());
      std::size_t end = 0;
      std::string_view name;
      const Markup kind = markupAt(i, end, name);
      if (kind == Markup::Incomplete) {
        // Markup this long is no tag of this format (a commented-out block, garbage): left to the ordinary
        // reading, which also keeps every rescan of it short.
        if (s.size() - i > kPiece) abandon();
        scan_ = i;
        return std::string::npos;
      }
      if (mustClose_ && kind != Markup::Closing) abandon();  // a comment or child element inside a block
      mustClose_ = false;
      scan_ = end;
      if (kind == Markup::Opening) {
        const Tag tag = blockTag(name);
        if (tag != Tag::Unknown) {
          pendingTag_ = tag;
          return end;
        }
      }
    }
  }

  // The markup at s[i] == '<', as the repair pass delimits it (xml_repair.cpp).
  Markup markupAt(std::size_t i, std::size_t& end, std::string_view& name) const {
    const std::string& s = out_.skeleton;
    const std::size_t n = s.size();
    auto until = [&](std::string_view terminator, std::size_t from, Markup kind) {
      const std::size_t at = s.find(terminator, from);
      if (at == std::string::npos) return Markup::Incomplete;
      end = at + terminator.size();
      return kind;
    };
    if (n - i < 4) return Markup::Incomplete;
    const char c = s[i + 1];
    if (c == '!') {
      if (s.compare(i, 4, "<!--") == 0) return until("-->", i + 4, Markup::Other);
      if (s[i + 2] == '[') abandon();  // CDATA: only the ordinary reading has its text
      return until(">", i + 2, Markup::Other);
    }
    if (c == '?') return until("?>", i + 2, Markup::Other);
    if (c == '/') return until(">", i + 2, Markup::Closing);
    if (!isNameStart(c)) abandon();  // the repair pass reports it
    std::size_t j = i + 1;
    while (j < n && isNameChar(s[j])) ++j;
    char quote = 0;
    for (std::size_t k = j; k < n; ++k) {
      const char ch = s[k];
      if (quote) {
        if (ch == quote) quote = 0;
      } else if (ch == '"' || ch == '\'') {
        quote = ch;
      } else if (ch == '<') {
        abandon();  // an unclosed tag: the repair pass reports it
      } else if (ch == '>') {
        end = k + 1;
        name = std::string_view(s).substr(i + 1, j - i - 1);
        return s[k - 1] == '/' ? Markup::Other : Markup::Opening;
      }
    }
    return Markup::Incomplete;
  }

  // 1-based line of a skeleton offset; offsets asked for only grow.
  int lineAt(std::size_t offset) {
    const std::string& s = out_.skeleton;
    line_ += std::count(s.begin() + static_cast<std::ptrdiff_t>(counted_), s.begin() + static_cast<std::ptrdiff_t>(offset), '\n');
    counted_ = offset;
    if (line_ >= INT32_MAX) abandon();
    return static_cast<int>(line_);
  }

  const ReadAt& read_;
  std::uint64_t size_;
  StreamedBlocks out_;
  std::size_t scan_ = 0;
  bool mustClose_ = false;
  Tag pendingTag_ = Tag::Unknown;
  std::size_t counted_ = 0;
  std::int64_t line_ = 1;
};

// Calls `token(text, line)` for each whitespace-separated token of the file's bytes [begin, end), as
// detail::TokenScanner splits the same text.
template <class Token>
void forEachToken(const ReadAt& read, std::uint64_t begin, std::uint64_t end, int firstLine, Buffer& buffer,
                  Token&& token) {
  std::int64_t line = firstLine;
  std::size_t carry = 0;
  std::uint64_t offset = begin;
  while (offset < end) {
    const std::size_t want = static_cast<std::size_t>(std::min<std::uint64_t>(buffer.size() - carry, end - offset));
    if (read(offset, buffer.data() + carry, want) != static_cast<long>(want)) abandon();  // the file changed
    offset += want;
    const std::size_t length = carry + want;
    const bool last = offset == end;
    std::size_t limit = length;  // tokens end before it
    if (!last) {
      while (limit > 0 && !detail::isXmlSpace(buffer[limit - 1])) --limit;
      if (limit == 0) abandon();  // a token as long as a piece: no number or index
    }
    const char* p = buffer.data();
    const char* stop = p + limit;
    const char* const filled = p + length;
    while (p < stop) {
      for (; p < stop && detail::isXmlSpace(*p); ++p) {
        line += *p == '\n';
        // tinyxml2 reads a lone CR as a line break in text, but not in its line numbers: only the DOM's count
        // is the DOM's.
        if (*p == '\r' && (p + 1 < filled ? p[1] != '\n' : last)) abandon();
      }
      if (p == stop) break;
      const char* start = p;
      while (p < stop && !detail::isXmlSpace(*p)) ++p;
      token(std::string_view(start, static_cast<std::size_t>(p - start)), line);
    }
    carry = length - limit;
    std::memmove(buffer.data(), buffer.data() + limit, carry);
  }
}

// Up to detail::kEstimateSample bytes from the start of each block in turn, a space between blocks: the sample
// detail::estimatedItems judges the blocks' items by.
std::string sampleOf(const ReadAt& read, const std::vector<const StreamedBlock*>& blocks) {
  std::string sample;
  // Its whole size at once: doubled past kEstimateSample by the last space, it left the heap for a fresh mapping at
  // every call (glibc maps blocks of 128 KiB and more), ~30 faults a scene.
  sample.reserve(detail::kEstimateSample + blocks.size());
  for (const StreamedBlock* block : blocks) {
    if (sample.size() >= detail::kEstimateSample) break;
    const std::size_t want = static_cast<std::size_t>(
        std::min<std::uint64_t>(block->end - block->begin, detail::kEstimateSample - sample.size()));
    const std::size_t at = sample.size();
    sample.resize(at + want);
    if (read(block->begin, sample.data() + at, want) != static_cast<long>(want)) abandon();  // the file changed
    sample += ' ';
  }
  return sample;
}

// A block of numbers, `Stride` per item, where readBlock would read them without a message: every token a
// whole finite number (in float range for `asFloat`), and whole items.
template <std::size_t Stride, class Item>
void parseNumbers(const ReadAt& read, const StreamedBlock& block, bool asFloat, Buffer& buffer, Item&& item) {
  double values[Stride];
  std::size_t k = 0, count = 0;
  forEachToken(read, block.begin, block.end, block.line, buffer, [&](std::string_view token, std::int64_t) {
    double v = 0.0;
    if (detail::parseDouble(token, v) != NumberStatus::Ok || (asFloat && std::fabs(v) > FLT_MAX)) abandon();
    values[k++] = v;
    ++count;
    if (k == Stride) {
      item(values);
      k = 0;
    }
  });
  if (count % Stride != 0 || count / Stride > static_cast<std::size_t>(INT32_MAX)) abandon();
}

}  // namespace

StreamedBlocks streamSkeleton(const ReadAt& read, std::uint64_t size) { return SkeletonReader(read, size).run(); }

namespace {

// A block of vertices, normals or texture coordinates, reserved from its own sample.
void parseNumberBlock(const ReadAt& read, StreamedBlock& block, Buffer& buffer) {
  const auto estimated = [&](std::size_t stride) {
    return detail::estimatedItems(sampleOf(read, {&block}), block.end - block.begin, stride);
  };
  switch (block.tag) {
    case Tag::VertexData:
      block.vertices.reserve(estimated(3));
      parseNumbers<3>(read, block, false, buffer, [&](const double* v) { block.vertices.emplace_back(v[0], v[1], v[2]); });
      break;
    case Tag::TextureData:
      block.texCoords.reserve(estimated(2));
      parseNumbers<2>(read, block, true, buffer, [&](const double* v) {
        block.texCoords.emplace_back(static_cast<float>(v[0]), static_cast<float>(v[1]));
      });
      break;
    case Tag::NormalData:
      block.normals.reserve(estimated(3));
      parseNumbers<3>(read, block, true, buffer, [&](const double* v) {
        block.normals.emplace_back(static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]));
      });
      break;
    default:
      abandon();
  }
}

// From this much text on each side, the faces and the other blocks are parsed on two threads: ~3 ms of parsing a
// side against ~0.1 ms to start a thread.
constexpr std::uint64_t kApartBytes = std::uint64_t{1} << 20;

// One <faces> block, appended to `streamed`'s triangles; `parseCorner` is the walk's (Loader::parseCorner).
template <class ParseCorner>
void parseFaceBlock(const ReadAt& read, StreamedBlock& block, Buffer& buffer, StreamedBlocks& streamed,
                    ParseCorner&& parseCorner) {
  // readFaces, without its messages.
  SceneArray<Triangle>& triangles = streamed.triangles;
  if (triangles.size() > static_cast<std::size_t>(UINT32_MAX / 2)) abandon();
  block.firstTriangle = static_cast<std::uint32_t>(triangles.size());
  FaceCorner corners[3];
  int cornerCount = 0;
  forEachToken(read, block.begin, block.end, block.line, buffer, [&](std::string_view token, std::int64_t line) {
    if (!parseCorner(token, corners[cornerCount])) abandon();
    if (++cornerCount < 3) return;
    cornerCount = 0;
    if ((corners[0].t < 0) != (corners[1].t < 0) || (corners[0].t < 0) != (corners[2].t < 0) ||
        (corners[0].n < 0) != (corners[1].n < 0) || (corners[0].n < 0) != (corners[2].n < 0))
      abandon();
    Triangle triangle;
    FaceAttributes attributes;
    bool zero = false;
    for (int k = 0; k < 3; ++k) {
      triangle.vertex[k] = static_cast<std::uint32_t>(corners[k].v);
      attributes.texCoord[k] = static_cast<std::int32_t>(corners[k].t);
      attributes.normal[k] = static_cast<std::int32_t>(corners[k].n);
      zero = zero || corners[k].v == 0 || corners[k].t == 0 || corners[k].n == 0;
    }
    // The line of the face's last token, where readFaces asks for it.
    const int at = zero ? static_cast<int>(line) : 0;
    for (int k = 0; k < 3; ++k) {
      block.vertexRange.add(corners[k].v, at);
      block.textureRange.add(corners[k].t, at);
      block.normalRange.add(corners[k].n, at);
    }
    appendFace(triangles, streamed.faceAttributes, triangle, attributes);
  });
  if (cornerCount != 0) abandon();
  block.triangleCount = static_cast<std::uint32_t>(triangles.size() - block.firstTriangle);
}

}  // namespace

void Loader::parseStreamedBlocks(StreamedBlocks& streamed, const ReadAt& read, int threads) {
  std::uint64_t faceBytes = 0, otherBytes = 0, longestFaces = 0, longestOthers = 0;
  std::vector<const StreamedBlock*> faceBlocks;
  for (const StreamedBlock& block : streamed.blocks) {
    const std::uint64_t bytes = block.end - block.begin;
    if (block.tag == Tag::Faces) {
      faceBytes += bytes, longestFaces = std::max(longestFaces, bytes);
      faceBlocks.push_back(&block);
    } else {
      otherBytes += bytes, longestOthers = std::max(longestOthers, bytes);
    }
  }
  streamed.triangles.reserve(detail::estimatedItems(sampleOf(read, faceBlocks), faceBytes, 3) + faceBlocks.size());
  // The faces' blocks or the others', in file order: no block reads another's.
  const auto parseKind = [&](bool faces, Buffer& buffer) {
    for (StreamedBlock& block : streamed.blocks) {
      if ((block.tag == Tag::Faces) != faces) continue;
      if (faces)
        parseFaceBlock(read, block, buffer, streamed, &Loader::parseCorner);
      else
        parseNumberBlock(read, block, buffer);
    }
  };
  // Apart, each side writes only its own blocks' arrays (the faces also the triangles and their attributes) and
  // reads the file with pread: the two share nothing. A thread that cannot be started leaves it to this one.
  std::thread apart;
  std::exception_ptr othersFailed;
  if (threads <= 0) threads = static_cast<int>(std::thread::hardware_concurrency());
  if (threads >= 2 && faceBytes >= kApartBytes && otherBytes >= kApartBytes) {
    try {
      apart = std::thread([&] {
        try {
          Buffer buffer(longestOthers);
          parseKind(false, buffer);
        } catch (...) {
          othersFailed = std::current_exception();
        }
      });
    } catch (const std::system_error&) {
    }
  }
  try {
    Buffer buffer(apart.joinable() ? longestFaces : std::max(longestFaces, longestOthers));
    if (!apart.joinable()) parseKind(false, buffer);
    parseKind(true, buffer);
  } catch (...) {
    if (apart.joinable()) apart.join();
    throw;
  }
  if (apart.joinable()) apart.join();
  if (othersFailed) std::rethrow_exception(othersFailed);
  streamed.triangleCount = streamed.triangles.size();
}

StreamedBlock* Loader::streamedBlock(const XMLElement* e, Tag tag) {
  if (!streamed_) return nullptr;
  const XMLNode* first = e->FirstChild();
  const tinyxml2::XMLText* text = first ? first->ToText() : nullptr;
  const std::string_view value = text ? std::string_view(text->Value()) : std::string_view();
  if (value.substr(0, kStreamMarker.size()) != kStreamMarker) {
    // A block the first pass did not take (a misspelt tag read as this one): read from the DOM, which is
    // exact unless faces from the stream are already in the scene's triangles.
    if (tag == Tag::Faces && streamed_->triangleCount != 0) abandon();
    return nullptr;
  }
  std::size_t index = 0;
  const char* digits = value.data() + kStreamMarker.size();
  const auto [end, ec] = std::from_chars(digits, value.data() + value.size(), index);
  // The marker must be all of the element's text: a stray closing tag the repair pass blanked inside a block
  // joins the text after it to the marker's (found by the fuzz target "scene").
  const bool alone = std::all_of(end, value.data() + value.size(), detail::isXmlSpace);
  if (ec != std::errc() || !alone || index >= streamed_->blocks.size() || first->NextSibling()) abandon();
  StreamedBlock& block = streamed_->blocks[index];
  if (block.tag != tag || block.claimed) abandon();
  block.claimed = true;
  return &block;
}

LoadedScene Loader::loadStreamed(StreamedBlocks& streamed) {
  streamed_ = &streamed;
  detail::RepairedXml repaired = detail::repairXml(streamed.skeleton, file_, options_.strict);
  for (Diagnostic& d : repaired.repairs) warnings_.add(std::move(d));
  const std::string& xml = repaired.changed ? repaired.text : streamed.skeleton;
  tinyxml2::XMLDocument doc(true, tinyxml2::PRESERVE_WHITESPACE);
  if (doc.Parse(xml.data(), xml.size()) != tinyxml2::XML_SUCCESS) abandon();  // its message quotes the file
  std::string().swap(repaired.text);
  std::string().swap(streamed.skeleton);
  return walk(doc);
}

}  // namespace rayview::scene_loading
