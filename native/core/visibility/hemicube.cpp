/// @file hemicube.cpp
/// @brief Hemi-cube and full-cube item buffers: homogeneous edge-function rasteriser with a z-buffer.
///
/// Every element is rasterised in the local frame of the cube without dividing by depth:
/// an edge (P, Q) of an element (P, Q relative to the eye) bounds the plane through the eye
/// with normal P x Q, so a pixel direction d lies inside the element's cone iff
/// sign * d . (P_k x P_k+1) >= 0 for all edges, with sign the side of the element's plane the
/// eye is on. That cone is exactly the part of the element in front of the eye (t > 0), so the
/// coverage needs no clipping; the near plane (z = epsilon on each face) only clips the
/// element's outline to find its pixel bounding box. Edges shared by two elements give exactly
/// negated functions, and ties (a pixel centre exactly on an edge) go to one side only, so
/// shared edges neither leave gaps nor count twice. Depth: along d, 1/t = (n . d) / (n . P) is
/// linear in the face coordinates, so it is compared exactly per pixel centre.

#include "visibility/hemicube.h"
#include "visibility/cube_faces.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace radiosity {
namespace {

/// Outcode bits of a local vector p: for each linear form p[i] +- p[j] (i < j) one bit for
/// "> 0" and one for "< 0"; plus one bit for "w <= 0" (behind the hemi-cube's base plane).
constexpr int kForms = 6;
constexpr uint16_t kBelow = 1u << (2 * kForms);

/// Form index and sign bit of the expression c1 * p[a] + c2 * p[b] > 0 (c1, c2 = +-1).
uint16_t form_bit(int a, float c1, int b, float c2) {
    if (a > b) {
        std::swap(a, b);
        std::swap(c1, c2);
    }
    const int pair = a == 0 ? (b == 1 ? 0 : 1) : 2;     // (0,1), (0,2), (1,2)
    const int form = 2 * pair + (c1 * c2 > 0 ? 1 : 0);  // p[a] - p[b] or p[a] + p[b]
    return static_cast<uint16_t>(1u << (2 * form + (c1 > 0 ? 0 : 1)));
}

uint16_t outcode(const Vec3& p) {
    auto bits = [](float form, unsigned k) {
        return (form > 0.0f ? 1u << (2 * k) : 0u) | (form < 0.0f ? 2u << (2 * k) : 0u);
    };
    return static_cast<uint16_t>(bits(p.x - p.y, 0) | bits(p.x + p.y, 1) | bits(p.x - p.z, 2) | bits(p.x + p.z, 3) |
                                 bits(p.y - p.z, 4) | bits(p.y + p.z, 5) | (p.z <= 0.0f ? kBelow : 0u));
}

/// Bits meaning "outside face f": x > z, -x > z, y > z, -y > z in the face's coordinates.
uint16_t face_reject_mask(int f, bool half) {
    const cube::Face& face = cube::faces[f];
    const int x = face.axis[0], y = face.axis[1], z = face.axis[2];
    const float sx = face.sign[0], sy = face.sign[1], sz = face.sign[2];
    uint16_t mask =
        form_bit(x, sx, z, -sz) | form_bit(x, -sx, z, -sz) | form_bit(y, sy, z, -sz) | form_bit(y, -sy, z, -sz);
    return half ? static_cast<uint16_t>(mask | kBelow) : mask;
}

/// Orthonormal basis (u, v, n), right-handed (Duff et al. 2017).
std::array<Vec3, 3> basis_around(const Vec3& n) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z), b = n.x * n.y * a;
    return {Vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x), Vec3(b, sign + n.y * n.y * a, -n.y), n};
}

/// A linear function a x + b y + c of face coordinates, with its tie rule for value 0.
struct Edge {
    float a, b, c;
    bool owns_zero;
};

/// ceil(v), at least `lo`; with ceil/floor as library calls on baseline x86-64, this is cheaper.
int ceil_at_least(float v, int lo) {
    if (!(v > float(lo))) return lo;
    if (v > 1e8f) return 100000000;
    const int t = static_cast<int>(v);
    return t + (float(t) < v ? 1 : 0);
}

/// floor(v), at most `hi`; below zero gives -1 (an empty range).
int floor_at_most(float v, int hi) {
    if (!(v < float(hi))) return hi;
    if (v < 0.0f) return -1;
    return static_cast<int>(v);
}

Edge make_edge(const Vec3& coefficient) {
    return {coefficient.x, coefficient.y, coefficient.z,
            coefficient.x > 0.0f || (coefficient.x == 0.0f && coefficient.y > 0.0f)};
}

}  // namespace

