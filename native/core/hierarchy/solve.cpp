/// @file solve.cpp
/// @brief Gather and push-pull sweeps of hierarchical radiosity (hierarchy/solve.h).
#include "hierarchy/solve.h"

#include "hierarchy/links.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace radiosity::hr {
namespace {

/// Light binned by direction, read by a surface with normal n: exact for light from within the
/// octant around n, an approximation (never negative) otherwise.
Rgb read_cube(const AmbientCube& cube, const Vec3& n) {
    Rgb g(0.0);
    for (int a = 0; a < 3; ++a) g += cube[2 * a + (n[a] >= 0.0f ? 0 : 1)] * double(std::abs(n[a]));
    return g;
}

void deposit(AmbientCube& cube, const Vec3& direction, const Rgb& value) {
    for (int a = 0; a < 3; ++a) cube[2 * a + (direction[a] >= 0.0f ? 0 : 1)] += value * double(std::abs(direction[a]));
}

/// Clusters with at least this many patches push and pull their two halves in parallel.
constexpr int32_t kPatchesPerTask = 2048;

/// Every node sums its links (`lamps_only`: only those from lamps) into gathered or cube.
void gather(Tree& tree, bool lamps_only = false) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tree.nodes.size(), 512), [&](const auto& range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
            Node& r = tree.nodes[i];
            r.gathered = Rgb(0.0);
            if (r.kind == Kind::Cluster) tree.cubes[r.cluster] = AmbientCube{};
            for (std::size_t k = 0; k < r.links.size(); ++k) {
                if (k + kPrefetchLinks < r.links.size())
                    prefetch_source(tree.nodes[r.links[k + kPrefetchLinks].source]);
                const Link& l = r.links[k];
                const Node& s = tree.nodes[l.source];
                if (lamps_only && !s.is_lamp()) continue;
                if (r.is_element() && s.is_element()) {
                    r.gathered += double(l.factor) * s.radiance;
                    continue;
                }
                const Vec3 direction = towards_source(r, s);
                const Rgb value = double(l.factor) * intensity(tree, s, -direction);
                if (r.is_element())
                    r.gathered += value;
                else
                    deposit(tree.cubes[r.cluster], direction, value);
            }
        }
    });
}

struct Totals {
    double change = 0.0, total = 0.0;
};

void set_range(const Tree& tree, Node& n) {
    if (n.is_leaf()) {
        n.radiance_low = n.radiance_high = static_cast<float>(max_channel(n.radiance));
        return;
    }
    n.radiance_low = std::numeric_limits<float>::max();
    n.radiance_high = 0.0f;
    for (int k = 0; k < n.child_count; ++k) {
        const Node& c = tree.nodes[child(n, k)];
        n.radiance_low = std::min(n.radiance_low, c.radiance_low);
        n.radiance_high = std::max(n.radiance_high, c.radiance_high);
    }
}

/// Passes a cluster's light on to its children: the cluster's own cube plus the one from above
/// goes on to child clusters; child elements read it at their normals.
/// `visit(child, cube, gathered)` for each child.
template <typename Visit>
void pass_down(const Tree& tree, const Node& cluster, const AmbientCube& cube_above, Visit visit) {
    AmbientCube cube = tree.cubes[cluster.cluster];
    for (int b = 0; b < 6; ++b) cube[b] += cube_above[b];
    for (int k = 0; k < cluster.child_count; ++k) {
        const int32_t c = child(cluster, k);
        const Node& below = tree.nodes[c];
        if (below.is_element())
            visit(c, AmbientCube{}, read_cube(cube, below.normal));
        else
            visit(c, cube, Rgb(0.0));
    }
}

