#include "libtex/labels.hpp"

#include <algorithm>
#include <deque>
#include <mutex>
#include <shared_mutex>
#include <unordered_map>

namespace tex {
namespace {

struct LabelTable {
    std::shared_mutex mutex;
    std::unordered_map<std::string, LabelId> ids;
    std::deque<std::string> names;  // deque: references stay valid as it grows
};

LabelTable& table() {
    static LabelTable t;
    return t;
}

}  // namespace

LabelId intern_label(std::string_view name) {
    LabelTable& t = table();
    const std::string key(name);
    {
        std::shared_lock lock(t.mutex);
        auto it = t.ids.find(key);
        if (it != t.ids.end()) return it->second;
    }
    std::unique_lock lock(t.mutex);
    auto [it, inserted] = t.ids.emplace(key, LabelId(t.names.size()));
    if (inserted) t.names.push_back(key);
    return it->second;
}

const std::string& label_name(LabelId id) {
    LabelTable& t = table();
    std::shared_lock lock(t.mutex);
    return t.names.at(id);
}

bool find_label(std::string_view name, LabelId& out) {
    LabelTable& t = table();
    std::shared_lock lock(t.mutex);
    auto it = t.ids.find(std::string(name));
    if (it == t.ids.end()) return false;
    out = it->second;
    return true;
}

Labels::Labels(std::initializer_list<std::string_view> names) {
    for (auto n : names) add(n);
}

Labels Labels::from_names(const std::vector<std::string>& names) {
    Labels l;
    for (const auto& n : names) l.add(n);
    return l;
}

void Labels::add(LabelId id) {
    auto it = std::lower_bound(ids_.begin(), ids_.end(), id);
    if (it == ids_.end() || *it != id) ids_.insert(it, id);
}

void Labels::merge(const Labels& other) {
    if (other.ids_.empty()) return;
    if (ids_.empty()) {
        ids_ = other.ids_;
        return;
    }
    std::vector<LabelId> out;
    out.reserve(ids_.size() + other.ids_.size());
    std::set_union(ids_.begin(), ids_.end(), other.ids_.begin(), other.ids_.end(),
                   std::back_inserter(out));
    ids_.swap(out);
}

void Labels::remove(LabelId id) {
    auto it = std::lower_bound(ids_.begin(), ids_.end(), id);
    if (it != ids_.end() && *it == id) ids_.erase(it);
}

bool Labels::has(LabelId id) const { return std::binary_search(ids_.begin(), ids_.end(), id); }

bool Labels::has(std::string_view name) const {
    LabelId id;
    return find_label(name, id) && has(id);
}

std::vector<std::string> Labels::names() const {
    std::vector<std::string> out;
    out.reserve(ids_.size());
    for (LabelId id : ids_) out.push_back(label_name(id));
    std::sort(out.begin(), out.end());
    return out;
}

}  // namespace tex
