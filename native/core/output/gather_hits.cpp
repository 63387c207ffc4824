/// @file gather_hits.cpp
/// @brief The final gather's recorded hits (gather_hits.h).
#include "output/gather_hits.h"

#include "common/word_hash.h"

namespace radiosity {
namespace {

/// Bytes a recorded set holds besides its hits: the key, the vector and the map's node.
constexpr std::size_t kSetOverhead = sizeof(GatherHits::Key) + sizeof(std::vector<hr::Visibility::Hit>) + 32;

}  // namespace

GatherHits::Key GatherHits::key(const Vec3& origin, const Vec3& normal, uint32_t seed, int grid, Kind kind,
                                uint32_t read) {
    using detail::float_bits;
    return Key{{float_bits(origin.x), float_bits(origin.y), float_bits(origin.z), float_bits(normal.x),
                float_bits(normal.y), float_bits(normal.z), seed,
                (uint32_t(grid) << 5) | (read << 2) | uint32_t(kind)}};
}

std::size_t GatherHits::KeyHash::operator()(const Key& key) const { return detail::WordsHash()(key.words); }

GatherHits::Shard& GatherHits::shard(const Key& key) const { return shards_[KeyHash()(key) % kShards]; }

const std::vector<hr::Visibility::Hit>* GatherHits::find(const Key& key) const {
    Shard& s = shard(key);
    const std::lock_guard<std::mutex> lock(s.mutex);
    const auto found = s.map.find(key);
    return found == s.map.end() ? nullptr : &found->second;
}

bool GatherHits::reserve(std::size_t size) {
    std::size_t held = bytes_.load(std::memory_order_relaxed);
    do {
        if (held + size > budget_bytes_) {
            full_.store(true, std::memory_order_relaxed);
            return false;
        }
    } while (!bytes_.compare_exchange_weak(held, held + size, std::memory_order_relaxed));
    return true;
}

void GatherHits::record(const Key& key, std::vector<hr::Visibility::Hit>&& hits) {
    const std::size_t size = hits.size() * sizeof(hr::Visibility::Hit) + kSetOverhead;
    if (!reserve(size)) return;
    Shard& s = shard(key);
    const std::lock_guard<std::mutex> lock(s.mutex);
    hits.shrink_to_fit();
    if (!s.map.emplace(key, std::move(hits)).second) bytes_.fetch_sub(size, std::memory_order_relaxed);
}

const detail::PointReads* GatherHits::find_reads(const Key& key) const {
    Shard& s = shard(key);
    const std::lock_guard<std::mutex> lock(s.mutex);
    const auto found = s.reads.find(key);
    return found == s.reads.end() ? nullptr : &found->second;
}

const detail::PointReads* GatherHits::record_reads(const Key& key, detail::PointReads& reads) {
    const std::size_t size = reads.bytes() + kSetOverhead;
    if (!reserve(size)) return nullptr;
    Shard& s = shard(key);
    const std::lock_guard<std::mutex> lock(s.mutex);
    const auto [kept, added] = s.reads.try_emplace(key, std::move(reads));
    if (!added) bytes_.fetch_sub(size, std::memory_order_relaxed);
    return &kept->second;
}

}  // namespace radiosity
