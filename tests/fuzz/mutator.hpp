#pragma once
// Deterministic mutations of valid inputs (docs/testing.md): every case is a pure function of
// (seed, target, case index), so a failing case is reproduced by its seed and index alone
// (docs/testing.md). Text inputs get token-aware mutations (a number replaced by an extreme
// one, a line duplicated or dropped) on top of the byte-level ones binary inputs get.
#include <algorithm>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace contactrb::fuzz {

// splitmix64: the per-case seed from (seed, target, index), independent of the order in
// which cases run.
inline std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

inline std::uint64_t case_seed(std::uint64_t seed, const std::string& target, std::uint64_t index) {
  std::uint64_t h = mix(seed);
  for (char c : target) h = mix(h ^ static_cast<unsigned char>(c));
  return mix(h ^ index);
}

class Mutator {
 public:
  explicit Mutator(std::uint64_t seed) : rng_(seed) {}

  std::size_t below(std::size_t n) { return n == 0 ? 0 : std::uniform_int_distribution<std::size_t>(0, n - 1)(rng_); }

  // 1 to 4 mutations of `input`; `text` adds the token-aware ones.
  std::string mutate(std::string input, bool text) {
    const std::size_t count = 1 + below(4);
    for (std::size_t k = 0; k < count; ++k) input = mutate_once(std::move(input), text);
    return input;
  }

  // 1 to 4 binary mutations of the bytes after the first `keep` (a header the caller rewrites
  // afterwards, e.g. a file seal recomputed over the damaged bytes).
  std::string mutate_after(const std::string& input, std::size_t keep) {
    const std::size_t n = std::min(keep, input.size());
    return input.substr(0, n) + mutate(input.substr(n), false);
  }

  // 1 to 4 binary mutations of the `width` bytes of `input` from offset `at`, the rest unchanged.
  std::string mutate_window(const std::string& input, std::size_t at, std::size_t width) {
    at = std::min(at, input.size());
    const std::size_t n = std::min(width, input.size() - at);
    return input.substr(0, at) + mutate(input.substr(at, n), false) + input.substr(at + n);
  }

  // One line of a batch file: a valid value mutated, or bytes of any kind.
  std::string batch_line() {
    static const std::vector<std::string> kValues{"0.3", "0.15", "0.45", " 0.2 ", "3e-1", "0.45000000000000001"};
    switch (below(4)) {
      case 0:
        return random_bytes(below(40));
      case 1:
        return interesting_number();
      default:
        return mutate(kValues[below(kValues.size())], true);
    }
  }

 private:
  std::string random_bytes(std::size_t n) {
    std::string s(n, '\0');
    for (char& c : s) c = static_cast<char>(below(256));
    return s;
  }

  std::string interesting_number() {
    static const std::vector<std::string> kNumbers{
        "0", "-0", "-1", "1", "2", "3", "-2147483648", "2147483647", "2147483648", "4294967296",
        "9223372036854775807", "18446744073709551616", "1e308", "-1e308", "1e309", "1e-320", "1e-400",
        "nan", "inf", "-inf", "0x10", "1e155", "0.49999999999999994", "1e100", "", "-", "+", "1e", "."};
    return kNumbers[below(kNumbers.size())];
  }

  // [begin, end) of a run of number characters in `s` around a random position, or none.
  bool pick_number(const std::string& s, std::size_t& begin, std::size_t& end) {
    const auto numeric = [](char c) { return (c >= '0' && c <= '9') || c == '.' || c == '-' || c == 'e' || c == '+'; };
    for (int attempt = 0; attempt < 16; ++attempt) {
      std::size_t p = below(s.size());
      if (!(s[p] >= '0' && s[p] <= '9')) continue;
      begin = p;
      end = p;
      while (begin > 0 && numeric(s[begin - 1])) --begin;
      while (end < s.size() && numeric(s[end])) ++end;
      return true;
    }
    return false;
  }

  std::string mutate_once(std::string s, bool text) {
    if (s.empty()) return random_bytes(1 + below(8));
    const std::size_t kinds = text ? 10 : 7;
    switch (below(kinds)) {
      case 0: {  // flip one bit
        const std::size_t p = below(s.size());
        s[p] = static_cast<char>(s[p] ^ (1 << below(8)));
        return s;
      }
      case 1: {  // a random byte
        s[below(s.size())] = static_cast<char>(below(256));
        return s;
      }
      case 2: {  // a few random bytes inserted
        s.insert(below(s.size() + 1), random_bytes(1 + below(8)));
        return s;
      }
      case 3: {  // a range deleted
        const std::size_t p = below(s.size());
        s.erase(p, 1 + below(std::min<std::size_t>(64, s.size() - p)));
        return s;
      }
      case 4: {  // truncated
        s.resize(below(s.size()));
        return s;
      }
      case 5: {  // a chunk duplicated in place
        const std::size_t p = below(s.size());
        const std::size_t n = 1 + below(std::min<std::size_t>(256, s.size() - p));
        s.insert(p, s.substr(p, n));
        return s;
      }
      case 6: {  // bytes set to 0x00 or 0xff (sizes and offsets of binary formats)
        const std::size_t p = below(s.size());
        const std::size_t n = 1 + below(std::min<std::size_t>(8, s.size() - p));
        std::fill_n(s.begin() + static_cast<std::ptrdiff_t>(p), n, below(2) == 0 ? '\0' : '\xff');
        return s;
      }
      case 7:
      case 8: {  // a number replaced by an extreme or malformed one
        std::size_t b = 0, e = 0;
        if (pick_number(s, b, e)) s.replace(b, e - b, interesting_number());
        return s;
      }
      default: {  // a line duplicated or removed
        const std::size_t p = s.rfind('\n', below(s.size()));
        const std::size_t start = p == std::string::npos ? 0 : p + 1;
        std::size_t stop = s.find('\n', start);
        stop = stop == std::string::npos ? s.size() : stop + 1;
        if (below(2) == 0) {
          s.insert(start, s.substr(start, stop - start));
        } else {
          s.erase(start, stop - start);
        }
        return s;
      }
    }
  }

  std::mt19937_64 rng_;
};

}  // namespace contactrb::fuzz
