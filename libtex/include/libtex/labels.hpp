// Cell labels: small sorted sets of interned strings.
//
// Labels are compared and merged very often while planar maps are induced (every edge
// and face collects the labels of its source curves), so they are stored as sorted
// arrays of integer ids, a few of them inline; the strings live once in a process-wide
// table.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

namespace tex {

using LabelId = std::uint32_t;

// Interns a label string; thread-safe. Identical strings give identical ids.
LabelId intern_label(std::string_view name);
// The string of an interned id.
const std::string& label_name(LabelId id);
// Id of an already interned label, or false when the label was never seen
// (then no cell can carry it).
bool find_label(std::string_view name, LabelId& out);

class Labels {
public:
    Labels() = default;
    // Inline sets are copied and moved as their fixed bytes (a constant-size copy the
    // compiler does in registers: curves are moved by the million).
    Labels(const Labels& o) {
        if (o.n_ <= kInline) {
            std::memcpy(small_, o.small_, sizeof small_);
            n_ = o.n_;
        } else {
            assign(o.heap(), o.n_);
        }
    }
    Labels& operator=(const Labels& o) {
        if (this == &o) return *this;
        if (o.n_ <= kInline) {
            release();
            std::memcpy(small_, o.small_, sizeof small_);
            n_ = o.n_;
        } else {
            assign(o.heap(), o.n_);
        }
        return *this;
    }
    Labels(Labels&& o) noexcept : n_(o.n_) {
        std::memcpy(small_, o.small_, sizeof small_);
        o.n_ = 0;
    }
    Labels& operator=(Labels&& o) noexcept {
        if (this == &o) return *this;
        release();
        n_ = o.n_;
        std::memcpy(small_, o.small_, sizeof small_);
        o.n_ = 0;
        return *this;
    }
    ~Labels() { release(); }
    Labels(std::initializer_list<std::string_view> names);
    static Labels from_names(const std::vector<std::string>& names);

    void add(LabelId id);
    void add(std::string_view name) { add(intern_label(name)); }
    void merge(const Labels& other);
    void remove(LabelId id);
    bool has(LabelId id) const;
    bool has(std::string_view name) const;
    bool empty() const { return n_ == 0; }
    std::size_t size() const { return n_; }
    const LabelId* begin() const { return n_ <= kInline ? small_ : heap(); }
    const LabelId* end() const { return begin() + n_; }
    std::vector<LabelId> ids() const { return {begin(), end()}; }
    std::vector<std::string> names() const;
    bool operator==(const Labels& o) const;
    bool operator!=(const Labels& o) const { return !(*this == o); }

private:
    // Most cells carry at most a few labels: those live inline, so that copying a curve or
    // an edge record does not allocate. A larger set lives in an array of exactly n_ ids
    // on the heap, whose address is kept in the bytes of the inline ids (16 bytes in all:
    // curves and the planar maps' records carry three sets each and are moved often).
    static constexpr std::uint32_t kInline = 3;
    LabelId* heap() const {
        LabelId* p;
        std::memcpy(&p, small_, sizeof p);
        return p;
    }
    void release() {
        if (n_ > kInline) delete[] heap();
    }
    // Replaces the set with the n sorted unique ids at first (which may not lie in it).
    void assign(const LabelId* first, std::uint32_t n);
    alignas(LabelId*) LabelId small_[kInline] = {};
    std::uint32_t n_ = 0;
};

}  // namespace tex
