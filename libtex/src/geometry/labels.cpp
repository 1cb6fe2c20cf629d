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
    // Mappers ask for the same few names over and over (HasLabel(e, "ridge")): a small
    // per-thread cache of names already interned spares the shared lock. Ids never change.
    struct Hit {
        std::string name;
        LabelId id;
    };
    thread_local std::vector<Hit> cache;
    for (const Hit& h : cache)
        if (h.name == name) {
            out = h.id;
            return true;
        }
    LabelTable& t = table();
    {
        std::shared_lock lock(t.mutex);
        auto it = t.ids.find(std::string(name));
        if (it == t.ids.end()) return false;
        out = it->second;
    }
    if (cache.size() < 16) cache.push_back({std::string(name), out});
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

void Labels::assign(const LabelId* first, std::uint32_t n) {
    LabelId* big = nullptr;
    if (n > kInline) {
        big = new LabelId[n];
        std::copy(first, first + n, big);
    }
    release();
    if (big) {
        std::memcpy(small_, &big, sizeof big);
    } else {
        std::copy(first, first + n, small_);
    }
    n_ = n;
}

void Labels::add(LabelId id) {
    const LabelId* b = begin();
    const LabelId* at = std::lower_bound(b, end(), id);
    if (at != end() && *at == id) return;
    const std::size_t k = std::size_t(at - b);
    if (n_ < kInline) {  // stays inline
        std::copy_backward(small_ + k, small_ + n_, small_ + n_ + 1);
        small_[k] = id;
        ++n_;
        return;
    }
    LabelId* grown = new LabelId[n_ + 1];
    std::copy(b, b + k, grown);
    grown[k] = id;
    std::copy(b + k, b + n_, grown + k + 1);
    release();
    std::memcpy(small_, &grown, sizeof grown);
    ++n_;
}

void Labels::merge(const Labels& other) {
    if (other.n_ == 0) return;
    if (n_ == 0) {
        *this = other;
        return;
    }
    LabelId local[2 * kInline];
    std::vector<LabelId> heap;
    LabelId* out = local;
    if (n_ + other.n_ > 2 * kInline) {
        heap.resize(n_ + other.n_);
        out = heap.data();
    }
    LabelId* last = std::set_union(begin(), end(), other.begin(), other.end(), out);
    assign(out, std::uint32_t(last - out));
}

void Labels::remove(LabelId id) {
    const LabelId* at = std::lower_bound(begin(), end(), id);
    if (at == end() || *at != id) return;
    std::vector<LabelId> rest(begin(), end());
    rest.erase(rest.begin() + (at - begin()));
    assign(rest.data(), std::uint32_t(rest.size()));
}

bool Labels::has(LabelId id) const {
    for (const LabelId* p = begin(); p != end(); ++p)
        if (*p >= id) return *p == id;
    return false;
}

bool Labels::has(std::string_view name) const {
    if (n_ == 0) return false;
    LabelId id;
    return find_label(name, id) && has(id);
}

bool Labels::operator==(const Labels& o) const { return n_ == o.n_ && std::equal(begin(), end(), o.begin()); }

std::vector<std::string> Labels::names() const {
    std::vector<std::string> out;
    out.reserve(n_);
    for (LabelId id : *this) out.push_back(label_name(id));
    std::sort(out.begin(), out.end());
    return out;
}

}  // namespace tex
static_assert(sizeof(tex::Labels) == 16, "three label sets per curve and record: keep them small");
