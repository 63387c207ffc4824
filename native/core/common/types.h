/// @file types.h
/// @brief Basic types shared by the whole core: vectors, colours, progress reporting, errors.
#pragma once

#include <glm/vec3.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>

namespace radiosity {

using Vec3 = glm::vec3;  ///< positions and directions, metres (float: what Blender stores)
using Rgb = glm::dvec3;  ///< radiance or reflectance per RGB channel (double: solver precision)

/// The largest of the three channels.
inline double max_channel(const Rgb& c) { return std::max({c.r, c.g, c.b}); }

/// Unit normals whose dot product reaches this (within 0.8 degrees) are parallel: faces of one
/// plane, however round-off turned their float normals (a ray's own face, coincident faces).
constexpr float kParallelCosine = 0.9999f;

/// What a long-running phase reports. `radiance` is the current per-element solution when the
/// phase has one (solvers), null otherwise; it is only valid during the callback.
struct Progress {
    const char* phase = "";  ///< "form_factors", "solve", ...
    std::size_t done = 0;    ///< units finished (hemi-cubes, iterations, shots)
    std::size_t total = 0;   ///< units expected (an upper bound for iterative solvers)
    double residual = 0.0;   ///< current relative residual, 0 where not applicable
    const Rgb* radiance = nullptr;
    std::size_t element_count = 0;
};

/// Called now and then by long phases, from any thread but never concurrently.
/// Return false to cancel: the phase then throws `Cancelled`.
using ProgressFn = std::function<bool(const Progress&)>;

// The core's errors. The binding maps each to one Python class (native/python/module.cpp), so
// the add-on reports all of them the same way; anything else escaping the core is a bug.

/// Thrown when a progress callback asked to stop.
struct Cancelled : std::runtime_error {
    Cancelled() : std::runtime_error("cancelled") {}
};

/// Thrown for input the core cannot use; the message names the offending item.
struct InputError : std::invalid_argument {
    using std::invalid_argument::invalid_argument;
};

/// Thrown when a bake would exceed its element cap or memory budget; the message says which
/// setting to change.
struct BudgetError : InputError {
    using InputError::InputError;
};

/// Thrown when an iterative solver diverges; the message names the method and the likely cause.
struct NotConverged : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// Thrown when a file (OpenVDB) cannot be read or written; the message names the file.
struct FileError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// Thrown when a phase produced light that is not a finite number: a fault of the bake, never a
/// result. Names the phase ("links", "solve", "output") and the input polygon where it appeared
/// (-1 when no polygon is to blame), so that the caller can name the object.
struct NumericalError : std::runtime_error {
    NumericalError(std::string phase_name, int32_t input_polygon)
        : std::runtime_error(
              "non-finite light in phase '" + phase_name + "'" +
              (input_polygon >= 0 ? " at input polygon " + std::to_string(input_polygon) : std::string())),
          phase(std::move(phase_name)),
          polygon(input_polygon) {}
    std::string phase;
    int32_t polygon = -1;
};

}  // namespace radiosity
