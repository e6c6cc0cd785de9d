// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The bytes of a VTK XML array (vti_read.cpp): raw in memory, read from the file, or base64
// decoded on the way as VTK writes it.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string_view>

#include "core/text.h"
#include "io/file_util.h"

namespace lic3d::vti {

inline int base64Value(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}

// Base64 as VTK writes it: whitespace anywhere, and several separately padded streams one after
// the other (a block's size header and its data are encoded apart, so "...==" may be followed by
// more). Decoding stops at the first byte that is not base64, '=' or whitespace, such as the '<'
// of the closing tag.
class Base64Reader {
 public:
  explicit Base64Reader(std::string_view text) : text_(text) {}

  // Up to `count` bytes; fewer at the end of the data or on invalid base64 (see invalid()).
  std::size_t read(unsigned char* out, std::size_t count) {
    std::size_t done = 0;
    while (done < count) {
      if (pendingBegin_ == pendingEnd_ && !decodeQuantum()) break;
      const std::size_t take = std::min<std::size_t>(count - done, pendingEnd_ - pendingBegin_);
      std::memcpy(out + done, pending_.data() + pendingBegin_, take);
      pendingBegin_ += take;
      done += take;
    }
    return done;
  }

  // Every 4 characters hold at most 3 bytes.
  std::uint64_t maxRemaining() const {
    return (text_.size() - position_) / 4 * 3 + 3 + (pendingEnd_ - pendingBegin_);
  }
  bool invalid() const { return invalid_; }

 private:
  bool decodeQuantum() {
    pendingBegin_ = 0;
    pendingEnd_ = 0;
    unsigned sextets = 0;
    std::uint32_t bits = 0;
    bool padded = false;
    while (sextets < 4 && position_ < text_.size()) {
      const char c = text_[position_];
      if (isAsciiSpace(c)) {
        ++position_;
        continue;
      }
      if (c == '=') {
        padded = true;
        break;
      }
      const int value = base64Value(c);
      if (value < 0) break;
      bits = bits << 6 | static_cast<std::uint32_t>(value);
      ++sextets;
      ++position_;
    }
    if (padded) {
      // "xx==" or "xxx=": the quantum ends early; its '=' signs are consumed.
      if (sextets < 2 || sextets > 3) return fail();
      while (position_ < text_.size() &&
             (text_[position_] == '=' || isAsciiSpace(text_[position_])))
        ++position_;
    }
    if (sextets == 0) return false;
    if (sextets == 1) return fail();
    // A missing final padding is tolerated: 2 or 3 characters still hold 1 or 2 bytes.
    bits <<= 6 * (4 - sextets);
    const unsigned bytes = sextets - 1;
    for (unsigned i = 0; i < bytes; ++i)
      pending_[i] = static_cast<unsigned char>(bits >> (16 - 8 * i));
    pendingEnd_ = bytes;
    return true;
  }

  bool fail() {
    invalid_ = true;
    return false;
  }

  std::string_view text_;
  std::size_t position_ = 0;
  std::array<unsigned char, 3> pending_{};
  std::size_t pendingBegin_ = 0;
  std::size_t pendingEnd_ = 0;
  bool invalid_ = false;
};

// The bytes of one binary or appended array: raw bytes, or base64 text decoded on the way.
class ByteSource {
 public:
  static ByteSource raw(std::string_view bytes) { return ByteSource(bytes, false); }
  static ByteSource base64(std::string_view text) { return ByteSource(text, true); }
  // `size` bytes of an open file from its current position on.
  static ByteSource file(FileReader reader, std::uint64_t size) {
    ByteSource source({}, false);
    source.fileSize_ = std::min(size, reader.remaining());
    source.file_.emplace(std::move(reader));
    return source;
  }

  std::size_t read(unsigned char* out, std::size_t count) {
    if (decoder_) return decoder_->read(out, count);
    if (file_) {
      const auto take = static_cast<std::size_t>(std::min<std::uint64_t>(count, maxRemaining()));
      const std::size_t got = file_->read(out, take);
      fileRead_ += got;
      return got;
    }
    const std::size_t take = std::min(count, raw_.size() - position_);
    std::memcpy(out, raw_.data() + position_, take);
    position_ += take;
    return take;
  }
  std::uint64_t maxRemaining() const {
    if (file_) return fileSize_ - fileRead_;
    return decoder_ ? decoder_->maxRemaining() : raw_.size() - position_;
  }
  // The next `count` bytes in place, when they are raw bytes in memory (not base64) and present.
  std::optional<std::string_view> take(std::size_t count) {
    if (decoder_ || file_ || count > raw_.size() - position_) return std::nullopt;
    const std::string_view bytes = raw_.substr(position_, count);
    position_ += count;
    return bytes;
  }
  bool invalid() const { return decoder_ && decoder_->invalid(); }

 private:
  ByteSource(std::string_view data, bool isBase64) {
    if (isBase64) {
      decoder_.emplace(data);
    } else {
      raw_ = data;
    }
  }

  std::string_view raw_;
  std::size_t position_ = 0;
  std::optional<Base64Reader> decoder_;
  std::optional<FileReader> file_;
  std::uint64_t fileSize_ = 0;
  std::uint64_t fileRead_ = 0;
};

}  // namespace lic3d::vti
