/// @file bake_cache.cpp
/// @brief The cache between bakes of the same geometry (bake_cache.h).
#include "bake/bake_cache.h"

#include "bake/pipelines.h"

#include <utility>

namespace radiosity {

BakeCache::BakeCache() = default;
BakeCache::~BakeCache() = default;

void BakeCache::clear() {
    transport_.reset();
    bytes_ = 0;
    key_ = 0;
}

std::unique_ptr<detail::UniformTransport> BakeCache::take(uint64_t key, std::string& why_not) {
    if (transport_ == nullptr) {
        why_not = "no earlier bake was kept";
        return nullptr;
    }
    if (key != key_) {
        why_not = "the geometry, or a setting that chooses the elements, changed";
        clear();
        return nullptr;
    }
    bytes_ = 0;
    return std::move(transport_);
}

void BakeCache::keep(uint64_t key, std::unique_ptr<detail::UniformTransport> transport, std::size_t bytes) {
    key_ = key;
    transport_ = std::move(transport);
    bytes_ = bytes;
}

}  // namespace radiosity
