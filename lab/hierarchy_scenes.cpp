#include "hierarchy_scenes.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <functional>

namespace radiosity::charts {
namespace {

/// An axis-aligned box, faces outward.
void add_box(test::SceneArrays& s, Vec3 lo, Vec3 hi, const Rgb& rho, int32_t material) {
    const Vec3 p[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                       {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
    const Rgb black(0.0);
    s.add_quad(p[0], p[3], p[2], p[1], rho, black, material);  // bottom
    s.add_quad(p[4], p[5], p[6], p[7], rho, black, material);  // top
    s.add_quad(p[0], p[1], p[5], p[4], rho, black, material);  // -y
    s.add_quad(p[2], p[3], p[7], p[6], rho, black, material);  // +y
    s.add_quad(p[1], p[2], p[6], p[5], rho, black, material);  // +x
    s.add_quad(p[3], p[0], p[4], p[7], rho, black, material);  // -x
}

/// The inside of the box [0, size], faces inward.
void add_room(test::SceneArrays& s, Vec3 size, const Rgb& rho) {
    const float x = size.x, y = size.y, z = size.z;
    const Rgb black(0.0);
    s.add_quad({0, 0, 0}, {x, 0, 0}, {x, y, 0}, {0, y, 0}, rho, black);  // floor
    s.add_quad({0, 0, z}, {0, y, z}, {x, y, z}, {x, 0, z}, rho, black);  // ceiling
    s.add_quad({0, 0, 0}, {0, y, 0}, {0, y, z}, {0, 0, z}, rho, black);
    s.add_quad({x, 0, 0}, {x, 0, z}, {x, y, z}, {x, y, 0}, rho, black);
    s.add_quad({0, y, 0}, {x, y, 0}, {x, y, z}, {0, y, z}, rho, black);
    s.add_quad({0, 0, 0}, {0, 0, z}, {x, 0, z}, {x, 0, 0}, rho, black);
}

/// A surface point and its outward normal at grid parameters (u, v) in [0, 1]^2.
using Surface = std::function<void(double u, double v, Vec3& point, Vec3& outward)>;

/// Triangulates `surface` on an nu x nv grid (shared vertices), each triangle facing outward;
/// degenerate triangles (at a sphere's poles) are left out. Returns the sum of edge lengths.
double add_surface(test::SceneArrays& s, const Surface& surface, int nu, int nv, const Rgb& rho, int32_t material,
                   std::size_t& edges) {
    const auto first = static_cast<int32_t>(s.positions.size() / 3);
    std::vector<Vec3> points, outward;
    for (int j = 0; j <= nv; ++j)
        for (int i = 0; i <= nu; ++i) {
            Vec3 p, n;
            surface(double(i) / nu, double(j) / nv, p, n);
            points.push_back(p);
            outward.push_back(n);
            s.positions.insert(s.positions.end(), {p.x, p.y, p.z});
        }
    double length = 0.0;
    auto add_triangle = [&](int a, int b, int c) {
        const Vec3 cross = glm::cross(points[b] - points[a], points[c] - points[a]);
        if (glm::length(cross) < 1e-12f) return;
        if (glm::dot(cross, outward[a] + outward[b] + outward[c]) < 0.0f) std::swap(b, c);
        s.corner_vertices.insert(s.corner_vertices.end(), {first + a, first + b, first + c});
        s.face_offsets.push_back(static_cast<int32_t>(s.corner_vertices.size()));
        for (int k = 0; k < 3; ++k) {
            s.reflectance.push_back(static_cast<float>(rho[k]));
            s.emission.push_back(0.0f);
        }
        s.material.push_back(material);
        length += glm::length(points[b] - points[a]) + glm::length(points[c] - points[b]) +
                  glm::length(points[a] - points[c]);
        edges += 3;
    };
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            const int a = j * (nu + 1) + i, b = a + 1, c = a + nu + 2, d = a + nu + 1;
            add_triangle(a, b, c);
            add_triangle(a, c, d);
        }
    return length;
}

}  // namespace

LitScene shadow_room() {
    LitScene scene;
    test::SceneArrays& s = scene.arrays;
    add_room(s, {4.0f, 3.0f, 2.5f}, Rgb(0.6));
    const Rgb wood(0.5, 0.35, 0.2);
    add_box(s, {1.5f, 1.1f, 0.71f}, {2.5f, 1.9f, 0.75f}, wood, 1);  // table top
    for (float x : {1.55f, 2.40f})
        for (float y : {1.15f, 1.80f}) add_box(s, {x, y, 0.0f}, {x + 0.05f, y + 0.05f, 0.71f}, wood, 1);
    PointLight lamp;
    lamp.position = Vec3(2.3f, 1.6f, 2.2f);
    lamp.intensity = Rgb(20.0);
    scene.lights.points.push_back(lamp);
    return scene;
}

LitScene object_room(std::size_t triangles) {
    LitScene scene;
    test::SceneArrays& s = scene.arrays;
    const float room = 10.0f, height = 3.0f;
    add_room(s, {room, room, height}, Rgb(0.6));
    const float lz = height - 0.001f, c = room / 2;
    s.add_quad({c - 0.5f, c - 0.5f, lz}, {c - 0.5f, c + 0.5f, lz}, {c + 0.5f, c + 0.5f, lz}, {c + 0.5f, c - 0.5f, lz},
               Rgb(0.0), Rgb(15.0), 2);
    PointLight lamp;
    lamp.position = Vec3(2.5f, 2.5f, 2.5f);
    lamp.intensity = Rgb(30.0);
    scene.lights.points.push_back(lamp);

    // Each object has about 4 n^2 triangles: 36 of them make `triangles`.
    const int grid = 6;
    const int n = std::max(2, int(std::lround(std::sqrt(double(triangles) / (4.0 * grid * grid)))));
    const int box_n = std::max(1, int(std::lround(n / std::sqrt(3.0))));
    const Rgb colours[3] = {Rgb(0.7, 0.7, 0.7), Rgb(0.65, 0.2, 0.15), Rgb(0.2, 0.45, 0.6)};
    double length = 0.0;
    std::size_t edges = 0;
    for (int gx = 0; gx < grid; ++gx)
        for (int gy = 0; gy < grid; ++gy) {
            const int k = gx * grid + gy;
            // 1 mm above the floor: resting objects would touch it along faces or circles.
            const Vec3 centre(1.0f + (room - 2.0f) * (gx + 0.5f) / grid, 1.0f + (room - 2.0f) * (gy + 0.5f) / grid,
                              0.001f);
            const Rgb rho = colours[k % 3];
            const int32_t material = 3 + k % 3;
            if (k % 3 == 0) {  // UV sphere, radius 0.45, on the floor
                const float r = 0.45f;
                const Vec3 o = centre + Vec3(0, 0, r);
                length += add_surface(
                    s,
                    [&](double u, double v, Vec3& p, Vec3& out) {
                        const double phi = 2 * M_PI * u, theta = M_PI * v;
                        out = Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
                        p = o + r * out;
                    },
                    2 * n, n, rho, material, edges);
            } else if (k % 3 == 1) {  // box 0.7 m, each face box_n x box_n quads
                const float h = 0.35f;
                const Vec3 o = centre + Vec3(0, 0, h);
                for (int axis = 0; axis < 3; ++axis)
                    for (float sign : {-1.0f, 1.0f}) {
                        length += add_surface(
                            s,
                            [&](double u, double v, Vec3& p, Vec3& out) {
                                out = Vec3(0.0f);
                                out[axis] = sign;
                                p = o + h * out;
                                p[(axis + 1) % 3] += float((2 * u - 1) * h);
                                p[(axis + 2) % 3] += float((2 * v - 1) * h);
                            },
                            box_n, box_n, rho, material, edges);
                    }
            } else {  // torus lying flat: ring radius 0.32, tube radius 0.13
                const float R = 0.32f, r = 0.13f;
                const Vec3 o = centre + Vec3(0, 0, r);
                length += add_surface(
                    s,
                    [&](double u, double v, Vec3& p, Vec3& out) {
                        const double phi = 2 * M_PI * u, psi = 2 * M_PI * v;
                        const Vec3 ring(std::cos(phi), std::sin(phi), 0.0);
                        out = float(std::cos(psi)) * ring + Vec3(0, 0, std::sin(psi));
                        p = o + R * ring + r * out;
                    },
                    2 * n, n, rho, material, edges);
            }
        }
    scene.triangle_edge = float(length / double(edges));
    return scene;
}

}  // namespace radiosity::charts
