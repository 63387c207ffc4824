/// @file bind_world.cpp
/// @brief The world's light from a numpy map to the core's WorldLight, with errors that say what is wrong.
#include "arrays.h"
#include "bindings.h"

namespace radiosity::python {

WorldLight parse_world(const py::object& map, int samples, int point_samples) {
    WorldLight world;
    world.samples = samples;
    world.point_samples = point_samples;
    if (map.is_none()) return world;
    const Array<float> pixels = map.cast<Array<float>>();
    if (pixels.ndim() != 3 || pixels.shape(2) != 3 || pixels.shape(0) < 1 || pixels.shape(1) < 1)
        throw InputError("world must be an equirectangular map of shape (height, width, 3), bottom row first");
    world.height = static_cast<int>(pixels.shape(0));
    world.width = static_cast<int>(pixels.shape(1));
    const float* p = pixels.data();
    world.radiance.resize(std::size_t(world.width) * std::size_t(world.height));
    for (std::size_t i = 0; i < world.radiance.size(); ++i)
        world.radiance[i] = Rgb(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
    world.check();
    return world;
}

}  // namespace radiosity::python
