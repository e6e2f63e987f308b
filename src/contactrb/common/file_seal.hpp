#pragma once
// A hash of a whole file's bytes kept in its first bytes (for HDF5 files: the 512-byte user
// block, which HDF5 and h5py skip). The snapshot and model writers seal the file after HDF5 has
// closed it; the readers check the seal before HDF5 parses anything, so that a damaged file
// (a bit flip, a truncation, a fuzzer's mutation) never reaches HDF5's parser: HDF5 1.10.8
// itself crashes on some damaged files, e.g. in H5HG_read when a variable-length string's
// length is damaged. Crafted files (resealed after an edit) still meet every check of the
// readers (checksums over the fields, index and size checks).
//
// Layout of the first kSealBlock bytes: "contactrb-seal1\0" (16 bytes), then the FNV-1a 64-bit
// hash (little-endian) of the file with those 8 bytes taken as 0 (FNV-1a over 64-bit words,
// the tail bytewise, xor the length), then zeros.
#include <array>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "contactrb/common/enum_names.hpp"
#include "contactrb/common/error.hpp"

namespace contactrb {

inline constexpr std::size_t kSealBlock = 512;
inline constexpr std::size_t kSealHashOffset = 16;

enum class SealState {
  Valid,     // the hash matches: the bytes are those the writer sealed
  Absent,    // no seal: an HDF5 file without a user block (an older version, another program's)
  Mismatch,  // sealed, but the bytes changed since (damaged, truncated, edited), or a damaged seal
};

inline const char* to_string(SealState state) {
  switch (state) {
    case SealState::Valid: return "valid";
    case SealState::Absent: return "absent";
    case SealState::Mismatch: return "mismatch";
  }
  return "unknown";
}

inline SealState seal_state_from_string(const std::string& name) {
  return enum_from_string(name, "seal state", std::array{SealState::Valid, SealState::Absent, SealState::Mismatch});
}

namespace seal_detail {
inline constexpr char kMagic[kSealHashOffset] = "contactrb-seal1";

// The hash of the file, the hash field read as zeros. False when the file cannot be read.
inline bool hash_file(const std::string& path, std::uint64_t& hash) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::uint64_t h = 14695981039346656037ULL;
  std::vector<char> buffer(1 << 20);
  std::size_t position = 0;
  while (in) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    const auto n = static_cast<std::size_t>(in.gcount());
    // The hash field as zeros (it lies in the first chunk).
    for (std::size_t p = kSealHashOffset; p < kSealHashOffset + 8; ++p) {
      if (p >= position && p < position + n) buffer[p - position] = 0;
    }
    // FNV-1a over 64-bit little-endian words (a byte at a time: 4 times slower), the last
    // chunk's tail bytes one at a time. Each step is a bijection of h: any one changed word
    // changes the hash.
    std::size_t i = 0;
    for (; i + 8 <= n; i += 8) {
      std::uint64_t word = 0;
      for (std::size_t b = 0; b < 8; ++b) word |= static_cast<std::uint64_t>(static_cast<unsigned char>(buffer[i + b])) << (8 * b);
      h ^= word;
      h *= 1099511628211ULL;
    }
    for (; i < n; ++i) {
      h ^= static_cast<unsigned char>(buffer[i]);
      h *= 1099511628211ULL;
    }
    position += n;
  }
  if (in.bad()) return false;
  hash = h ^ position;  // the length too
  return true;
}
}  // namespace seal_detail

// Writes the seal into the first bytes of `path` (their kSealBlock bytes must be free: an HDF5
// file created with a user block of kSealBlock bytes). Throws contactrb::Error naming the file.
inline void seal_file(const std::string& path) {
  {
    std::fstream out(path, std::ios::binary | std::ios::in | std::ios::out);
    require(static_cast<bool>(out), "cannot open '" + path + "' to seal it");
    out.write(seal_detail::kMagic, kSealHashOffset);
    const std::array<char, 8> zero{};
    out.write(zero.data(), zero.size());
    require(static_cast<bool>(out.flush()), "cannot seal '" + path + "'");
  }
  std::uint64_t h = 0;
  require(seal_detail::hash_file(path, h), "cannot read '" + path + "' to seal it");
  std::array<char, 8> bytes{};
  for (std::size_t i = 0; i < 8; ++i) bytes[i] = static_cast<char>((h >> (8 * i)) & 0xffu);
  std::fstream out(path, std::ios::binary | std::ios::in | std::ios::out);
  out.seekp(static_cast<std::streamoff>(kSealHashOffset));
  out.write(bytes.data(), bytes.size());
  require(static_cast<bool>(out.flush()), "cannot seal '" + path + "'");
}

// The state of `path`'s seal; Absent for a file too short to hold one (HDF5 refuses it).
inline SealState check_seal(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::array<char, kSealHashOffset + 8> head{};
  if (!in.read(head.data(), head.size())) return SealState::Absent;
  if (std::memcmp(head.data(), seal_detail::kMagic, kSealHashOffset) != 0) {
    // No seal: an HDF5 file without a user block starts with HDF5's signature; anything else in
    // place of the magic is a damaged seal (the file must not reach HDF5's parser).
    static constexpr char kHdf5Signature[8] = {'\x89', 'H', 'D', 'F', '\r', '\n', '\x1a', '\n'};
    return std::memcmp(head.data(), kHdf5Signature, sizeof kHdf5Signature) == 0 ? SealState::Absent
                                                                                : SealState::Mismatch;
  }
  std::uint64_t stored = 0;
  for (std::size_t i = 0; i < 8; ++i) {
    stored |= static_cast<std::uint64_t>(static_cast<unsigned char>(head[kSealHashOffset + i])) << (8 * i);
  }
  std::uint64_t actual = 0;
  if (!seal_detail::hash_file(path, actual)) return SealState::Mismatch;
  return actual == stored ? SealState::Valid : SealState::Mismatch;
}

}  // namespace contactrb
