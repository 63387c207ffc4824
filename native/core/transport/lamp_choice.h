/// @file lamp_choice.h
/// @brief Many lamps at the cost of those that matter at a place: the lamps that give a large
/// share of its light are traced, the others stand for each other (internal; the lamps' light at
/// points and on elements).
#pragma once

#include "common/stratified.h"
#include "common/types.h"

#include <vector>

namespace radiosity::detail {

/// A lamp gives a large share of a place's light from this fraction of the unshadowed total on.
constexpr double kTracedShare = 1.0 / 32.0;
/// How many of the other lamps are traced, drawn in proportion to their unshadowed light.
constexpr int kPicks = 4;

/// The sum over lamps of `traced(l, seed, fully)` (their light with shadows, whose mean without
/// shadows is `unshadowed[l]`; `fully`: with all the rays its soft shadow needs, else one): every lamp with at least
/// kTracedShare of the unshadowed total traced, and of the rest kPicks drawn with probability in proportion to their
/// unshadowed light (stratified over its running sum, jittered from `seed`), each scaled by the rest's total over
/// kPicks times its own. Unbiased; exact when nothing hides the rest, whose shadows are what the picks sample.
template <typename Traced>
Rgb sum_over_lamps(const std::vector<Rgb>& unshadowed, uint32_t seed, Traced traced) {
    double total = 0.0;
    for (const Rgb& u : unshadowed) total += max_channel(u);
    if (!(total > 0.0)) return Rgb(0.0);
    Rgb sum(0.0);
    double rest = 0.0;
    for (std::size_t l = 0; l < unshadowed.size(); ++l) {
        const double w = max_channel(unshadowed[l]);
        if (w >= kTracedShare * total)
            sum += traced(l, mix_seed(seed, uint32_t(l)), true);
        else
            rest += w;
    }
    if (!(rest > 0.0)) return sum;
    const double step = rest / kPicks;
    double next = step * next_jitter(seed), running = 0.0;
    for (std::size_t l = 0; l < unshadowed.size() && next < rest; ++l) {
        const double w = max_channel(unshadowed[l]);
        if (!(w > 0.0) || w >= kTracedShare * total) continue;
        running += w;
        int picked = 0;
        for (; next < running; next += step) ++picked;
        if (picked > 0) sum += traced(l, mix_seed(seed, uint32_t(l)), false) * (picked * step / w);
    }
    return sum;
}

}  // namespace radiosity::detail