/// Pushes what the ancestors gathered (`cube` for clusters, `gathered` for elements) down to the
/// leaves, updates them when `update`, and pulls radiance and emitters back up.
void push_pull(Tree& tree, int32_t id, const AmbientCube& cube_above, const Rgb& gathered_above, bool update,
               Totals& totals) {
    Node& n = tree.nodes[id];
    if (n.kind == Kind::Cluster) {
        struct Below {
            int32_t node = -1;
            AmbientCube cube{};
            Rgb gathered{0.0};
            Totals totals;
        };
        std::array<Below, 2> below;
        int count = 0;
        pass_down(tree, n, cube_above, [&](int32_t c, const AmbientCube& cube, const Rgb& gathered) {
            below[count++] = {c, cube, gathered, {}};
        });
        auto visit = [&](Below& b) { push_pull(tree, b.node, b.cube, b.gathered, update, b.totals); };
        // Large clusters' halves in parallel: a sweep visits every node, and there are millions.
        if (count == 2 && n.patch_end - n.patch_begin >= kPatchesPerTask)
            tbb::parallel_invoke([&] { visit(below[0]); }, [&] { visit(below[1]); });
        else
            for (int k = 0; k < count; ++k) visit(below[k]);
        Emitter& emitter = tree.emitters[n.cluster];
        emitter = Emitter{};
        std::array<double, 2> power{};
        for (int k = 0; k < count; ++k) {
            const Emitter c = tree.emitter(tree.nodes[below[k].node]);
            emitter.power += c.power;
            for (int ch = 0; ch < 3; ++ch) emitter.moment[ch] += c.moment[ch];
            power[k] = max_channel(c.power);
            totals.change += below[k].totals.change;
            totals.total += below[k].totals.total;
        }
        for (int ch = 0; ch < 3; ++ch) emitter.moment_length[ch] = glm::length(emitter.moment[ch]);
        ClusterSplit& split = tree.splits[n.cluster];
        split.power_share =
            power[0] + power[1] > 0.0 ? static_cast<float>(power[0] / (power[0] + power[1])) : split.area_share;
        return;
    }
    const Rgb gathered = gathered_above + n.gathered;
    if (n.is_leaf()) {
        if (update) {
            const Rgb next = n.emission + n.reflectance * gathered;
            const Rgb change = glm::abs(next - n.radiance);
            totals.change += double(n.area) * (change.r + change.g + change.b);
            totals.total += double(n.area) * (next.r + next.g + next.b);
            n.radiance = next;
        }
    } else {
        Rgb sum(0.0);
        double area = 0.0;
        for (int k = 0; k < n.child_count; ++k) {
            const int32_t c = child(n, k);
            push_pull(tree, c, AmbientCube{}, gathered, update, totals);
            sum += double(tree.nodes[c].area) * tree.nodes[c].radiance;
            area += tree.nodes[c].area;
        }
        // Children without area (they carry no power) have no area mean: their plain mean.
        if (area > 0.0) {
            n.radiance = sum / area;
        } else {
            n.radiance = Rgb(0.0);
            for (int k = 0; k < n.child_count; ++k)
                n.radiance += tree.nodes[child(n, k)].radiance / double(n.child_count);
        }
    }
    set_range(tree, n);
}

/// Pushes gathered light down without touching radiance: `total[id]` of every element.
void push(const Tree& tree, int32_t id, const AmbientCube& cube_above, const Rgb& gathered_above,
          std::vector<Rgb>& total) {
    const Node& n = tree.nodes[id];
    if (n.kind == Kind::Cluster) {
        pass_down(tree, n, cube_above, [&](int32_t c, const AmbientCube& cube, const Rgb& gathered) {
            push(tree, c, cube, gathered, total);
        });
        return;
    }
    total[id] = gathered_above + n.gathered;
    for (int k = 0; k < n.child_count; ++k) push(tree, child(n, k), AmbientCube{}, total[id], total);
}

}  // namespace

std::vector<Rgb> lamp_light(Tree& tree) {
    std::vector<Rgb> total(tree.nodes.size(), Rgb(0.0));
    if (tree.root < 0 || tree.lamp_nodes.empty()) return total;
    gather(tree, true);
    push(tree, tree.root, AmbientCube{}, Rgb(0.0), total);
    return total;
}

void pull(Tree& tree) {
    Totals unused;
    if (tree.root >= 0) push_pull(tree, tree.root, AmbientCube{}, Rgb(0.0), false, unused);
}

SweepResult solve_links(Tree& tree, double tolerance, int max_sweeps, std::vector<double>& history,
                        const ProgressFn& progress) {
    SweepResult result;
    if (tree.root < 0) {
        result.converged = true;
        return result;
    }
    while (result.sweeps < max_sweeps) {
        gather(tree);
        Totals totals;
        push_pull(tree, tree.root, AmbientCube{}, Rgb(0.0), true, totals);
        ++result.sweeps;
        if (!std::isfinite(totals.change) || !std::isfinite(totals.total)) {
            result.finite = false;
            result.converged = false;
            result.residual = std::numeric_limits<double>::quiet_NaN();
            history.push_back(result.residual);
            for (std::size_t i = 0; i < tree.nodes.size() && result.bad_node < 0; ++i) {
                const Node& n = tree.nodes[i];
                const Rgb& L = n.radiance;
                if (n.is_element() && n.is_leaf() && !(std::isfinite(L.r) && std::isfinite(L.g) && std::isfinite(L.b)))
                    result.bad_node = static_cast<int32_t>(i);
            }
            break;
        }
        result.residual = totals.total > 0.0 ? totals.change / totals.total : 0.0;
        history.push_back(result.residual);
        result.converged = result.residual <= tolerance;
        if (progress) {
            Progress p;
            p.phase = "solve";
            p.done = static_cast<std::size_t>(result.sweeps);
            p.total = static_cast<std::size_t>(max_sweeps);
            p.residual = result.residual;
            if (!progress(p)) throw Cancelled();
        }
        if (result.converged) break;
    }
    return result;
}

double reference_radiance(const Tree& tree) {
    double power = 0.0, area = 0.0, brightest = 0.0;
    for (std::size_t i = 0; i < tree.nodes.size(); ++i) {
        const Node& n = tree.nodes[i];
        if (!n.is_element()) continue;
        const double reflected = max_channel(glm::max(n.radiance - n.emission, Rgb(0.0)));
        if (i < tree.patch_count) {
            power += double(n.area) * reflected;
            area += n.area;
        }
        if (n.is_leaf()) brightest = std::max(brightest, reflected);
    }
    const double mean = area > 0.0 ? power / area : 0.0;
    return std::max(mean, kBrightestShare * brightest);
}

}  // namespace radiosity::hr
