/// @file gather_hits.h
/// @brief What the final gather's rays hit, kept so that a later gather over the same geometry
/// reads them instead of tracing them again (a re-bake after a lighting edit, the light groups'
/// layers).
///
/// A gather's indirect rays and its probe rays leave from points chosen from the geometry alone
/// (final_gather.h), along stratified directions seeded by the point's place: which element each
/// ray first hits, where on it and how far are a function of the geometry and of the ray set
/// (origin, normal, seed, grid). Light is linear in its sources, and only what a hit reads (the
/// solved radiance there less its emission) depends on them; Christensen's photon-map final gather
/// and the irradiance cache of Ward et al. rely on the same split. Recorded hits are exactly what
/// Embree returns for those rays, so a gather that reads them gives bit for bit the colours a gather
/// that traces them gives. The output points' indirect rays, many more than the values they read,
/// are kept folded into what they read instead (point_reads.h), which every gather at those points
/// evaluates, traced or not. Shadow rays are kept as each source's light (kept_direct_light.h).
#pragma once

#include "output/point_reads.h"
#include "visibility/ray_tracer.h"

#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <unordered_map>
#include <vector>

namespace radiosity {

/// The hits of a gather's ray sets, each set named by where and how its rays leave. Thread-safe.
/// Recording stops once the hits would pass `budget_bytes`; a set not recorded is traced again.
class GatherHits {
public:
    /// Which rays: the gather's indirect rays (after a front seen from behind became its back side)
    /// or the probe rays that decide which points gather (fronts alone).
    enum class Kind : uint32_t { Indirect = 0, Probe = 1 };
    /// How a folded set is read (bits): with the wedge tables, with the gradients, with the bubbles.
    static constexpr uint32_t kWithWedges = 1, kWithGradients = 2, kWithBubbles = 4;

    /// A ray set: its origin and normal (bits), seed, grid, kind and how it is read.
    struct Key {
        std::array<uint32_t, 8> words{};
        bool operator==(const Key& other) const { return words == other.words; }
    };
    static Key key(const Vec3& origin, const Vec3& normal, uint32_t seed, int grid, Kind kind, uint32_t read = 0);

    explicit GatherHits(std::size_t budget_bytes = 0) : budget_bytes_(budget_bytes) {}
    GatherHits(const GatherHits&) = delete;
    GatherHits& operator=(const GatherHits&) = delete;

    /// The recorded hits of `key`, or null. The vector stays valid while this object lives.
    const std::vector<hr::Visibility::Hit>* find(const Key& key) const;
    /// Keeps `hits` as the hits of `key`, unless that would pass the budget (then `full` turns true).
    void record(const Key& key, std::vector<hr::Visibility::Hit>&& hits);

    /// The folded reads of an indirect ray set (point_reads.h), or null. Valid while this object lives.
    const detail::PointReads* find_reads(const Key& key) const;
    /// Keeps `reads` (moved from) as the reads of `key` and returns them as kept; null when that would
    /// pass the budget (then `full` turns true and `reads` is left as it was).
    const detail::PointReads* record_reads(const Key& key, detail::PointReads& reads);

    std::size_t bytes() const { return bytes_.load(std::memory_order_relaxed); }
    /// Whether some ray set was left unrecorded for the budget.
    bool full() const { return full_.load(std::memory_order_relaxed); }
    void set_budget(std::size_t budget_bytes) { budget_bytes_ = budget_bytes; }
    std::size_t budget() const { return budget_bytes_; }

private:
    struct KeyHash {
        std::size_t operator()(const Key& key) const;
    };
    using Map = std::unordered_map<Key, std::vector<hr::Visibility::Hit>, KeyHash>;
    static constexpr std::size_t kShards = 64;
    struct Shard {
        mutable std::mutex mutex;
        Map map;
        std::unordered_map<Key, detail::PointReads, KeyHash> reads;
    };
    Shard& shard(const Key& key) const;
    /// Counts `size` more bytes unless that would pass the budget (then false, and `full`).
    bool reserve(std::size_t size);

    mutable std::array<Shard, kShards> shards_;
    std::size_t budget_bytes_;
    std::atomic<std::size_t> bytes_{0};
    std::atomic<bool> full_{false};
};

/// One ray set of a gather: its hits read where `hits` holds them, else traced one by one and kept
/// by finish(), each with one flag its tracer computed from the ray's direction (kept in the sign of
/// its distance), so that a gather reading the hits needs no directions. Without `hits`, every ray
/// is traced.
class RecordedRays {
public:
    RecordedRays(GatherHits* hits, const Vec3& origin, const Vec3& normal, uint32_t seed, int grid,
                 GatherHits::Kind kind)
        : hits_(hits), key_(GatherHits::key(origin, normal, seed, grid, kind)) {
        if (hits_ != nullptr) known_ = hits_->find(key_);
    }

    /// Ray `i`'s hit and its flag (rays are asked for in order 0, 1, ...): recorded, or `trace()`,
    /// which returns both.
    template <typename Trace>
    hr::Visibility::Hit hit(int i, bool& flag, const Trace& trace) {
        if (known_ != nullptr) {
            hr::Visibility::Hit recorded = (*known_)[std::size_t(i)];
            flag = std::signbit(recorded.distance);
            recorded.distance = std::fabs(recorded.distance);
            return recorded;
        }
        const auto [traced, traced_flag] = trace();
        flag = traced_flag;
        if (hits_ != nullptr) {
            traced_.push_back(traced);
            traced_.back().distance = std::copysign(traced.distance, flag ? -1.0f : 1.0f);
        }
        return traced;
    }

    /// Keeps the hits traced (once every ray of the set was asked for).
    void finish() {
        if (hits_ != nullptr && known_ == nullptr) hits_->record(key_, std::move(traced_));
    }

    GatherHits* hits() const { return hits_; }
    const GatherHits::Key& key() const { return key_; }

private:
    GatherHits* hits_;
    GatherHits::Key key_;
    const std::vector<hr::Visibility::Hit>* known_ = nullptr;
    std::vector<hr::Visibility::Hit> traced_;
};

}  // namespace radiosity
