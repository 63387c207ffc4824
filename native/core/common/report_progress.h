/// @file report_progress.h
/// @brief One progress report from a phase that may be cancelled (internal).
#pragma once

#include "common/types.h"

namespace radiosity::detail {

/// Calls `progress` (when set) with `phase`, `done` of `total`; throws Cancelled when it returns false.
inline void report_progress(const ProgressFn& progress, const char* phase, std::size_t done, std::size_t total) {
    if (!progress) return;
    Progress p;
    p.phase = phase;
    p.done = done;
    p.total = total;
    if (!progress(p)) throw Cancelled();
}

}  // namespace radiosity::detail
