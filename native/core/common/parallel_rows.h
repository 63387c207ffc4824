/// @file parallel_rows.h
/// @brief One parallel loop over matrix rows with progress and cancel, for the surface form
/// factors and the zonal exchange factors (internal).
#pragma once

#include "common/types.h"

#include <tbb/parallel_for.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <atomic>
#include <mutex>

namespace radiosity::detail {

/// Runs `row(i)` for i in [0, count) in parallel (TBB), reporting `phase` about every
/// 1% from one thread at a time. `row` returns false to stop the loop early (a budget exceeded).
/// Returns whether every row was done; throws Cancelled on the caller's thread when the callback
/// asked to stop (it may run on a worker thread, where throwing would not reach the caller).
template <typename Row>
bool parallel_rows(const char* phase, std::size_t count, std::size_t grain, std::size_t element_count,
                   const ProgressFn& progress, Row row) {
    std::atomic<std::size_t> done{0};
    std::atomic<bool> cancelled{false}, stopped{false};
    std::mutex report;
    const std::size_t step = std::max<std::size_t>(1, (count + 99) / 100);
    auto tell = [&](std::size_t finished) {
        if (!progress) return;
        std::lock_guard<std::mutex> lock(report);
        Progress p;
        p.phase = phase;
        p.done = finished;
        p.total = count;
        p.element_count = element_count;
        if (!progress(p)) cancelled = true;
    };
    tbb::task_group_context context;
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, count, grain),
        [&](const tbb::blocked_range<std::size_t>& range) {
            for (std::size_t i = range.begin(); i != range.end(); ++i) {
                if (cancelled || stopped) {
                    context.cancel_group_execution();
                    return;
                }
                if (!row(i)) stopped = true;
                const std::size_t finished = ++done;
                if (finished % step == 0 && finished != count) tell(finished);
            }
        },
        context);
    if (!cancelled && !stopped) tell(count);
    if (cancelled) throw Cancelled();
    return !stopped;
}

}  // namespace radiosity::detail