struct Hemicube::Impl {
    std::shared_ptr<const CubeWeights> weights;
    cube::Layout layout;
    std::array<Vec3, 3> basis{};       ///< world directions of local u, v, w
    std::vector<float> inverse_depth;  ///< per cell, 0 = nothing drawn
    std::vector<int32_t> item;         ///< per cell
    std::vector<Vec3> local;           ///< per element vertex, relative to the eye, local frame
    std::vector<uint16_t> code;        ///< per element vertex outcode
    std::vector<double> sum;           ///< accumulate(): per element
    std::vector<int32_t> touched;
    float eye_scale = 0.0f;  ///< the largest coordinate of the eye: float positions' round-off scales with it

    void render(const Elements& elements, const Vec3& origin, const std::array<Vec3, 3>& frame, bool hemisphere,
                int32_t exclude);
    template <int K>
    void draw(const Elements& elements, int32_t e, uint8_t face_set, const Vec3& eye_local);
    template <int K, int F>
    void rasterise(const std::array<Vec3, K>& corner, const std::array<Vec3, K>& edge, const Vec3& depth, int32_t id);
};

void Hemicube::Impl::render(const Elements& elements, const Vec3& origin, const std::array<Vec3, 3>& frame,
                            bool hemisphere, int32_t exclude) {
    const int n = weights->resolution;
    layout = hemisphere ? cube::hemisphere_layout(n) : cube::sphere_layout(n);
    basis = frame;
    eye_scale = std::max({std::abs(origin.x), std::abs(origin.y), std::abs(origin.z)});
    inverse_depth.assign(layout.cells(), 0.0f);
    item.assign(layout.cells(), -1);
    if (sum.size() < elements.size()) sum.resize(elements.size(), 0.0);

    const std::size_t vertex_count = elements.vertices.size();
    local.resize(vertex_count);
    code.resize(vertex_count);
    for (std::size_t v = 0; v < vertex_count; ++v) {
        const float dx = elements.vertices[v].x - origin.x, dy = elements.vertices[v].y - origin.y,
                    dz = elements.vertices[v].z - origin.z;
        local[v] = Vec3(frame[0].x * dx + frame[0].y * dy + frame[0].z * dz,
                        frame[1].x * dx + frame[1].y * dy + frame[1].z * dz,
                        frame[2].x * dx + frame[2].y * dy + frame[2].z * dz);
        code[v] = outcode(local[v]);
    }
    std::array<uint16_t, 6> reject{};
    for (int f = 0; f < layout.face_count; ++f) reject[f] = face_reject_mask(f, hemisphere && f > 0);

    for (std::size_t i = 0; i < elements.size(); ++i) {
        const auto e = static_cast<int32_t>(i);
        if (e == exclude || !elements.blocks(i)) continue;  // lamps are seen by their direct light
        const auto& c = elements.corners[i];
        const bool triangle = c[3] < 0;
        const uint16_t common = code[c[0]] & code[c[1]] & code[c[2]] & (triangle ? 0xffff : code[c[3]]);
        if (hemisphere && (common & kBelow)) continue;
        uint8_t face_set = 0;
        for (int f = 0; f < layout.face_count; ++f)
            if (!(common & reject[f])) face_set |= static_cast<uint8_t>(1u << f);
        if (!face_set) continue;
        const Vec3 eye_local(glm::dot(frame[0], elements.centre[i] - origin),
                             glm::dot(frame[1], elements.centre[i] - origin),
                             glm::dot(frame[2], elements.centre[i] - origin));
        if (triangle)
            draw<3>(elements, e, face_set, eye_local);
        else
            draw<4>(elements, e, face_set, eye_local);
    }
}

template <int K>
void Hemicube::Impl::draw(const Elements& elements, int32_t e, uint8_t face_set, const Vec3& centre) {
    const Vec3& nw = elements.normal[e];
    const Vec3 normal(glm::dot(basis[0], nw), glm::dot(basis[1], nw), glm::dot(basis[2], nw));
    // Distance of the element's plane from the eye, negative when the eye sees its front. Within the
    // round-off of float positions the eye lies in the plane (a merged emitter's own back sides,
    // under the eye): edge-on, it covers no area.
    const float plane = glm::dot(normal, centre);
    if (!(std::abs(plane) > 1e-6f * (glm::length(centre) + eye_scale))) return;
    // An emitter's two sides lie on the same vertices and cover the same cells at the same depth:
    // seen from behind, an element that has a twin is left to it, which faces the eye.
    if (plane >= 0.0f && elements.has_twin(e)) return;
    const float side = plane < 0.0f ? -1.0f : 1.0f;
    std::array<Vec3, K> corner, edge;
    for (int k = 0; k < K; ++k) corner[k] = local[elements.corners[e][k]];
    for (int k = 0; k < K; ++k) edge[k] = side * glm::cross(corner[k], corner[(k + 1) % K]);
    const Vec3 depth = normal / plane;
    const int32_t id = plane < 0.0f ? e : -1;  // seen from behind: occludes, credited to nobody
    // One instance per face, so that the face's axis permutation is known at compile time.
    if (face_set & 1u) rasterise<K, 0>(corner, edge, depth, id);
    if (face_set & 2u) rasterise<K, 1>(corner, edge, depth, id);
    if (face_set & 4u) rasterise<K, 2>(corner, edge, depth, id);
    if (face_set & 8u) rasterise<K, 3>(corner, edge, depth, id);
    if (face_set & 16u) rasterise<K, 4>(corner, edge, depth, id);
    if (face_set & 32u) rasterise<K, 5>(corner, edge, depth, id);
}

