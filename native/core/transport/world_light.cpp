/// @file world_light.cpp
/// @brief The world's light: the map, its sampler, and its irradiance on elements and points
/// (world.h, world_light.h).
#include "transport/world_light.h"

#include "common/parallel_rows.h"
#include "common/stratified.h"
#include "visibility/shadow_ray.h"

#include <tbb/parallel_for.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

namespace radiosity {
namespace {

/// The pixel a unit direction falls in (Cycles' direction_to_equirectangular).
std::size_t pixel_of(const WorldLight& world, const glm::dvec3& d) {
    double u = 0.5 - std::atan2(d.y, d.x) / (2.0 * M_PI);
    u -= std::floor(u);
    const double v = 1.0 - std::acos(std::clamp(d.z, -1.0, 1.0)) / M_PI;
    const int i = std::clamp(int(u * world.width), 0, world.width - 1);
    const int j = std::clamp(int(v * world.height), 0, world.height - 1);
    return std::size_t(j) * std::size_t(world.width) + std::size_t(i);
}

/// Solid angle of a pixel in row j: 2 pi / width times the band of cos(theta) the row spans.
double pixel_solid_angle(const WorldLight& world, int j) {
    const double cos_low = std::cos(M_PI * (1.0 - double(j) / world.height));
    const double cos_high = std::cos(M_PI * (1.0 - double(j + 1) / world.height));
    return 2.0 * M_PI / world.width * (cos_high - cos_low);
}

/// Points per edge of an element's grid for a cosine grid of `cos_grid`: each point takes about
/// 4 x 4 directions of each strategy.
int points_grid(int cos_grid) { return std::max(1, cos_grid / 4); }

}  // namespace

WorldLight WorldLight::uniform(const Rgb& radiance, int samples) {
    WorldLight world;
    world.width = world.height = 1;
    world.radiance = {radiance};
    world.samples = samples;
    return world;
}

bool WorldLight::empty() const {
    if (width <= 0 || height <= 0) return true;
    return std::none_of(radiance.begin(), radiance.end(), [](const Rgb& c) { return c.r > 0 || c.g > 0 || c.b > 0; });
}

Rgb WorldLight::radiance_from(const Vec3& direction) const {
    if (width <= 0 || height <= 0) return Rgb(0.0);
    return radiance[pixel_of(*this, glm::normalize(glm::dvec3(direction)))];
}

void WorldLight::check() const {
    if (width < 0 || height < 0 || radiance.size() != std::size_t(width) * std::size_t(height))
        throw InputError("world: the map's size (" + std::to_string(width) + " x " + std::to_string(height) +
                         ") does not match its " + std::to_string(radiance.size()) + " pixels");
    for (const Rgb& c : radiance)
        if (!std::isfinite(c.r) || !std::isfinite(c.g) || !std::isfinite(c.b) || c.r < 0 || c.g < 0 || c.b < 0)
            throw InputError("world: the map's radiance must be finite and >= 0");
    if (samples < 1 || point_samples < 1) throw InputError("world: samples and point_samples must be >= 1");
}

namespace detail {

WorldSampler::WorldSampler(const WorldLight& world) : world_(world), empty_(world.empty()) {
    if (empty_) return;
    const bool uniform = std::all_of(world.radiance.begin(), world.radiance.end(),
                                     [&](const Rgb& c) { return c == world.radiance.front(); });
    // Square grids: all for the cosine on a uniform map, half each otherwise.
    auto grid = [&](int samples) {
        return std::max(1, int(std::ceil(std::sqrt(std::max(1, samples) / (uniform ? 1.0 : 2.0)) - 1e-9)));
    };
    cos_grid_ = grid(world.samples);
    if (uniform) {
        point_cos_rays_ = std::max(1, world.point_samples);
        return;
    }
    map_grid_ = cos_grid_;
    point_map_grid_ = grid(world.point_samples);
    point_cos_rays_ = std::max(1, world.point_samples - point_map_grid_ * point_map_grid_);
    const std::size_t W = std::size_t(world.width), H = std::size_t(world.height);
    pixel_pdf_.assign(W * H, 0.0);
    pixel_cdf_.assign(W * H, 0.0);
    row_cdf_.assign(H, 0.0);
    double total = 0.0;
    for (std::size_t j = 0; j < H; ++j) {
        const double omega = pixel_solid_angle(world, int(j));
        double row = 0.0;
        for (std::size_t i = 0; i < W; ++i) {
            const Rgb& c = world.radiance[j * W + i];
            pixel_pdf_[j * W + i] = (c.r + c.g + c.b) * omega;
            row += pixel_pdf_[j * W + i];
            pixel_cdf_[j * W + i] = row;
        }
        for (std::size_t i = 0; i < W; ++i) pixel_cdf_[j * W + i] = row > 0.0 ? pixel_cdf_[j * W + i] / row : 1.0;
        total += row;
        row_cdf_[j] = total;
    }
    for (double& c : row_cdf_) c /= total;
    for (double& p : pixel_pdf_) p /= total;
    row_cdf_.back() = 1.0;
}

glm::dvec3 WorldSampler::map_direction(double a, double b) const {
    const int W = world_.width, H = world_.height;
    // The row, then the pixel in it; what is left of each number places the point in the pixel.
    const std::size_t j = std::min(
        std::size_t(H - 1), std::size_t(std::upper_bound(row_cdf_.begin(), row_cdf_.end(), a) - row_cdf_.begin()));
    const double row_low = j > 0 ? row_cdf_[j - 1] : 0.0;
    const double within_row = std::clamp((a - row_low) / std::max(row_cdf_[j] - row_low, 1e-300), 0.0, 1.0);
    const auto row_begin = pixel_cdf_.begin() + std::ptrdiff_t(j * std::size_t(W));
    const std::size_t i =
        std::min(std::size_t(W - 1), std::size_t(std::upper_bound(row_begin, row_begin + W, b) - row_begin));
    const double pixel_low = i > 0 ? row_begin[std::ptrdiff_t(i) - 1] : 0.0;
    const double within_pixel =
        std::clamp((b - pixel_low) / std::max(row_begin[std::ptrdiff_t(i)] - pixel_low, 1e-300), 0.0, 1.0);
    const double u = (double(i) + within_pixel) / W, v = (double(j) + within_row) / H;
    const double phi = M_PI - 2.0 * M_PI * u, theta = M_PI * (1.0 - v);
    return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

double WorldSampler::map_pdf(const glm::dvec3& direction) const {
    if (map_grid_ == 0) return 0.0;
    const double sin_theta = std::sqrt(std::max(0.0, 1.0 - direction.z * direction.z));
    if (!(sin_theta > 0.0)) return 0.0;
    // Uniform in (u, v) over the pixel: dw = 2 pi^2 sin(theta) du dv.
    return pixel_pdf_[pixel_of(world_, direction)] * double(world_.width) * double(world_.height) /
           (2.0 * M_PI * M_PI * sin_theta);
}

Rgb WorldSampler::irradiance(const hr::Visibility& visibility, const Vec3& origin, const Vec3& normal,
                             const glm::dvec2* cos_uv, int cos_count, const glm::dvec2* map_uv, int map_count) const {
    Rgb sum(0.0);
    if (empty_) return sum;
    if (map_grid_ == 0) map_count = 0;
    glm::dvec3 t, b;
    const glm::dvec3 n(normal);
    tangent_frame(n, t, b);
    for (int k = 0; k < cos_count; ++k) {
        const glm::dvec3 w = cosine_direction(n, t, b, cos_uv[k].x, cos_uv[k].y);
        add(visibility, origin, w, glm::dot(n, w), double(cos_count), map_count, sum);
    }
    for (int k = 0; k < map_count; ++k) {
        const glm::dvec3 w = map_direction(map_uv[k].x, map_uv[k].y);
        add(visibility, origin, w, glm::dot(n, w), double(cos_count), map_count, sum);
    }
    return sum;
}

void WorldSampler::add(const hr::Visibility& visibility, const Vec3& origin, const glm::dvec3& w, double cosine,
                       double cos_density, int map_count, Rgb& sum) const {
    if (!(cosine > 0.0)) return;
    const double density = cos_density * cosine / M_PI + double(map_count) * map_pdf(w);
    if (!(density > 0.0) || !visibility.escapes(origin, Vec3(w))) return;
    sum += world_.radiance[pixel_of(world_, w)] * (cosine / density);
}

std::vector<glm::dvec2> padded_samples(int points, int grid, uint32_t& seed) {
    const int side = int(std::lround(std::sqrt(double(points))));
    const int fine = grid * side;
    std::vector<glm::dvec2> uv(std::size_t(points * grid * grid));
    std::vector<int> sub(static_cast<std::size_t>(points));
    for (int cell = 0; cell < grid * grid; ++cell) {
        for (int k = 0; k < points; ++k) sub[std::size_t(k)] = k;
        for (int k = points - 1; k > 0; --k)  // Fisher-Yates
            std::swap(sub[std::size_t(k)], sub[std::size_t(std::min(k, int(next_jitter(seed) * float(k + 1))))]);
        for (int k = 0; k < points; ++k) {
            const int x = (cell % grid) * side + sub[std::size_t(k)] % side;
            const int y = (cell / grid) * side + sub[std::size_t(k)] / side;
            const double u = (double(x) + next_jitter(seed)) / fine, v = (double(y) + next_jitter(seed)) / fine;
            uv[std::size_t(k * grid * grid + cell)] = {u, v};
        }
    }
    return uv;
}

std::vector<glm::dvec2> multi_jittered_samples(int grid, uint32_t& seed) {
    const std::size_t n = std::size_t(grid);
    auto shuffled = [&]() {
        std::vector<int> order(n);
        for (std::size_t k = 0; k < n; ++k) order[k] = int(k);
        for (std::size_t k = n; k > 1; --k)  // Fisher-Yates
            std::swap(order[k - 1], order[std::min(k - 1, std::size_t(next_jitter(seed) * float(k)))]);
        return order;
    };
    // The canonical arrangement: cell (i, j) holds sub-column j and sub-row i; shuffling the
    // sub-columns within each column and the sub-rows within each row keeps both projections
    // stratified.
    std::vector<std::vector<int>> sub_column(n), sub_row(n);
    for (std::size_t k = 0; k < n; ++k) {
        sub_column[k] = shuffled();
        sub_row[k] = shuffled();
    }
    std::vector<glm::dvec2> uv(n * n);
    const double fine = double(grid) * grid;
    for (std::size_t j = 0; j < n; ++j)
        for (std::size_t i = 0; i < n; ++i) {
            const double u = (double(i * n + std::size_t(sub_column[i][j])) + next_jitter(seed)) / fine;
            const double v = (double(j * n + std::size_t(sub_row[j][i])) + next_jitter(seed)) / fine;
            uv[j * n + i] = {u, v};
        }
    return uv;
}

std::vector<Rgb> world_light_at_corners(const Elements& mesh, const WorldLight& world, const hr::Visibility& visibility,
                                        float scene_size, const ProgressFn& progress) {
    std::vector<Rgb> light(4 * mesh.size(), Rgb(0.0));
    const WorldSampler sampler(world);
    if (sampler.empty()) return light;
    // One evaluation per (vertex, polygon): the first slot that has it computes, the others copy.
    std::vector<std::pair<std::pair<int32_t, int32_t>, std::size_t>> keys;
    for (std::size_t e = 0; e < mesh.size(); ++e)
        if (std::max({mesh.reflectance[e].r, mesh.reflectance[e].g, mesh.reflectance[e].b}) > 0.0)
            for (int k = 0; k < (mesh.is_triangle(e) ? 3 : 4); ++k)
                keys.push_back({{mesh.corners[e][k], mesh.polygon[e]}, 4 * e + std::size_t(k)});
    std::sort(keys.begin(), keys.end());
    std::vector<std::size_t> first;
    for (std::size_t i = 0; i < keys.size(); ++i)
        if (i == 0 || keys[i].first != keys[i - 1].first) first.push_back(i);
    const float lift = 1e-5f * scene_size;
    parallel_rows("output", first.size(), 64, 0, progress, [&](std::size_t g) {
        const std::size_t slot = keys[first[g]].second, e = slot / 4;
        const Vec3 corner = mesh.vertices[std::size_t(keys[first[g]].first.first)];
        const Vec3 x = corner + 1e-4f * (mesh.centre[e] - corner);
        const Vec3 n = mesh.normal[e];
        const uint32_t seed = mix_seed(uint32_t(keys[first[g]].first.first), 0x3011DU);
        const Rgb E = sampler.irradiance(visibility, x + lift * n, n, seed);
        const std::size_t end = g + 1 < first.size() ? first[g + 1] : keys.size();
        for (std::size_t i = first[g]; i < end; ++i) {
            const std::size_t s = keys[i].second;
            light[s] = mesh.reflectance[s / 4] * E / M_PI;
        }
        return true;
    });
    return light;
}

}  // namespace detail

std::vector<Rgb> world_irradiance(const Elements& elements, const WorldLight& world, const ProgressFn& progress) {
    world.check();
    std::vector<Rgb> irradiance(elements.size(), Rgb(0.0));
    const detail::WorldSampler sampler(world);
    if (sampler.empty() || elements.size() == 0) return irradiance;
    const float scene_size = scene_diagonal(elements.vertices);
    const hr::Visibility visibility(elements.vertices, detail::blocking_corners(elements), scene_size);
    const float lift = 1e-5f * scene_size;
    detail::parallel_rows("world", elements.size(), 8, 0, progress, [&](std::size_t e) {
        if (!(std::max({elements.reflectance[e].r, elements.reflectance[e].g, elements.reflectance[e].b}) > 0.0))
            return true;
        const int count = elements.is_triangle(e) ? 3 : 4;
        std::array<Vec3, 4> c;
        for (int k = 0; k < count; ++k) c[k] = elements.vertices[elements.corners[e][k]];
        const Vec3 n = elements.normal[e];
        // The mean over a grid of stratified points of the element, each with its share of the
        // rays: stratified directions at each point (the sky's edge seen from one point is found
        // far more closely than by rays scattered over points and directions at once), padded
        // across the points so that together they stratify the directions as finely as all the
        // element's rays can.
        const uint32_t seed = detail::mix_seed(uint32_t(e), 0x3011DU);
        uint32_t direction_seed = detail::mix_seed(seed, 0xD1EC7U);
        const int grid = points_grid(sampler.cos_grid()), point_count = grid * grid;
        std::vector<Vec3> points(static_cast<std::size_t>(point_count));
        detail::stratified_points(c.data(), count, grid, seed, points.data());
        const int cos_grid = (sampler.cos_grid() + grid - 1) / grid, map_grid = (sampler.map_grid() + grid - 1) / grid;
        const std::vector<glm::dvec2> cos_uv = detail::padded_samples(point_count, cos_grid, direction_seed);
        const std::vector<glm::dvec2> map_uv = detail::padded_samples(point_count, map_grid, direction_seed);
        const int cos_count = cos_grid * cos_grid, map_count = map_grid * map_grid;
        Rgb sum(0.0);
        for (int k = 0; k < point_count; ++k)
            sum += sampler.irradiance(visibility, points[std::size_t(k)] + lift * n, n,
                                      &cos_uv[std::size_t(k * cos_count)], cos_count, map_uv.data() + k * map_count,
                                      map_count);
        irradiance[e] = sum / double(point_count);
        return true;
    });
    return irradiance;
}

std::vector<Rgb> world_irradiance_at(const Elements& surfaces, const WorldLight& world, const std::vector<Vec3>& points,
                                     const std::vector<Vec3>& normals) {
    world.check();
    if (points.size() != normals.size()) throw InputError("world_irradiance_at: one normal per point");
    std::vector<Rgb> irradiance(points.size(), Rgb(0.0));
    const detail::WorldSampler sampler(world);
    if (sampler.empty()) return irradiance;
    const float scene_size = scene_diagonal(surfaces.vertices);
    const hr::Visibility visibility(surfaces.vertices, surfaces.corners, scene_size);
    tbb::parallel_for(std::size_t(0), points.size(), [&](std::size_t i) {
        const Vec3 n = glm::normalize(normals[i]);
        irradiance[i] = sampler.irradiance(visibility, points[i] + (1e-5f * scene_size) * n, n,
                                           detail::mix_seed(uint32_t(i), 0x3011DU));
    });
    return irradiance;
}

}  // namespace radiosity
