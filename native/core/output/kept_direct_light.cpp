/// @file kept_direct_light.cpp
/// @brief The final gather's direct light kept per source (kept_direct_light.h).
#include "output/kept_direct_light.h"

#include <algorithm>

namespace radiosity {
namespace {

/// Bytes a kept point holds besides its values: the key, the vector and the map's node.
constexpr std::size_t kPointOverhead = sizeof(KeptDirectLight::Key) + sizeof(std::vector<KeptDirectLight::Value>) + 32;

}  // namespace

namespace {

Signature point_signature(const PointLight& lamp) {
    Signature s;
    s.word(0x9017U).vec(lamp.position).rgb(lamp.intensity).vec(lamp.direction).number(lamp.cos_half_angle);
    s.number(lamp.smooth).word(lamp.cosine_profile).number(lamp.radius).word(uint32_t(lamp.shape));
    return s;
}

Signature sun_signature(const SunLight& sun) {
    Signature s;
    s.word(0x5011U).vec(sun.direction).rgb(sun.irradiance).number(sun.half_angle).word(sun.disk_directions);
    return s;
}

}  // namespace

SourceSignatures source_signatures(const Lights& lights, const WorldLight& world) {
    SourceSignatures out;
    const std::size_t points = lights.points.size();
    for (std::size_t l = 0; l < points + lights.suns.size(); ++l) {
        const Signature lamp = l < points ? point_signature(lights.points[l]) : sun_signature(lights.suns[l - points]);
        out.lamps.push_back(
            {Signature(lamp).word(uint32_t(l)).word(0).value(), Signature(lamp).word(uint32_t(l)).word(1).value()});
    }
    Signature w;
    w.word(0x3011DU).word(uint32_t(world.width)).word(uint32_t(world.height));
    w.word(uint32_t(world.samples)).word(uint32_t(world.point_samples));
    for (const Rgb& c : world.radiance) w.rgb(c);
    out.world = w.value();
    return out;
}

KeptDirectLight::Key KeptDirectLight::key(const Vec3& x, const Vec3& normal, uint32_t seed) {
    using detail::float_bits;
    return Key{{float_bits(x.x), float_bits(x.y), float_bits(x.z), float_bits(normal.x), float_bits(normal.y),
                float_bits(normal.z), seed}};
}

std::size_t KeptDirectLight::KeyHash::operator()(const Key& key) const { return detail::WordsHash()(key.words); }

KeptDirectLight::Shard& KeptDirectLight::shard(const Key& key) { return shards_[KeyHash()(key) % kShards]; }

std::size_t KeptDirectLight::point_bytes(std::size_t values) { return values * sizeof(Value) + kPointOverhead; }

std::vector<KeptDirectLight::Value> KeptDirectLight::find(const Key& key) {
    Shard& s = shard(key);
    const std::lock_guard<std::mutex> lock(s.mutex);
    const auto found = s.map.find(key);
    return found == s.map.end() ? std::vector<Value>{} : found->second;
}

void KeptDirectLight::store(const Key& key, std::vector<Value>&& values) {
    Shard& s = shard(key);
    const std::lock_guard<std::mutex> lock(s.mutex);
    std::vector<Value>& held = s.map[key];
    const std::size_t before = held.empty() ? 0 : point_bytes(held.capacity());
    values.shrink_to_fit();
    const std::size_t after = point_bytes(values.capacity());
    if (after > before && bytes() + (after - before) > budget_bytes_) {
        full_.store(true, std::memory_order_relaxed);
        if (held.empty()) s.map.erase(key);
        return;
    }
    held = std::move(values);
    bytes_.fetch_add(after, std::memory_order_relaxed);
    bytes_.fetch_sub(before, std::memory_order_relaxed);
}

void KeptDirectLight::drop_unused(std::vector<Value>& values, uint32_t bake) {
    values.erase(std::remove_if(values.begin(), values.end(), [&](const Value& v) { return v.bake != bake; }),
                 values.end());
    values.shrink_to_fit();
}

void KeptDirectLight::prune() {
    for (Shard& s : shards_) {
        const std::lock_guard<std::mutex> lock(s.mutex);
        for (auto it = s.map.begin(); it != s.map.end();) {
            std::vector<Value>& values = it->second;
            const std::size_t before = point_bytes(values.capacity());
            drop_unused(values, bake_);
            bytes_.fetch_sub(before, std::memory_order_relaxed);
            if (values.empty()) {
                it = s.map.erase(it);
            } else {
                bytes_.fetch_add(point_bytes(values.capacity()), std::memory_order_relaxed);
                ++it;
            }
        }
    }
}

void KeptDirectLight::clear() {
    for (Shard& s : shards_) {
        const std::lock_guard<std::mutex> lock(s.mutex);
        s.map.clear();
    }
    bytes_.store(0, std::memory_order_relaxed);
    full_.store(false, std::memory_order_relaxed);
}

KeptDirectLight::Point::Point(KeptDirectLight* kept, const Vec3& x, const Vec3& normal, uint32_t seed)
    : kept_(kept), key_(key(x, normal, seed)) {
    if (kept_ != nullptr) values_ = kept_->find(key_);
}

void KeptDirectLight::Point::finish() {
    if (kept_ != nullptr) kept_->store(key_, std::move(values_));
}

}  // namespace radiosity
