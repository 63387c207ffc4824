/// @file kept_first_shot.cpp
/// @brief The lamps' first shot kept lamp by lamp (kept_first_shot.h).
#include "bake/kept_first_shot.h"

namespace radiosity::detail {

void KeptFirstShot::begin_bake(std::size_t elements) {
    if (values_.size() != elements) clear();
    values_.resize(elements);
    ++bake_;
}

Rgb KeptFirstShot::light(std::size_t e, uint64_t signature, const std::function<Rgb()>& trace) {
    return KeptDirectLight::kept_or_made(values_[e], signature, bake_, trace);
}

void KeptFirstShot::prune() {
    bytes_ = values_.capacity() * sizeof(values_[0]);
    for (std::vector<KeptDirectLight::Value>& kept : values_) {
        KeptDirectLight::drop_unused(kept, bake_);
        bytes_ += kept.capacity() * sizeof(KeptDirectLight::Value);
    }
}

void KeptFirstShot::clear() {
    values_.clear();
    values_.shrink_to_fit();
    bytes_ = 0;
}

}  // namespace radiosity::detail
