// Cell labels: small sorted sets of interned strings.
//
// Labels are compared and merged very often while planar maps are induced (every edge
// and face collects the labels of its source curves), so they are stored as sorted
// vectors of integer ids; the strings live once in a process-wide table.
#pragma once

#include <cstdint>
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
    Labels(std::initializer_list<std::string_view> names);
    static Labels from_names(const std::vector<std::string>& names);

    void add(LabelId id);
    void add(std::string_view name) { add(intern_label(name)); }
    void merge(const Labels& other);
    void remove(LabelId id);
    bool has(LabelId id) const;
    bool has(std::string_view name) const;
    bool empty() const { return ids_.empty(); }
    std::size_t size() const { return ids_.size(); }
    const std::vector<LabelId>& ids() const { return ids_; }
    std::vector<std::string> names() const;
    bool operator==(const Labels& o) const { return ids_ == o.ids_; }
    bool operator!=(const Labels& o) const { return ids_ != o.ids_; }

private:
    std::vector<LabelId> ids_;  // sorted, unique
};

}  // namespace tex
