/// @file max_tree.h
/// @brief Tournament tree: the index of the largest of n keys in O(1), a key update in O(log n).
/// Progressive refinement picks its next shooter with it (internal).
#pragma once

#include <cstdint>
#include <vector>

namespace radiosity::detail {

class MaxTree {
public:
    explicit MaxTree(const std::vector<double>& keys) : key_(keys) {
        while (leaves_ < key_.size()) leaves_ *= 2;
        node_.assign(2 * leaves_, -1);
        for (std::size_t i = 0; i < key_.size(); ++i) node_[leaves_ + i] = static_cast<int32_t>(i);
        for (std::size_t p = leaves_ - 1; p >= 1; --p) node_[p] = winner(node_[2 * p], node_[2 * p + 1]);
    }
    int32_t top() const { return node_[1]; }
    double key(int32_t i) const { return key_[i]; }
    void set(int32_t i, double key) {
        key_[i] = key;
        for (std::size_t p = (leaves_ + i) / 2; p >= 1; p /= 2) node_[p] = winner(node_[2 * p], node_[2 * p + 1]);
    }

private:
    int32_t winner(int32_t a, int32_t b) const {
        if (a < 0) return b;
        if (b < 0) return a;
        return key_[b] > key_[a] ? b : a;
    }
    std::vector<double> key_;
    std::size_t leaves_ = 1;
    std::vector<int32_t> node_;  // node_[1] is the root; leaves at leaves_ + i
};

}  // namespace radiosity::detail
