/// @file kept_direct_light.h
/// @brief The final gather's direct light kept source by source at each point, so that a later
/// gather over the same geometry traces shadow rays only towards the sources that changed (a
/// re-bake after a lighting edit).
///
/// Light is linear in its sources, and at a point each source's share of the direct light is a
/// function of that source alone and of the geometry: a lamp's light with shadows (lamp_points.h:
/// which lamps are traced, and with how many rays, is chosen from their unshadowed light, cheap,
/// but what a traced lamp gives is the lamp's own), an emitting group's visible share (its rays
/// follow from its light and the total, both known before any ray), the World's light. Each is kept
/// under a signature of everything it is computed from besides the point and the geometry (the
/// lamp's parameters, its index and whether it got all its rays; the group's elements, their
/// radiance relative to its brightest, and its ray count; the World's map and sample counts): a
/// source whose signature is found is read, any other traced and kept. So a re-bake's direct light
/// is the same to the bit as a bake from scratch's, and costs the shadow rays of the moved, resized
/// or recoloured sources only (the
/// precomputed, per-source light transport of Sloan, Kautz and Snyder 2002 and of the per-light
/// layers of UberBake, Rodriguez et al. 2020, kept here as the values themselves).
///
/// A point is named by its place, normal and seed. Values not read or made by the latest bake
/// (a moved lamp's old place) are dropped when it ends (prune). Thread-safe.
#pragma once

#include "common/types.h"
#include "common/word_hash.h"
#include "transport/lights.h"
#include "transport/world.h"

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <unordered_map>
#include <utility>
#include <vector>

namespace radiosity {

class KeptDirectLight {
public:
    /// A point: its place and normal (bits) and seed.
    struct Key {
        std::array<uint32_t, 7> words{};
        bool operator==(const Key& other) const { return words == other.words; }
    };
    static Key key(const Vec3& x, const Vec3& normal, uint32_t seed);

    /// What one source gave at a point, under its signature; `bake`: the latest bake that used it.
    struct Value {
        uint64_t signature = 0;
        Rgb light{0.0};
        uint32_t bake = 0;
    };

    explicit KeptDirectLight(std::size_t budget_bytes = 0) : budget_bytes_(budget_bytes) {}
    KeptDirectLight(const KeptDirectLight&) = delete;
    KeptDirectLight& operator=(const KeptDirectLight&) = delete;

    /// The light in `values` under `signature`, marked as used by `bake`; else `compute()` (returning
    /// Rgb), kept so.
    template <typename Compute>
    static Rgb kept_or_made(std::vector<Value>& values, uint64_t signature, uint32_t bake, const Compute& compute) {
        for (Value& value : values)
            if (value.signature == signature) {
                value.bake = bake;
                return value.light;
            }
        const Rgb made = compute();
        values.push_back({signature, made, bake});
        return made;
    }
    /// Drops the values of `values` that `bake` did not use, and the room they took.
    static void drop_unused(std::vector<Value>& values, uint32_t bake);

    /// A new bake begins: what it does not use is dropped by prune().
    void begin_bake() { ++bake_; }
    /// Drops the values the latest bake did not use.
    void prune();
    void clear();
    void set_budget(std::size_t budget_bytes) { budget_bytes_ = budget_bytes; }
    std::size_t bytes() const { return bytes_.load(std::memory_order_relaxed); }
    /// Whether some point's values were left unkept for the budget (they are traced again).
    bool full() const { return full_.load(std::memory_order_relaxed); }

    /// One point's values, read at construction and kept by finish(): each source's light through
    /// light(). Not thread-safe itself: one per point and thread.
    class Point {
    public:
        Point(KeptDirectLight* kept, const Vec3& x, const Vec3& normal, uint32_t seed);
        /// The light kept under `signature`, or `compute()` (returning Rgb), then kept.
        template <typename Compute>
        Rgb light(uint64_t signature, const Compute& compute) {
            if (kept_ == nullptr) return compute();
            return kept_or_made(values_, signature, kept_->bake_, compute);
        }
        /// Keeps the values read and made.
        void finish();

    private:
        KeptDirectLight* kept_;
        Key key_;
        std::vector<Value> values_;
    };

private:
    struct KeyHash {
        std::size_t operator()(const Key& key) const;
    };
    using Map = std::unordered_map<Key, std::vector<Value>, KeyHash>;
    static constexpr std::size_t kShards = 64;
    struct Shard {
        std::mutex mutex;
        Map map;
    };
    Shard& shard(const Key& key);
    std::vector<Value> find(const Key& key);
    void store(const Key& key, std::vector<Value>&& values);
    static std::size_t point_bytes(std::size_t values);

    std::array<Shard, kShards> shards_;
    std::size_t budget_bytes_;
    std::atomic<std::size_t> bytes_{0};
    std::atomic<bool> full_{false};
    uint32_t bake_ = 1;
};

/// A signature of what a kept value was made from.
using Signature = detail::WordHash;

/// What the gather's direct light reads of the lamps and the World, as signatures.
struct SourceSignatures {
    std::vector<std::array<uint64_t, 2>> lamps;  ///< per lamp (the points, then the suns): [fully]
    uint64_t world = 0;
};
SourceSignatures source_signatures(const Lights& lights, const WorldLight& world);

}  // namespace radiosity
