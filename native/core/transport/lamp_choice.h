/// @file lamp_choice.h
/// @brief Many lamps at the cost of those that matter at a place: the lamps that give a large
/// share of its light are traced with all their rays, the next brightest with one ray each, and
/// beyond those the others stand for each other (internal; the lamps' light at points and on
/// elements).
#pragma once

#include "common/stratified.h"
#include "common/types.h"

#include <algorithm>
#include <cstddef>
#include <vector>

namespace radiosity::detail {

/// A lamp gives a large share of a place's light from this fraction of the unshadowed total on.
constexpr double kTracedShare = 1.0 / 32.0;
/// How many of the other lamps are traced one by one with a ray each, the brightest there first.
constexpr std::size_t kOneRayLamps = 64;
/// How many of the lamps beyond those are traced, drawn in proportion to their unshadowed light.
constexpr int kPicks = 4;

/// The sum over lamps of `traced(l, seed, fully)` (their light with shadows, whose mean without
/// shadows is `unshadowed[l]`; `fully`: with all the rays its soft shadow needs, else one): every lamp with at least
/// kTracedShare of the unshadowed total traced fully, the kOneRayLamps brightest of the others with one ray each, and
/// of the lamps beyond those kPicks drawn with probability in proportion to their unshadowed light (stratified over its
/// running sum, jittered from `seed`), each scaled by their total over kPicks times its own. So a place lit by up to
/// kOneRayLamps + 32 lamps traces each of them, and a corner in the shadow of the lamps that would light it most takes
/// the few that reach it exactly, not from a draw; with more lamps the draw is unbiased, and exact when nothing hides
/// them.
template <typename Traced>
Rgb sum_over_lamps(const std::vector<Rgb>& unshadowed, uint32_t seed, Traced traced) {
    double total = 0.0;
    for (const Rgb& u : unshadowed) total += max_channel(u);
    if (!(total > 0.0)) return Rgb(0.0);
    const auto light = [&](std::size_t l) { return max_channel(unshadowed[l]); };
    thread_local std::vector<std::size_t> others;
    others.clear();
    Rgb sum(0.0);
    for (std::size_t l = 0; l < unshadowed.size(); ++l) {
        const double w = light(l);
        if (w >= kTracedShare * total)
            sum += traced(l, mix_seed(seed, uint32_t(l)), true);
        else if (w > 0.0)
            others.push_back(l);
    }
    const std::size_t one_ray = std::min(others.size(), kOneRayLamps);
    if (others.size() > one_ray) {
        const auto brighter = [&](std::size_t a, std::size_t b) {
            return light(a) > light(b) || (light(a) == light(b) && a < b);
        };
        std::nth_element(others.begin(), others.begin() + one_ray, others.end(), brighter);
        std::sort(others.begin() + one_ray, others.end());
    }
    for (std::size_t i = 0; i < one_ray; ++i) sum += traced(others[i], mix_seed(seed, uint32_t(others[i])), false);
    double rest = 0.0;
    for (std::size_t i = one_ray; i < others.size(); ++i) rest += light(others[i]);
    if (!(rest > 0.0)) return sum;
    const double step = rest / kPicks;
    double next = step * next_jitter(seed), running = 0.0;
    for (std::size_t i = one_ray; i < others.size() && next < rest; ++i) {
        const std::size_t l = others[i];
        running += light(l);
        int picked = 0;
        for (; next < running; next += step) ++picked;
        if (picked > 0) sum += traced(l, mix_seed(seed, uint32_t(l)), false) * (picked * step / light(l));
    }
    return sum;
}

}  // namespace radiosity::detail
