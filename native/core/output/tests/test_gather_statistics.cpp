/// @file test_gather_statistics.cpp
/// @brief The final gather's own sampling variance (gather_statistics.h RaySpread) against the
/// spread of its stratified mean over many independent jitters.
#include "output/gather_statistics.h"

#include "common/stratified.h"

#include <gtest/gtest.h>

#include <cmath>

namespace radiosity::detail {
namespace {

/// Radiance seen in direction (u, v) of the gather's square: a bright window with a sharp edge over
/// a smoothly varying wall, as a room's hemisphere looks.
double seen(double u, double v) { return (u * u + v * v < 0.3 ? 1.0 : 0.0) + 0.2 + 0.1 * std::sin(6.0 * u + 2.0 * v); }

TEST(GatherStatistics, TwoHalvesGiveTheVarianceOfTheStratifiedMean) {
    const Elements none;
    const hr::Visibility::Hit hit;
    for (const int grid : {8, 16, 56}) {
        const int rays = grid * grid, seeds = 4000;
        double sum = 0.0, sum_squares = 0.0, estimated = 0.0;
        for (int s = 0; s < seeds; ++s) {
            uint32_t seed = mix_seed(uint32_t(s), 0x7E57U);
            PointStatistics statistics;
            RaySpread spread(none, &statistics, grid);
            double total = 0.0;
            for (int i = 0; i < rays; ++i) {
                const double u = (double(i % grid) + next_jitter(seed)) / grid;
                const double v = (double(i / grid) + next_jitter(seed)) / grid;
                total += seen(u, v);
                spread.add(i, Rgb(seen(u, v)), hit);
            }
            const double mean = total / rays;
            spread.finish(Rgb(mean), rays);
            sum += mean;
            sum_squares += mean * mean;
            estimated += statistics.variance.r;
        }
        const double variance = (sum_squares - sum * sum / seeds) / (seeds - 1);
        const double ratio = estimated / seeds / variance;
        std::printf("grid %d: variance of the mean over %d jitters %.3g, two halves' estimate %.3g (x%.2f)\n", grid,
                    seeds, variance, estimated / seeds, ratio);
        EXPECT_GT(ratio, 0.8) << grid;
        EXPECT_LT(ratio, 1.5) << grid;
    }
}

}  // namespace
}  // namespace radiosity::detail
