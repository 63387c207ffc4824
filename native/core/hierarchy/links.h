/// @file links.h
/// @brief Links of hierarchical radiosity (internal): the factor and error estimate of a pair of
/// nodes, and the refinement that replaces a link by links between children (hierarchy.h).
#pragma once

#include "hierarchy/tree.h"
#include "visibility/ray_tracer.h"

#include <tbb/enumerable_thread_specific.h>

#include <atomic>
#include <deque>

namespace radiosity::hr {

/// A source's intensity towards `u` (unit, leaving the source): clusters and elements by their
/// emitter (hierarchy.h), point lamps by their profile; a sun's irradiance.
Rgb intensity(const Tree& tree, const Node& source, const Vec3& u);

class Refiner {
public:
    /// `max_bytes`: the nodes and links may take this many bytes; pairs stop splitting beyond (0: no cap).
    Refiner(Tree& tree, const Visibility& visibility, std::size_t max_bytes = 0)
        : tree_(tree), visibility_(visibility), max_bytes_(max_bytes) {}

    /// The first links: every pair of sibling subtrees and every lamp with the root, at the
    /// coarsest level (sources are dark before the first solve, so nothing asks for more).
    /// Measures each cluster's openness (openness()) first: 64 rays per cluster.
    void link_initial(const ProgressFn& progress);
    /// Replaces every link whose error now exceeds `threshold` (radiance) by links between
    /// children, as deep as the estimates ask. Returns how many links were refined.
    std::size_t refine(double threshold, const ProgressFn& progress);

    std::size_t rays() const { return rays_; }
    std::size_t links() const { return links_; }
    /// Bytes of nodes, links and vertices now (HierarchyStats::bytes).
    std::size_t bytes() const;
    /// Whether a pair stayed whole because the nodes and links reached `max_bytes`.
    bool memory_cap_reached() const { return memory_cap_reached_; }
    /// The share of cluster `c`'s surface (by area) from which light leaves its bounding sphere
    /// without meeting anything on the way: rays from random points of its patches, cos-weighted.
    /// A cluster is a link's end as a whole, as if every part of it saw what lies outside: it
    /// emits all its light outwards (also what its parts send each other, which its own links
    /// carry too) and every part reads what it receives (also the floor under a block standing
    /// on it, and faces pressed against each other). What is not open is the light such a link
    /// would make from nothing: a doubt of the link (estimate_point_source), which refinement
    /// removes by linking the cluster's parts where that light matters.
    float openness(const Node& c) const { return c.kind == Kind::Cluster ? openness_[c.cluster] : 1.0f; }

private:
    struct Estimate {
        Link link;
        bool useful = false;  ///< carries light now or may after refinement
        /// Most of the uncertainty comes from treating the source as a point (split the source),
        /// not from how the transfer varies over the receiver or is partly hidden (split it).
        bool source_side = false;
        int rays = 0;
    };
    using Output = std::deque<std::pair<int32_t, Link>>;
    /// A pair of nodes waiting to be linked; `split`: split it at least once.
    struct Pending {
        int32_t receiver = -1, source = -1;
        bool split = false;
    };

    /// A pair whose estimate says nothing (too near, or a lamp over a cluster): it splits
    /// whatever the threshold (the source first when `source_side`); marked by the largest
    /// uncertainty.
    static Estimate must_split(bool source_side = false);
    static bool is_must_split(const Link& link);
    Estimate estimate(int32_t receiver, int32_t source) const;
    Estimate estimate_elements(const Node& r, const Node& s) const;
    Estimate estimate_point_source(const Node& r, const Node& s) const;
    /// The link's estimated radiance error; `receiver_split`: the receiver has children.
    double error(const Node& receiver, const Link& link, bool receiver_split) const;
    double source_error(const Link& link) const;  ///< the part of error() splitting the source reduces
    /// The error a receiver's links may sum to: `threshold`, or more for a receiver smaller than
    /// an element of the minimum size, in proportion to its area.
    double receiver_threshold(const Node& receiver, double threshold) const;
    /// Links the pending pairs, splitting them depth first while their error is too large. Pairs
    /// still waiting after a bounded number of estimates go to the next level, and each level is
    /// one parallel loop with progress and cancel: no pair (the root's two halves of a large
    /// scene) holds the progress bar while it splits.
    void link_all(std::vector<Pending> pending, double threshold, const ProgressFn& progress);
    /// Moves the new links from the threads' outputs into their receivers' lists (phase "links":
    /// at 10^6 patches the first links take seconds to place).
    void place(tbb::enumerable_thread_specific<Output>& outputs, const ProgressFn& progress);
    /// `pair` and the pairs it splits into, depth first, for at most `kEstimatesPerTask`
    /// estimates; what is left goes into `next`.
    void link_depth_first(const Pending& pair, double threshold, Output& out, std::vector<Pending>& next,
                          std::size_t& rays);
    /// One pair: its link into `out`, or, while the error is too large (or once when `split`), the
    /// pairs of the larger end's children with the other end onto `stack`, first child on top.
    void link(const Pending& pair, double threshold, Output& out, std::vector<Pending>& stack, std::size_t& rays);
    /// Sample points of a cluster: centres of its patches, picked by power or by area.
    int cluster_samples(const Node& c, uint32_t seed, bool by_power, std::array<Vec3, 4>& points) const;

    /// Which nodes had children when the pass began. Decisions read this, not the live tree,
    /// which other threads split meanwhile: the same scene refines the same way every run.
    void take_split_snapshot();
    void measure_openness(const ProgressFn& progress);
    bool split_at_start(int32_t node) const;

    Tree& tree_;
    const Visibility& visibility_;
    /// Whether splitting may go on: false once bytes() reaches `max_bytes_` (and marks the cap).
    bool within_memory();

    std::vector<uint8_t> split_;
    std::vector<float> openness_;  ///< per cluster (Node::cluster)
    std::size_t rays_ = 0;
    std::size_t max_bytes_ = 0;
    std::atomic<std::size_t> links_{0};  ///< links made, plus pairs waiting (each may become one)
    std::atomic<bool> memory_cap_reached_{false};
};

}  // namespace radiosity::hr
