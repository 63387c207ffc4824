/// @file kept_first_shot.cpp
/// @brief The lamps' first shot kept lamp by lamp (kept_first_shot.h).
#include "bake/kept_first_shot.h"

#include <algorithm>

namespace radiosity::detail {

void KeptFirstShot::begin_bake(std::size_t elements) {
    if (values_.size() != elements) clear();
    values_.resize(elements);
    ++bake_;
}

Rgb KeptFirstShot::light(std::size_t e, uint64_t signature, const std::function<Rgb()>& trace) {
    std::vector<KeptDirectLight::Value>& kept = values_[e];
    for (KeptDirectLight::Value& value : kept)
        if (value.signature == signature) {
            value.bake = bake_;
            return value.light;
        }
    const Rgb made = trace();
    kept.push_back({signature, made, bake_});
    return made;
}

void KeptFirstShot::prune() {
    bytes_ = values_.capacity() * sizeof(values_[0]);
    for (std::vector<KeptDirectLight::Value>& kept : values_) {
        const auto unused = std::remove_if(kept.begin(), kept.end(),
                                           [&](const KeptDirectLight::Value& value) { return value.bake != bake_; });
        if (unused == kept.end()) continue;
        kept.erase(unused, kept.end());
        kept.shrink_to_fit();
    }
    for (const std::vector<KeptDirectLight::Value>& kept : values_)
        bytes_ += kept.capacity() * sizeof(KeptDirectLight::Value);
}

void KeptFirstShot::clear() {
    values_.clear();
    values_.shrink_to_fit();
    bytes_ = 0;
}

}  // namespace radiosity::detail