template <int K, int F>
void Hemicube::Impl::rasterise(const std::array<Vec3, K>& corner, const std::array<Vec3, K>& edge_vector,
                               const Vec3& depth_vector, int32_t id) {
    constexpr cube::Face face = cube::faces[F];
    constexpr int f = F;
    // Pixel bounding box of the outline, clipped at the near plane z = epsilon where needed.
    std::array<Vec3, K> q;
    bool in_front = true;
    float extent = 0.0f;
    for (int k = 0; k < K; ++k) {
        q[k] = cube::to_face(face, corner[k]);
        in_front = in_front && q[k].z > 0.0f;
        extent = std::max(extent, std::abs(q[k].z) + std::abs(q[k].x) + std::abs(q[k].y));
    }
    float x_lo = INFINITY, x_hi = -INFINITY, y_lo = INFINITY, y_hi = -INFINITY;
    auto include = [&](const Vec3& p) {
        const float inv = 1.0f / p.z;
        x_lo = std::min(x_lo, p.x * inv);
        x_hi = std::max(x_hi, p.x * inv);
        y_lo = std::min(y_lo, p.y * inv);
        y_hi = std::max(y_hi, p.y * inv);
    };
    if (in_front) {
        for (int k = 0; k < K; ++k) include(q[k]);
    } else {
        const float near = 1e-6f * extent;
        for (int k = 0; k < K; ++k) {
            const Vec3 &a = q[k], &b = q[(k + 1) % K];
            if (a.z >= near) include(a);
            if ((a.z < near) != (b.z < near)) include(a + (b - a) * ((near - a.z) / (b.z - a.z)));
        }
        if (x_lo > x_hi) return;
    }
    const int n = layout.resolution, rows = layout.rows(f);
    const float h = layout.cell_size(), x0 = -1.0f + 0.5f * h, y0 = layout.y_min(f) + 0.5f * h;
    // A small margin so that rounding in the projection never drops a pixel the edges include.
    const float margin = 1e-3f;
    const float inv_h = 1.0f / h;
    const int col_lo = ceil_at_least((x_lo - x0) * inv_h - margin, 0);
    const int col_hi = floor_at_most((x_hi - x0) * inv_h + margin, n - 1);
    const int row_lo = ceil_at_least((y_lo - y0) * inv_h - margin, 0);
    const int row_hi = floor_at_most((y_hi - y0) * inv_h + margin, rows - 1);
    if (col_lo > col_hi || row_lo > row_hi) return;

    std::array<Edge, K> edge;
    for (int k = 0; k < K; ++k) edge[k] = make_edge(cube::to_face(face, edge_vector[k]));
    const Vec3 depth = cube::to_face(face, depth_vector);
    const std::size_t base = layout.offset(f);
    float* z_buffer = inverse_depth.data() + base;
    int32_t* items = item.data() + base;
    for (int r = row_lo; r <= row_hi; ++r) {
        const float y = y0 + r * h;
        std::array<float, K> row_value;
        for (int k = 0; k < K; ++k) row_value[k] = edge[k].b * y + edge[k].c;
        const float depth_row = depth.y * y + depth.z;
        float* z_row = z_buffer + std::size_t(r) * n;
        int32_t* item_row = items + std::size_t(r) * n;
        // Branch-free, so that the compiler can vectorise the row.
        for (int col = col_lo; col <= col_hi; ++col) {
            const float x = x0 + col * h;
            bool inside = true;
            for (int k = 0; k < K; ++k) {
                const float value = edge[k].a * x + row_value[k];
                inside &= (value > 0.0f) | ((value >= 0.0f) & edge[k].owns_zero);
            }
            const float z = depth.x * x + depth_row;
            const bool nearer = inside & (z > z_row[col]);
            z_row[col] = nearer ? z : z_row[col];
            item_row[col] = nearer ? id : item_row[col];
        }
    }
}

