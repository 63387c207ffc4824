/// @file word_hash.h
/// @brief FNV-1a over 32-bit words (Fowler, Noll and Vo), with splitmix64's finaliser: the keys of
/// the hash maps that find a point's or an edge's kept data, and the signatures of what a kept value
/// was made from (internal).
#pragma once

#include "common/types.h"

#include <array>
#include <cstdint>
#include <cstring>

namespace radiosity::detail {

/// A float's bits, -0 as +0 (one place, one key).
inline uint32_t float_bits(float x) {
    x += 0.0f;
    uint32_t w;
    std::memcpy(&w, &x, sizeof w);
    return w;
}

class WordHash {
public:
    WordHash& word(uint32_t w) {
        h_ ^= w;
        h_ *= 1099511628211ULL;
        return *this;
    }
    template <std::size_t N>
    WordHash& words(const std::array<uint32_t, N>& ws) {
        for (const uint32_t w : ws) word(w);
        return *this;
    }
    WordHash& size(std::size_t n) { return word(uint32_t(n)).word(uint32_t(uint64_t(n) >> 32)); }
    WordHash& number(float x) { return word(float_bits(x)); }
    WordHash& number(double x) {
        uint64_t w;
        std::memcpy(&w, &x, sizeof w);
        return word(uint32_t(w)).word(uint32_t(w >> 32));
    }
    WordHash& rgb(const Rgb& c) { return number(c.r).number(c.g).number(c.b); }
    WordHash& vec(const Vec3& v) { return number(v.x).number(v.y).number(v.z); }

    /// The hash, its bits mixed by splitmix64's finaliser (Steele, Lea and Flood 2014): FNV's low
    /// bits alone mix poorly, and maps and shards take the low bits.
    uint64_t value() const {
        uint64_t z = h_;
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
        return z ^ (z >> 31);
    }

private:
    uint64_t h_ = 1469598103934665603ULL;
};

/// A map's hash of a key of N words.
struct WordsHash {
    template <std::size_t N>
    std::size_t operator()(const std::array<uint32_t, N>& words) const {
        return std::size_t(WordHash().words(words).value());
    }
};

}  // namespace radiosity::detail
