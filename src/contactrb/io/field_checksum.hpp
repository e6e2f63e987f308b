#pragma once
// A checksum over named fields that does not depend on the order in which they are visited:
// a reader may need some fields before others (the snapshot reader reads the per-snapshot
// tables before the snapshot groups they describe), while the writer visits them in file
// order. Each field gets its own 64-bit FNV-1a digest (kind, shape, bytes), and the file
// checksum is FNV-1a over (name, digest) in name order. Internal to io/.
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <map>
#include <string>

namespace contactrb::io {

class FieldChecksum {
 public:
  // `kind` tells apart fields of equal bytes but different meaning (an int 1 and a string
  // "\1\0\0\0"); `dims` is the shape (a 2 x 3 and a 3 x 2 matrix have the same bytes).
  // A name may be added once; adding it again replaces its digest.
  void add(const std::string& name, char kind, std::initializer_list<std::uint64_t> dims, const void* data,
           std::size_t bytes) {
    std::uint64_t h = kOffset;
    mix(h, &kind, 1);
    for (std::uint64_t d : dims) mix(h, &d, sizeof d);
    mix(h, data, bytes);
    fields_[name] = h;
  }

  std::uint64_t value() const {
    std::uint64_t h = kOffset;
    for (const auto& [name, digest] : fields_) {
      mix(h, name.c_str(), name.size() + 1);  // with its terminator: "ab"+"c" != "a"+"bc"
      mix(h, &digest, sizeof digest);
    }
    return h;
  }

 private:
  static constexpr std::uint64_t kOffset = 14695981039346656037ULL;
  static constexpr std::uint64_t kPrime = 1099511628211ULL;
  static void mix(std::uint64_t& h, const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) {
      h ^= p[i];
      h *= kPrime;
    }
  }
  std::map<std::string, std::uint64_t> fields_;
};

}  // namespace contactrb::io