Hemicube::Hemicube(std::shared_ptr<const CubeWeights> weights) : impl_(std::make_unique<Impl>()) {
    if (!weights) throw InputError("Hemicube needs cube weights");
    impl_->weights = std::move(weights);
}
Hemicube::~Hemicube() = default;
Hemicube::Hemicube(Hemicube&&) noexcept = default;
Hemicube& Hemicube::operator=(Hemicube&&) noexcept = default;

void Hemicube::render_hemisphere(const Elements& elements, const Vec3& origin, const Vec3& normal, int32_t exclude) {
    impl_->render(elements, origin, basis_around(glm::normalize(normal)), true, exclude);
}

void Hemicube::render_hemisphere(const Elements& elements, const Vec3& origin, const Vec3& normal, int32_t exclude,
                                 float angle) {
    const std::array<Vec3, 3> frame = basis_around(glm::normalize(normal));
    const float c = std::cos(angle), s = std::sin(angle);
    impl_->render(elements, origin, {c * frame[0] + s * frame[1], c * frame[1] - s * frame[0], frame[2]}, true,
                  exclude);
}

void Hemicube::render_sphere(const Elements& elements, const Vec3& origin, int32_t exclude) {
    impl_->render(elements, origin, {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)}, false, exclude);
}

void Hemicube::accumulate(const std::vector<float>& cell_weight, SparseRow& row) {
    Impl& m = *impl_;
    if (cell_weight.size() != m.item.size()) throw InputError("accumulate: weights do not match the last render");
    m.touched.clear();
    // Neighbouring cells mostly see the same element: add runs locally before touching the sums.
    int32_t run_id = -1;
    double run_sum = 0.0;
    auto flush = [&] {
        if (run_id < 0) return;
        if (m.sum[run_id] == 0.0) m.touched.push_back(run_id);
        m.sum[run_id] += run_sum;
    };
    for (std::size_t cell = 0; cell < m.item.size(); ++cell) {
        const int32_t id = m.item[cell];
        if (id != run_id) {
            flush();
            run_id = id;
            run_sum = 0.0;
        }
        run_sum += cell_weight[cell];
    }
    flush();
    row.clear();
    row.col.reserve(m.touched.size());
    row.val.reserve(m.touched.size());
    auto emit = [&](int32_t id) {
        row.col.push_back(id);
        row.val.push_back(static_cast<float>(m.sum[id]));
        m.sum[id] = 0.0;
    };
    // Columns ascending: sort the touched ids, or scan all when most elements were seen.
    if (m.touched.size() * 16 > m.sum.size()) {
        for (std::size_t id = 0; id < m.sum.size(); ++id)
            if (m.sum[id] != 0.0) emit(static_cast<int32_t>(id));
    } else {
        std::sort(m.touched.begin(), m.touched.end());
        for (int32_t id : m.touched) emit(id);
    }
}

const std::vector<int32_t>& Hemicube::item_buffer() const { return impl_->item; }

Vec3 Hemicube::cell_direction(std::size_t cell) const {
    const Impl& m = *impl_;
    int f = m.layout.face_count - 1;
    while (f > 0 && cell < m.layout.offset(f)) --f;
    const std::size_t within = cell - m.layout.offset(f);
    const int row = static_cast<int>(within / m.layout.resolution),
              col = static_cast<int>(within % m.layout.resolution);
    const float h = m.layout.cell_size();
    const Vec3 local =
        cube::to_local(cube::faces[f], Vec3(-1.0f + (col + 0.5f) * h, m.layout.y_min(f) + (row + 0.5f) * h, 1.0f));
    return glm::normalize(m.basis[0] * local.x + m.basis[1] * local.y + m.basis[2] * local.z);
}

float Hemicube::cell_distance(std::size_t cell) const {
    const Impl& m = *impl_;
    const float z = m.inverse_depth[cell];
    if (!(z > 0.0f)) return INFINITY;
    int f = m.layout.face_count - 1;
    while (f > 0 && cell < m.layout.offset(f)) --f;
    const std::size_t within = cell - m.layout.offset(f);
    const int row = static_cast<int>(within / m.layout.resolution),
              col = static_cast<int>(within % m.layout.resolution);
    const float h = m.layout.cell_size();
    const float x = -1.0f + (col + 0.5f) * h, y = m.layout.y_min(f) + (row + 0.5f) * h;
    // The z-buffer holds 1/t for the point t (x, y, 1) in face coordinates.
    return std::sqrt(x * x + y * y + 1.0f) / z;
}

const CubeWeights& Hemicube::weights() const { return *impl_->weights; }

}  // namespace radiosity
