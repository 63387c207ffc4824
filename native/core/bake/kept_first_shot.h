/// @file kept_first_shot.h
/// @brief The lamps' first shot onto the solve's elements kept lamp by lamp between bakes of the
/// same elements, so that a re-bake after a lamp's edit traces shadow rays from that lamp alone.
///
/// An element's light from the point and spot lamps (transport/lights.h) is a sum over the lamps,
/// which ones traced and with how many rays chosen from their unshadowed light (cheap, computed
/// again); what a traced lamp gives is the lamp's own. It is kept per element under the lamp's
/// signature (output/kept_direct_light.h's source_signatures: its parameters, its index and whether
/// it got all its rays), read where the signature is found and traced and kept where it is not, so
/// a re-bake's first shot is the same to the bit as a bake from scratch's. What the latest bake did
/// not use (a moved lamp's old light) is dropped when it ends.
#pragma once

#include "output/kept_direct_light.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace radiosity::detail {

class KeptFirstShot {
public:
    /// A new bake over `elements` solve elements: what it does not use is dropped by prune().
    void begin_bake(std::size_t elements);
    /// The light kept for element `e` under `signature`, or `trace()`, then kept. Thread-safe for
    /// distinct elements (each is lit by one thread).
    Rgb light(std::size_t e, uint64_t signature, const std::function<Rgb()>& trace);
    /// Drops the values the latest bake did not use.
    void prune();
    void clear();
    std::size_t bytes() const { return bytes_; }

private:
    std::vector<std::vector<KeptDirectLight::Value>> values_;  ///< per element
    uint32_t bake_ = 0;
    std::size_t bytes_ = 0;
};

}  // namespace radiosity::detail
